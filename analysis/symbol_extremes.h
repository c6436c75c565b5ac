// The numerical side of the interpolation symbol A(w) = sum_k M(k) cos(w.k) (docs/design.md §18):
// the smallest and largest |A| over all frequencies. The lattice lies in Z^n, so A has period
// 2 pi along each axis: a grid of kSymbolGrid^n points of [0, 2 pi)^n, then a pattern search from
// each of the smallest grid values (halving its step down to 1e-12). The generator decides the
// zeros exactly where it can (generator/interpolation_symbol.h); this finds minima anywhere.
#pragma once
#include <vector>

#include "analysis/error_kernel.h"

namespace boxgen::analysis {

inline constexpr int kSymbolGrid = 48;

struct SymbolExtremes {
  double min_abs = 0, max_abs = 0;
  Vec min_at{};  // a frequency where |A| is smallest, reduced to [-pi, pi)^n
};

// `samples`: M(k) at the lattice points (n = 2 or 3 coordinates each). Throws
// std::invalid_argument for no samples or a dimension other than 2 or 3.
SymbolExtremes symbol_extremes(const std::vector<LatticeTap>& samples);

}  // namespace boxgen::analysis
