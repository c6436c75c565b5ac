#include "analysis/spectrum.h"

#include <cmath>
#include <stdexcept>

namespace boxgen::analysis {

double sinc(double t) {
  // Below 1e-4 the series 1 - t^2/6 + t^4/120 is exact to double precision.
  if (std::abs(t) < 1e-4) return 1 - t * t / 6;
  return std::sin(t) / t;
}

long double sinc(long double t) {
  if (std::abs(t) < 1e-5L) return 1 - t * t / 6 + t * t * t * t / 120;
  return std::sin(t) / t;
}

BoxSplineSpectrum::BoxSplineSpectrum(const IntDirections& directions) {
  if (directions.empty()) throw std::invalid_argument("a box spline needs at least one direction");
  n_ = static_cast<int>(directions.front().size());
  if (n_ < 1 || n_ > 3) throw std::invalid_argument("directions must have 1 to 3 components");
  for (const auto& d : directions) {
    if (static_cast<int>(d.size()) != n_)
      throw std::invalid_argument("directions of different lengths");
    Vec v{0, 0, 0};
    for (int i = 0; i < n_; ++i) v[i] = static_cast<double>(d[i]);
    xi_.push_back(v);
  }
}

double BoxSplineSpectrum::operator()(const Vec& w) const {
  double p = 1;
  for (const Vec& x : xi_) p *= sinc(0.5 * (x[0] * w[0] + x[1] * w[1] + x[2] * w[2]));
  return p;
}

long double BoxSplineSpectrum::precise(const Vec& w) const {
  long double p = 1;
  for (const Vec& x : xi_) {
    const long double t =
        0.5L * (static_cast<long double>(x[0]) * w[0] + static_cast<long double>(x[1]) * w[1] +
                static_cast<long double>(x[2]) * w[2]);
    p *= sinc(t);
  }
  return p;
}

}  // namespace boxgen::analysis
