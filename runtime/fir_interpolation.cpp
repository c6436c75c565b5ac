#include "runtime/fir_interpolation.h"

#include <fmt/format.h>

#include <cstdint>
#include <map>
#include <stdexcept>
#include <vector>

#include "runtime/interpolation.h"
#include "support/fir_prefilter.hpp"

namespace boxgen::runtime {

namespace {

// The lattice points of the shells 0..last (by squared norm), grown in a box until complete.
std::vector<support::FirPoint> shell_points(const CosetLattice& lattice, int last) {
  for (std::int64_t r = 2;; r *= 2) {
    std::map<std::int64_t, std::vector<support::FirPoint>> by_norm;
    for (std::int64_t z = -r; z <= r; ++z)
      for (std::int64_t y = -r; y <= r; ++y)
        for (std::int64_t x = -r; x <= r; ++x)
          if (lattice.contains(x, y, z)) by_norm[x * x + y * y + z * z].push_back({x, y, z});
    std::vector<support::FirPoint> out;
    int shells = 0;
    for (const auto& [norm, points] : by_norm) {
      if (norm > r * r) break;  // beyond the box's inscribed sphere shells may be incomplete
      out.insert(out.end(), points.begin(), points.end());
      if (++shells == last + 1) return out;
    }
  }
}

}  // namespace

PrefilterTaps fir_interpolation_taps(const SplineFilter& f, int last_shell) {
  if (last_shell < 0 || last_shell > kMaxFirShell)
    throw std::invalid_argument(
        fmt::format("qfir:{}: the last shell must be 0 to {}", last_shell, kMaxFirShell));
  support::FirPrefilterProblem<double> problem;
  problem.order = f.approximation_order();
  for (const auto& [o, w] : lattice_values(f)) problem.samples.push_back({{o[0], o[1], o[2]}, w});
  // One unknown per point: the minimiser is unique, hence as symmetric as the filter.
  const std::vector<support::FirPoint> points = shell_points(f.lattice(), last_shell);
  for (const auto& p : points) problem.groups.push_back({p});
  problem.smoothing = support::kQfirSmoothing;
  const auto weights = support::solve_fir_prefilter(problem);
  if (!weights)
    throw std::invalid_argument(fmt::format(
        "qfir:{}: no prefilter of approximation order {} for filter {} lies on the shells 0 to {}",
        last_shell, problem.order, f.name(), last_shell));
  PrefilterTaps out;
  for (std::size_t i = 0; i < points.size(); ++i)
    out.push_back({{static_cast<int>(points[i][0]), static_cast<int>(points[i][1]),
                    static_cast<int>(points[i][2])},
                   (*weights)[i]});
  return out;
}

}  // namespace boxgen::runtime
