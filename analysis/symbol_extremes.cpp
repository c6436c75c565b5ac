#include "analysis/symbol_extremes.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>
#include <utility>

namespace boxgen::analysis {

namespace {

class Symbol {
 public:
  explicit Symbol(const std::vector<LatticeTap>& samples) {
    if (samples.empty()) throw std::invalid_argument("symbol: no lattice samples");
    n_ = static_cast<int>(samples.front().point.size());
    if (n_ != 2 && n_ != 3) throw std::invalid_argument("symbol: the dimension must be 2 or 3");
    for (const auto& s : samples) {
      Vec k{};
      for (int i = 0; i < n_; ++i)
        k[static_cast<std::size_t>(i)] = static_cast<double>(s.point[static_cast<std::size_t>(i)]);
      taps_.emplace_back(k, s.value);
    }
  }
  int dimension() const { return n_; }
  double abs(const Vec& w) const {
    double a = 0;
    for (const auto& [k, m] : taps_) a += m * std::cos(w[0] * k[0] + w[1] * k[1] + w[2] * k[2]);
    return std::fabs(a);
  }

 private:
  int n_ = 3;
  std::vector<std::pair<Vec, double>> taps_;
};

// Moves to a neighbour w +- step e_i while that lowers |A|, halving the step otherwise.
std::pair<double, Vec> refine(const Symbol& a, Vec w, double value, double step) {
  while (step > 1e-12) {
    bool moved = false;
    for (int i = 0; i < a.dimension() && !moved; ++i)
      for (const double sign : {1.0, -1.0}) {
        Vec p = w;
        p[static_cast<std::size_t>(i)] += sign * step;
        const double v = a.abs(p);
        if (v < value) {
          w = p;
          value = v;
          moved = true;
          break;
        }
      }
    if (!moved) step /= 2;
  }
  return {value, w};
}

}  // namespace

SymbolExtremes symbol_extremes(const std::vector<LatticeTap>& samples) {
  const Symbol a(samples);
  const int n = a.dimension();
  const double h = 2 * std::numbers::pi / kSymbolGrid;
  std::vector<std::pair<double, Vec>> grid;
  const int count = n == 3 ? kSymbolGrid * kSymbolGrid * kSymbolGrid : kSymbolGrid * kSymbolGrid;
  SymbolExtremes out;
  for (int index = 0; index < count; ++index) {
    Vec w{};
    int rest = index;
    for (int i = 0; i < n; ++i, rest /= kSymbolGrid)
      w[static_cast<std::size_t>(i)] = h * (rest % kSymbolGrid);
    const double v = a.abs(w);
    out.max_abs = std::max(out.max_abs, v);
    grid.emplace_back(v, w);
  }
  constexpr std::size_t kStarts = 16;
  const std::size_t starts = std::min(kStarts, grid.size());
  std::partial_sort(grid.begin(), grid.begin() + static_cast<std::ptrdiff_t>(starts), grid.end(),
                    [](const auto& x, const auto& y) { return x.first < y.first; });
  out.min_abs = grid.front().first;
  out.min_at = grid.front().second;
  for (std::size_t s = 0; s < starts; ++s) {
    const auto [v, w] = refine(a, grid[s].second, grid[s].first, h / 2);
    if (v < out.min_abs) {
      out.min_abs = v;
      out.min_at = w;
    }
  }
  for (int i = 0; i < n; ++i) {  // into [-pi, pi)
    double& x = out.min_at[static_cast<std::size_t>(i)];
    x -= 2 * std::numbers::pi * std::floor((x + std::numbers::pi) / (2 * std::numbers::pi));
  }
  return out;
}

}  // namespace boxgen::analysis
