#include "analysis/error_kernel.h"

#include <cmath>
#include <stdexcept>
#include <utility>

namespace boxgen::analysis {

namespace {

long double phase(const Vec& w, const std::vector<std::int64_t>& j) {
  long double t = 0;
  for (std::size_t i = 0; i < j.size(); ++i)
    t += static_cast<long double>(w[i]) * static_cast<long double>(j[i]);
  return t;
}

}  // namespace

ErrorKernel::ErrorKernel(BoxSplineSpectrum psi, double det_g,
                         std::vector<LatticeTap> autocorrelation, std::vector<LatticeTap> prefilter)
    : psi_(std::move(psi)),
      det_g_(det_g),
      autocorrelation_(std::move(autocorrelation)),
      prefilter_(std::move(prefilter)) {
  if (autocorrelation_.empty())
    throw std::invalid_argument("the error kernel needs the autocorrelation samples");
}

ErrorKernel ErrorKernel::interpolation(BoxSplineSpectrum psi, double det_g,
                                       std::vector<LatticeTap> autocorrelation,
                                       std::vector<LatticeTap> lattice_samples) {
  if (lattice_samples.empty())
    throw std::invalid_argument("the interpolation error kernel needs the lattice samples");
  ErrorKernel e(std::move(psi), det_g, std::move(autocorrelation), std::move(lattice_samples));
  e.inverse_ = true;
  return e;
}

long double ErrorKernel::aliasing_sum(const Vec& w) const {
  long double a = 0;
  for (const auto& t : autocorrelation_)
    a += static_cast<long double>(t.value) * std::cos(phase(w, t.point));
  return det_g_ * a;
}

long double ErrorKernel::minimum(const Vec& w) const {
  const long double p = psi_.precise(w);
  return 1 - p * p / aliasing_sum(w);
}

long double ErrorKernel::operator()(const Vec& w) const {
  const long double p = psi_.precise(w);
  const long double a = aliasing_sum(w);
  long double qr = 1, qi = 0;
  if (!prefilter_.empty()) {
    qr = 0;
    for (const auto& t : prefilter_) {
      const long double ph = phase(w, t.point);
      qr += t.value * std::cos(ph);
      qi -= t.value * std::sin(ph);
    }
    if (inverse_) {  // Q = 1 / S = conj(S) / |S|^2
      const long double s2 = qr * qr + qi * qi;
      qr /= s2;
      qi = -qi / s2;
    }
  }
  const long double dr = qr - p / a;
  return 1 - p * p / a + a * (dr * dr + qi * qi);
}

long double aliasing_sum_direct(const BoxSplineSpectrum& psi, const DualLattice& dual, const Vec& w,
                                double radius) {
  long double sum = 0;
  for (const Vec& k : dual.points_within(radius)) {
    const long double p = psi.precise({w[0] + k[0], w[1] + k[1], w[2] + k[2]});
    sum += p * p;
  }
  return sum;
}

}  // namespace boxgen::analysis
