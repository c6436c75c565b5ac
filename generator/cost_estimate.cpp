#include "generator/cost_estimate.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <map>

#include "generator/box_spline_properties.h"
#include "generator/cell_complex.h"
#include "generator/common_scale.h"
#include "generator/error.h"
#include "generator/knot_normals.h"
#include "generator/piecewise_form.h"

namespace boxgen::generator {

namespace {

// Calibration: a least-squares fit (in log time) of the user CPU seconds of `boxgen analyze`
// with its default checks on the issue-11 table and the presets (bench/bench_derivation.cpp
// measures them; README, "Derivation cost"): the median of three runs of every row, refitted
// after the stencil location and the sums moved to integer arithmetic. The work terms follow the
// code:
//  - truncated power: per knot cell, every difference shift adds a translated piece;
//  - directional integration and the checks: per knot cell, coefficient work times the number of
//    knot planes (the crossings a path meets);
//  - spline regions: the regions follow the fine cells of F, and each reference region's stencil
//    points are located, translated and summed by the partition-of-unity check; each fine cell
//    is translated from the split unit cube, its facets found and merged. The stencil term was
//    refitted (from 4.6e-7) on the two long 2-D rows, (20,1), ... and (30,1), ..., when the fine
//    cells stopped keeping stencils of their own (stop 17).
constexpr double kSecondsPerShiftCoefficient = 5.4e-9;  // knot cell x shift x monomial
constexpr double kSecondsPerPlaneCoefficient = 7.9e-8;  // knot cell x monomial x knot plane
constexpr double kSecondsPerStencilPoint = 1.9e-7;      // fine cell of F x stencil point
constexpr double kSecondsPerFineCell = 9.6e-7;  // translating, facets and merging of a fine cell
// In 3-D each cell of the split unit cube also costs its exact slicing and the choice of
// reference regions (polytopes with many vertices); the unit cube is split once and translated
// to the other cubes of F, so this is per cell of one cube, not per fine cell of F. Fitted
// afterwards on two skewed 3-D matrices outside the table, (3,1,0), (0,3,1), (1,0,3), (1,1,1)
// and (2,1,0), (0,2,1), (1,0,2), (1,1,1), (1,-1,0) (README, "Derivation cost"), whose unit cube
// has hundreds to thousands of cells; lowered from 2.5e-4 when slicing and the choice of reference
// regions became 2-3 times faster (stop 16), checked on (3,1,0) and (4,1,0), (0,4,1), (1,0,4),
// (1,1,1).
constexpr double kSecondsPerCubeCell3D = 1.0e-4;
// The process's own start and the smallest derivations (the hat measures 0.003 s of CPU): lowered
// from 0.024 s when the small presets fell to 0.02-0.04 s (stop 16), and to 0.004 s (from 0.006)
// when the hat measured 0.002 s in bench_derivation (stop 17).
constexpr double kSecondsStart = 0.004;
constexpr double kBytesBase = 7e6;
constexpr double kBytesPerCoefficient =
    300;  // memoised pieces and translates per knot-cell coefficient
constexpr double kBytesPerStencilPoint =
    80;  // a reference region's basis entry (refitted on the two long 2-D rows, stop 17)
constexpr double kBytesPerFineCell = 3500;  // its exact vertices, key and placement
constexpr double kEnumerableCells = 2e6;    // above this bound, do not enumerate

double binomial(double p, int k) {
  double r = 1;
  for (int i = 0; i < k; ++i) r = r * (p - i) / (i + 1);
  return std::max(r, 0.0);
}

// Distinct shifts sum(S) with a nonzero weight in M = sum_S (-1)^|S| T(. - sum S), as the
// truncated-power derivation groups them; an upper bound when there could be too many to list.
double difference_shifts(const IntColumns& directions, int n) {
  double box = 1;
  for (int i = 0; i < n; ++i) {
    std::int64_t range = 0;
    for (const auto& xi : directions) range += std::llabs(xi[i]);
    box *= static_cast<double>(range + 1);
  }
  const double bound = std::min(box, std::pow(2.0, static_cast<double>(directions.size())));
  if (bound > 1e5) return bound;
  std::map<IntVec, long> w{{IntVec(n, 0), 1}};
  for (const auto& xi : directions) {
    std::map<IntVec, long> next = w;
    for (const auto& [s, c] : w) {
      IntVec t = s;
      for (int i = 0; i < n; ++i) t[i] += xi[i];
      next[t] -= c;
    }
    w.clear();
    for (const auto& [s, c] : next)
      if (c != 0) w.emplace(s, c);
  }
  return static_cast<double>(w.size());
}

double knot_cell_bound(const KnotPlanes& planes, int n) {
  double inner_planes = 0;
  for (const auto& levels : planes.levels) inner_planes += static_cast<double>(levels.size()) - 2;
  double bound = 0;
  for (int k = 0; k <= n; ++k) bound += binomial(inner_planes, k);
  return bound;
}

}  // namespace

void refuse_if_too_many_cells(const BoxSplineSpec& spec) {
  const double bound =
      knot_cell_bound(knot_planes(spec.directions, spec.dimension()), spec.dimension());
  if (bound > kEnumerableCells * 50)
    fail_input(
        fmt::format("too costly to derive exactly: up to {:.3g} knot cells (limit {:.3g}); use "
                    "fewer directions "
                    "or smaller entries",
                    bound, kEnumerableCells * 50));
}

CostEstimate estimate_cost(const BoxSplineSpec& spec, bool verify, bool full_checks) {
  const int n = spec.dimension();
  const KnotPlanes planes = knot_planes(spec.directions, n);
  const double bound = knot_cell_bound(planes, n);
  // The fine arrangement is periodic under integer shifts: one unit cube has the cells of each.
  const std::size_t cube_cells =
      split_cube(arrangement_normals(spec.directions, n), IntVec(n, 0)).size();
  if (bound > kEnumerableCells) {
    CostEstimate e =
        estimate_cost(spec, static_cast<std::size_t>(bound), cube_cells, verify, full_checks);
    e.cells_exact = false;
    return e;
  }
  Zonotope box(spec.directions, n);
  return estimate_cost(spec, KnotComplex(planes, box.box_lo(), box.box_hi()).cells().size(),
                       cube_cells, verify, full_checks);
}

CostEstimate estimate_cost(const BoxSplineSpec& given, std::size_t knot_cells,
                           std::size_t cube_cells, bool verify, bool full_checks) {
  // A scaled pair (k Xi, k G) is derived as (Xi, G) (common_scale.h): its fundamental region has
  // the reduced pair's cubes.
  const BoxSplineSpec spec = reduced_spec(given, common_scale(given));
  const int n = spec.dimension();
  const int degree = spec.count() - n;
  CostEstimate e;
  e.knot_cells = knot_cells;
  e.cells_exact = true;
  const double per_cube = static_cast<double>(cube_cells);
  e.fundamental_cells =
      static_cast<std::size_t>(per_cube * static_cast<double>(spec.lattice.det_abs()));
  const double monomials = static_cast<double>(monomial_count(n, degree));
  const double stencil = cln::double_approx(box_spline_properties(spec).stencil_size);
  const double shifts = difference_shifts(spec.directions, n);
  double knot_planes_count = 0;
  for (const auto& levels : knot_planes(spec.directions, n).levels)
    knot_planes_count += static_cast<double>(levels.size());
  const double cells = static_cast<double>(e.knot_cells),
               fine = static_cast<double>(e.fundamental_cells);
  // The fit is for the default checks; without them about half the plane work remains, and the
  // full checks visit every cell of every symmetry orbit and every fine cell's stencil.
  const double checks = verify ? (full_checks ? 2.0 : 1.0) : 0.5;
  e.seconds = kSecondsStart + cells * shifts * monomials * kSecondsPerShiftCoefficient +
              checks * cells * monomials * knot_planes_count * kSecondsPerPlaneCoefficient +
              (verify && full_checks ? 2.0 : 1.0) * fine * stencil * kSecondsPerStencilPoint +
              fine * kSecondsPerFineCell + (n == 3 ? per_cube * kSecondsPerCubeCell3D : 0.0);
  e.bytes = kBytesBase + kBytesPerCoefficient * cells * monomials +
            kBytesPerStencilPoint * fine * stencil + kBytesPerFineCell * fine;
  return e;
}

void refuse_if_too_costly(const CostEstimate& e, double max_seconds) {
  const double limit = max_seconds > 0 ? max_seconds : kDefaultMaxSeconds;
  if (e.seconds > limit)
    fail_input(fmt::format(
        "too costly to derive exactly: predicted {:.3g} s and {:.3g} MB ({} knot cells{}), "
        "beyond the limit of {:.3g} s; raise it with --max-seconds, or use fewer directions",
        e.seconds, e.bytes / 1e6, e.knot_cells, e.cells_exact ? "" : " at most", limit));
}

}  // namespace boxgen::generator
