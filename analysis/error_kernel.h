// The Blu-Unser frequency error kernel on a lattice (docs/design.md §10, the paper's Fig. 13):
//   E(w) = 1 - psi_hat^2 / A + A |Q(w) - psi_hat / A|^2,   E_min(w) = 1 - psi_hat^2 / A,
//   A(w) = sum_{k in 2 pi G^-T Z^n} psi_hat(w + k)^2 = |det G| sum_{j in L} a(j) e^{-i w.j},
//   Q(w) = sum_j q(j) e^{-i w.j},
// where a(j) are the generator's exact autocorrelation samples and q the prefilter taps (both
// converted to double by the caller). Interpolation (`interp`) has Q = 1 / S with the
// interpolation symbol S(w) = sum_k M(k) e^{-i w.k} of the lattice samples M(k) (§18), and its
// regularisation where S vanishes Q = conj(S) / (|S|^2 + mu |D|^2) (§17, with the runtime's D and
// mu: support/lattice_regulariser.h): given those samples instead of taps, the kernel uses that Q.
// Evaluated in long double: E falls like |w|^8 with an order-4 prefilter and is formed by
// cancellation near 0.
#pragma once
#include <complex>
#include <cstdint>
#include <vector>

#include "analysis/dual_lattice.h"
#include "analysis/spectrum.h"

namespace boxgen::analysis {

struct LatticeTap {
  std::vector<std::int64_t> point;  // a lattice point j (lattice coordinates = world coordinates)
  double value;
};

class ErrorKernel {
 public:
  // `prefilter` empty: no prefilter (Q = 1, the samples used as coefficients).
  ErrorKernel(BoxSplineSpectrum psi, double det_g, std::vector<LatticeTap> autocorrelation,
              std::vector<LatticeTap> prefilter);
  // Interpolation: Q = 1 / S, S from the lattice samples M(k) (which must be non-empty; the
  // caller checks that S has no zero).
  static ErrorKernel interpolation(BoxSplineSpectrum psi, double det_g,
                                   std::vector<LatticeTap> autocorrelation,
                                   std::vector<LatticeTap> lattice_samples);
  // Regularised interpolation: Q = conj(S) / (|S|^2 + mu |D|^2), D from the regulariser's taps
  // (mu = 0: interpolation).
  static ErrorKernel regularised_interpolation(BoxSplineSpectrum psi, double det_g,
                                               std::vector<LatticeTap> autocorrelation,
                                               std::vector<LatticeTap> lattice_samples,
                                               std::vector<LatticeTap> regulariser, double mu);
  std::complex<long double> prefilter_response(const Vec& w) const;  // Q(w)
  long double operator()(const Vec& w) const;                        // E(w)
  long double minimum(const Vec& w) const;                           // E_min(w)
  long double aliasing_sum(const Vec& w) const;  // A(w) from the autocorrelation samples

 private:
  BoxSplineSpectrum psi_;
  double det_g_;
  std::vector<LatticeTap> autocorrelation_, prefilter_;
  bool inverse_ = false;                 // prefilter_ holds M(k): Q = conj(S) / (|S|^2 + mu |D|^2)
  std::vector<LatticeTap> regulariser_;  // D
  double mu_ = 0;
};

// A(w) as the truncated sum over the dual lattice points with |k| <= radius (for tests: an
// independent route to A through the spectrum alone).
long double aliasing_sum_direct(const BoxSplineSpectrum& psi, const DualLattice& dual, const Vec& w,
                                double radius);

}  // namespace boxgen::analysis
