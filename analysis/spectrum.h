// The Fourier transform of the centred box spline psi = M^c (docs/design.md §10):
//   psi_hat(w) = prod_xi sinc(xi . w / 2),  sinc(t) = sin(t) / t,
// with w in the generator's lattice coordinates. psi_hat(0) = 1.
#pragma once
#include <array>
#include <cstdint>
#include <vector>

namespace boxgen::analysis {

// A point or vector of R^n, n = 2 or 3 (unused trailing entries are 0).
using Vec = std::array<double, 3>;
using IntDirections = std::vector<std::vector<std::int64_t>>;

class BoxSplineSpectrum {
 public:
  // `directions`: the columns xi of Xi (each of length n = 2 or 3).
  explicit BoxSplineSpectrum(const IntDirections& directions);
  int dimension() const { return n_; }
  double operator()(const Vec& w) const;    // psi_hat(w)
  long double precise(const Vec& w) const;  // the same in long double

 private:
  int n_;
  std::vector<Vec> xi_;
};

double sinc(double t);
long double sinc(long double t);

}  // namespace boxgen::analysis
