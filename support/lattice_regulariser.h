// The regularisation of interpolation where a filter's symbol vanishes (docs/design.md §17),
// written once: the runtime's `interpolate` solves with it, and `boxgen kernel --prefilter
// interp[:LAMBDA]` draws the error kernel of the same prefilter,
//
//     Q(w) = conj(A(w)) / (|A(w)|^2 + mu |D(w)|^2),   mu = lambda max|A|^2 / max|D|^2,
//
// A(w) = sum_k M(k) e^{-i w.k} the filter's symbol from its values M(k) at the lattice points and
// D the lattice Laplacian to the power ceil(k / 4) (k: the filter's approximation order).
// Taps are integer points of Z^3 with a weight (a 2-D lattice's points have z = 0); A and D are
// periodic with period 2 pi along each axis in those coordinates.
#pragma once
#include <array>
#include <cstdint>
#include <optional>
#include <string_view>
#include <utility>
#include <vector>

namespace boxgen::support {

using LatticeTaps = std::vector<std::pair<std::array<int, 3>, double>>;

// The smallest and largest |A(w)| over the grid w = 2 pi (i, j, k) / 64, which holds the zeros of
// the registry's filters.
struct SymbolBounds {
  double min = 0, max = 0;
};
SymbolBounds symbol_bounds(const LatticeTaps& values);

// Where min |A| < kVanishing max |A| the symbol is taken to vanish: interpolation then
// regularises with lambda = kDefaultLambda unless told otherwise (and refuses lambda = 0).
inline constexpr double kVanishing = 1e-6;
inline constexpr double kDefaultLambda = 1e-3;

// The discrete convolution of two tap tables (sorted by point, zero weights dropped).
LatticeTaps convolve(const LatticeTaps& p, const LatticeTaps& q);

// The regulariser D of the lattice G Z^n (`basis`: the n columns of G, n entries each, n <= 3) for
// a filter of approximation order `order`: the Laplacian sum_t (2 delta_0 - delta_t - delta_-t)
// over the shortest lattice vectors (and the next shells by length while those do not generate
// the lattice), to the power ceil(max(order, 4) / 4). It depends on the lattice, not on the
// basis that describes it.
LatticeTaps regulariser_taps(const std::vector<std::vector<std::int64_t>>& basis, int order);

struct Regularisation {
  SymbolBounds symbol;      // of the filter's values
  double lambda = 0;        // the weight relative to max |A|^2 (0: exact interpolation)
  double mu = 0;            // lambda max|A|^2 / max|D|^2
  LatticeTaps regulariser;  // D; empty where lambda = 0
};

// The regularisation of the filter `name` with these values: lambda as given, or, when none is,
// 0 where the symbol does not vanish and kDefaultLambda where it does. Throws
// std::invalid_argument (one line) for lambda not finite or outside [0, 1], or lambda = 0 where
// the symbol vanishes.
Regularisation regularisation(const LatticeTaps& values,
                              const std::vector<std::vector<std::int64_t>>& basis, int order,
                              std::optional<double> lambda, std::string_view name);

}  // namespace boxgen::support
