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

// sum_j t(j) e^{-i w.j}
std::complex<long double> fourier_sum(const std::vector<LatticeTap>& taps, const Vec& w) {
  long double re = 0, im = 0;
  for (const auto& t : taps) {
    const long double ph = phase(w, t.point);
    re += t.value * std::cos(ph);
    im -= t.value * std::sin(ph);
  }
  return {re, im};
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

ErrorKernel ErrorKernel::regularised_interpolation(BoxSplineSpectrum psi, double det_g,
                                                   std::vector<LatticeTap> autocorrelation,
                                                   std::vector<LatticeTap> lattice_samples,
                                                   std::vector<LatticeTap> regulariser, double mu) {
  if (!(mu >= 0) || (mu > 0 && regulariser.empty()))
    throw std::invalid_argument("the regularised error kernel needs D and mu >= 0");
  ErrorKernel e =
      interpolation(std::move(psi), det_g, std::move(autocorrelation), std::move(lattice_samples));
  e.regulariser_ = std::move(regulariser);
  e.mu_ = mu;
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

std::complex<long double> ErrorKernel::prefilter_response(const Vec& w) const {
  if (prefilter_.empty()) return 1;
  const std::complex<long double> s = fourier_sum(prefilter_, w);
  if (!inverse_) return s;
  long double d2 = 0;
  if (mu_ > 0) d2 = std::norm(fourier_sum(regulariser_, w));
  return std::conj(s) / (std::norm(s) + mu_ * d2);
}

long double ErrorKernel::operator()(const Vec& w) const {
  const long double p = psi_.precise(w);
  const long double a = aliasing_sum(w);
  const std::complex<long double> q = prefilter_response(w);
  const long double dr = q.real() - p / a;
  return 1 - p * p / a + a * (dr * dr + q.imag() * q.imag());
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
