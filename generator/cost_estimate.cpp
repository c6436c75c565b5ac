#include "generator/cost_estimate.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "generator/box_spline_properties.h"
#include "generator/cell_complex.h"
#include "generator/error.h"
#include "generator/knot_normals.h"
#include "generator/piecewise_form.h"

namespace boxgen {

namespace {

// Calibration (seconds and bytes per unit of work), fitted on the issue-11 table and the
// presets; see bench/bench_derivation.cpp, which measures them.
constexpr double kSecondsPerKnotWork = 4.0e-7;   // per knot cell x monomial x difference shift
constexpr double kSecondsPerCheckWork = 2.0e-6;  // per knot cell x monomial (checks)
constexpr double kSecondsPerStencilWork = 4.0e-7;  // per fine cell of F x stencil point x monomial
constexpr double kBytesBase = 8e6;
constexpr double kBytesPerCoefficient = 120;     // a stored exact coefficient and its share of maps
constexpr double kEnumerableCells = 2e6;         // above this bound, do not enumerate

double binomial(double p, int k) {
  double r = 1;
  for (int i = 0; i < k; ++i) r = r * (p - i) / (i + 1);
  return std::max(r, 0.0);
}

// Distinct shifts sum(S) with a nonzero weight in M = sum_S (-1)^|S| T(. - sum S), counted
// through their projections as an upper bound (no 2^m enumeration).
double difference_shifts(const IntColumns& directions, int n) {
  double shifts = 1;
  for (int i = 0; i < n; ++i) {
    std::int64_t range = 0;
    for (const auto& xi : directions) range += std::llabs(xi[i]);
    shifts *= static_cast<double>(range + 1);
  }
  return std::min(shifts, std::pow(2.0, static_cast<double>(directions.size())));
}

}  // namespace

CostEstimate estimate_cost(const BoxSplineSpec& spec, bool verify, bool full_checks) {
  const int n = spec.dimension();
  const int degree = spec.count() - n;
  CostEstimate e;
  const KnotPlanes planes = knot_planes(spec.directions, n);
  double inner_planes = 0;
  for (const auto& levels : planes.levels) inner_planes += static_cast<double>(levels.size()) - 2;
  double bound = 0;
  for (int k = 0; k <= n; ++k) bound += binomial(inner_planes, k);
  Zonotope box(spec.directions, n);
  if (bound <= kEnumerableCells) {
    e.knot_cells = KnotComplex(planes, box.box_lo(), box.box_hi()).cells().size();
    e.cells_exact = true;
  } else {
    e.knot_cells = static_cast<std::size_t>(bound);
  }
  // The fine arrangement is periodic under integer shifts: one unit cube has the cells of each.
  IntVec origin(n, 0);
  const double per_cube = static_cast<double>(split_cube(arrangement_normals(spec.directions, n), origin).size());
  e.fundamental_cells = static_cast<std::size_t>(per_cube * static_cast<double>(spec.lattice.det_abs()));
  const double monomials = static_cast<double>(monomial_count(n, degree));
  const double stencil = cln::double_approx(box_spline_properties(spec).stencil_size);
  const double shifts = difference_shifts(spec.directions, n);
  const double cells = static_cast<double>(e.knot_cells), fine = static_cast<double>(e.fundamental_cells);
  double work = cells * monomials * shifts * kSecondsPerKnotWork + fine * stencil * monomials * kSecondsPerStencilWork;
  if (verify) work += cells * monomials * kSecondsPerCheckWork * (full_checks ? 8 : 1) +
                      fine * stencil * monomials * kSecondsPerStencilWork;
  e.seconds = work;
  e.bytes = kBytesBase + kBytesPerCoefficient * monomials * (cells * 3 + fine * std::min(stencil, 64.0));
  return e;
}

void refuse_if_too_costly(const CostEstimate& e, double max_seconds) {
  const double limit = max_seconds > 0 ? max_seconds : kDefaultMaxSeconds;
  if (e.seconds > limit)
    fail_input(fmt::format("too costly to derive exactly: predicted {:.3g} s and {:.3g} MB ({} knot cells{}), "
                           "beyond the limit of {:.3g} s; raise it with --max-seconds, or use fewer directions",
                           e.seconds, e.bytes / 1e6, e.knot_cells, e.cells_exact ? "" : " at most", limit));
}

}  // namespace boxgen
