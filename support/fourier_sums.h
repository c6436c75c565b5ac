// Fourier sums of small real kernels on a box of Z^3 at the frequencies 2 pi k / n, computed axis
// by axis: the runtime's interpolation solves a coset system at every frequency of its transform
// with them, and the regulariser's symbol bounds (support/lattice_regulariser.h), which boxgen's
// error kernel shares with the runtime, scan a grid with them.
#pragma once
#include <array>
#include <cmath>
#include <complex>
#include <cstddef>
#include <cstdint>
#include <numbers>
#include <vector>

#include "support/integer_math.h"

namespace boxgen::support {

using Complex = std::complex<double>;

// Complex products by the textbook formula, without the library's recovery of infinities (C99
// Annex G), which sums of finite values of order 1 do not need (runtime/interpolation.cpp gives
// its cost).
inline Complex product(const Complex& a, const Complex& b) {
  return {a.real() * b.real() - a.imag() * b.imag(), a.real() * b.imag() + a.imag() * b.real()};
}

// A real kernel on a box lo <= t <= hi of Z^3 (x fastest).
struct BoxKernel {
  std::array<int, 3> lo{}, width{};
  std::vector<double> values;
  double& at(int t0, int t1, int t2) {
    return values[static_cast<std::size_t>(t0 - lo[0]) +
                  static_cast<std::size_t>(width[0]) *
                      (static_cast<std::size_t>(t1 - lo[1]) +
                       static_cast<std::size_t>(width[1]) * static_cast<std::size_t>(t2 - lo[2]))];
  }
};

// e^{-2 pi i k t / n} for k in [0, count) and t in [lo, lo + width): table[k * width + t - lo].
inline std::vector<Complex> twiddles(int n, int count, int lo, int width) {
  std::vector<Complex> table(static_cast<std::size_t>(count) * static_cast<std::size_t>(width));
  for (int k = 0; k < count; ++k)
    for (int t = 0; t < width; ++t) {
      // The phase reduced mod n in integers first: exact for large k t.
      const std::int64_t r = static_cast<std::int64_t>(k) * (lo + t) -
                             n * floor_div(static_cast<std::int64_t>(k) * (lo + t), n);
      const double angle = -2 * std::numbers::pi * static_cast<double>(r) / n;
      table[static_cast<std::size_t>(k) * static_cast<std::size_t>(width) +
            static_cast<std::size_t>(t)] = {std::cos(angle), std::sin(angle)};
    }
  return table;
}

// The Fourier sums F_p(k) = sum_t kernel_p(t) e^{-2 pi i k.t / n} of several kernels on one box,
// frequency by frequency: fix k2 (partial sums over t2), then k1, then k0, so that each
// frequency costs width0 complex products per kernel.
class FourierSums {
 public:
  FourierSums(const std::vector<BoxKernel>& kernels, const std::array<int, 3>& n,
              const std::array<int, 3>& count)
      : kernels_(&kernels), box_(kernels.front()) {
    for (std::size_t a = 0; a < 3; ++a) e_[a] = twiddles(n[a], count[a], box_.lo[a], box_.width[a]);
    const auto w = box_.width;
    g2_.resize(kernels.size() * static_cast<std::size_t>(w[0] * w[1]));
    g1_.resize(kernels.size() * static_cast<std::size_t>(w[0]));
  }
  void set_k2(int k2) {
    const auto w = box_.width;
    const Complex* e = &e_[2][static_cast<std::size_t>(k2) * static_cast<std::size_t>(w[2])];
    for (std::size_t p = 0; p < kernels_->size(); ++p) {
      const std::vector<double>& v = (*kernels_)[p].values;
      for (int t01 = 0; t01 < w[0] * w[1]; ++t01) {
        Complex s = 0;
        for (int t2 = 0; t2 < w[2]; ++t2) s += v[index(t01 + w[0] * w[1] * t2)] * e[t2];
        g2_[p * static_cast<std::size_t>(w[0] * w[1]) + static_cast<std::size_t>(t01)] = s;
      }
    }
  }
  void set_k1(int k1) {
    const auto w = box_.width;
    const Complex* e = &e_[1][static_cast<std::size_t>(k1) * static_cast<std::size_t>(w[1])];
    for (std::size_t p = 0; p < kernels_->size(); ++p)
      for (int t0 = 0; t0 < w[0]; ++t0) {
        Complex s = 0;
        for (int t1 = 0; t1 < w[1]; ++t1)
          s += product(g2_[p * static_cast<std::size_t>(w[0] * w[1]) +
                           static_cast<std::size_t>(t0 + w[0] * t1)],
                       e[t1]);
        g1_[p * static_cast<std::size_t>(w[0]) + static_cast<std::size_t>(t0)] = s;
      }
  }
  Complex at_k0(std::size_t p, int k0) const {
    const auto w = box_.width;
    const Complex* e = &e_[0][static_cast<std::size_t>(k0) * static_cast<std::size_t>(w[0])];
    const Complex* g = &g1_[p * static_cast<std::size_t>(w[0])];
    Complex s = 0;
    for (int t0 = 0; t0 < w[0]; ++t0) s += product(g[t0], e[t0]);
    return s;
  }

 private:
  // An index computed in int (the kernels' boxes: small), as a std::size_t.
  static std::size_t index(int i) { return static_cast<std::size_t>(i); }

  const std::vector<BoxKernel>* kernels_;
  const BoxKernel& box_;
  std::array<std::vector<Complex>, 3> e_;
  std::vector<Complex> g2_, g1_;
};

}  // namespace boxgen::support
