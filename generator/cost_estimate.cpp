#include "generator/cost_estimate.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <map>
#include <string>

#include "generator/box_spline_properties.h"
#include "generator/cell_complex.h"
#include "generator/common_scale.h"
#include "generator/error.h"
#include "generator/knot_normals.h"
#include "generator/piecewise_form.h"
#include "generator/symmetry.h"
#include "generator/zonotope.h"
#include "support/available_memory.h"

namespace boxgen::generator {

namespace {

// Calibration: a least-squares fit of the relative error of the CPU seconds (user + sys) and the
// peak memory (max RSS) of `boxgen analyze` with the second derivation on every knot cell (as
// the full checks run it; the default checks' share of it is below), on the table of
// docs/performance.md ("Derivation cost": bench/bench_derivation.cpp and the families
// (1,0) x k, (0,1) x k, (1,1) x k, (1,-1) x k, e1 x k, e2 x k, e3 x k, [e1 e2 e3 (1,1,1)] x k,
// measured with /usr/bin/time on the 2-core development machine). The work terms follow the
// code; a term whose fitted constant came out zero (the truncated power's shift sums, the 3-D
// unit-cube split) is left out: it is within the others' noise. Measured with perf on
// (1,0) x 5, ...: 81% of the time is the second derivation (LevelIntegrator on unit segments),
// whose work the old model put at cells x monomials x knot planes, 10-40 times too low.
//  - directional integration: every cell of every level M_k is expanded along the next column and
//    joined to its neighbours (integration_work); the rational numbers grow with the degree, so
//    a second term weights each level by its degree. 2-D and 3-D have their own constants: a
//    3-D piece of axis-parallel columns (tensor products) is sparse, and the per-product cost
//    fitted on 2-D (dense) pieces is 5-10 times that of 3-D;
//  - checks on the pieces (symmetry, integral, continuity): per knot cell, coefficient work times
//    the number of knot planes;
//  - spline regions: each fine cell of F locates, translates and sums its stencil's pieces (the
//    partition-of-unity check), and is translated from the split unit cube, its facets found and
//    merged.
constexpr double kSecondsPerPlaneCoefficient = 1.09e-7;  // knot cell x monomial x knot plane
constexpr double kSecondsPerIntegrationProduct2D = 7.09e-8;
constexpr double kSecondsPerIntegrationProductDegree2D = 1.19e-8;  // x the level's degree
constexpr double kSecondsPerIntegrationProduct3D = 7.82e-9;
constexpr double kSecondsPerIntegrationProductDegree3D = 1.17e-9;
constexpr double kSecondsPerStencilPoint = 7.88e-7;  // fine cell of F x stencil point
constexpr double kSecondsPerFineCell = 1.02e-4;  // translating, facets and merging of a fine cell
// The default checks run the second derivation on one knot cell per symmetry orbit only
// (derivation.cpp). Its lazy integration still visits most cells of the lower levels on the way,
// so its time is a share of the whole complex's, fitted as one constant (the per-row shares came
// out 0.3 to 0.9 with no trend in the group's order); the coefficients it keeps alive shrink
// with the group's order |G|, fitted as min(1, c / sqrt|G|). Fitted on bench_derivation's rows
// (docs/performance.md, "Cost estimate"); the full checks keep the whole complex's work.
constexpr double kOrbitIntegrationShare = 0.45;
constexpr double kOrbitStoredPerRootGroupOrder = 1.4;
// The process's own start (CLN, GiNaC and the presets) and the smallest derivations.
constexpr double kSecondsStart = 0.02;
// Peak memory: the process (10 MB), each knot cell's polynomial with its translates and cell
// geometry, the coefficients the directional integration keeps alive to its end (every level's
// polynomials, integrated terms G_e and jumps: CLN rationals of about 40 bytes, most of them
// immediate or short), and each stencil point's basis entry.
constexpr double kBytesBase = 1.0e7;
constexpr double kBytesPerKnotCell = 5000;
constexpr double kBytesPerStoredCoefficient = 41;
constexpr double kBytesPerStencilPoint = 75;
constexpr double kEnumerableCells = 2e6;  // above this bound, do not enumerate

double binomial(double p, int k) {
  double r = 1;
  for (int i = 0; i < k; ++i) r = r * (p - i) / (i + 1);
  return std::max(r, 0.0);
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

void refuse_up_front_if_too_costly(const BoxSplineSpec& spec, bool verify, bool full_checks,
                                   double max_seconds, double max_bytes) {
  const double bound =
      knot_cell_bound(knot_planes(spec.directions, spec.dimension()), spec.dimension());
  if (bound <= kEnumerableCells) return;
  refuse_if_too_costly(estimate_cost(spec, verify, full_checks), max_seconds, max_bytes);
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

std::vector<std::size_t> integration_level_cells(const BoxSplineSpec& spec, bool* exact) {
  const int n = spec.dimension();
  const IntColumns columns = basis_first(spec.directions, n);
  std::vector<std::size_t> cells;
  if (exact) *exact = true;
  for (std::size_t k = static_cast<std::size_t>(n); k < columns.size(); ++k) {
    const IntColumns prefix(columns.begin(), columns.begin() + static_cast<std::ptrdiff_t>(k));
    KnotPlanes planes = knot_planes(prefix, n);
    const double bound = knot_cell_bound(planes, n);
    if (bound > kEnumerableCells) {
      cells.push_back(static_cast<std::size_t>(bound));
      if (exact) *exact = false;
      continue;
    }
    const Zonotope box(prefix, n);
    cells.push_back(KnotComplex(std::move(planes), box.box_lo(), box.box_hi()).cells().size());
  }
  return cells;
}

double integration_work(int n, int degree, const IntVec& direction) {
  // Poly::along_direction expands every monomial x^e of the cell's polynomial along the
  // direction: prod_k (e_k + 1) products over the components k that are not zero.
  double along = 0;
  const auto& exponents = monomial_exponents(n, degree);
  for (std::size_t i = 0; i < monomial_count(n, degree); ++i) {
    double terms = 1;
    for (int k = 0; k < n; ++k)
      if (direction[static_cast<std::size_t>(k)] != 0) terms *= exponents[i][k] + 1;
    along += terms;
  }
  // LevelIntegrator::jump: Horner in t over the degree + 2 integrated terms G_e, each step a
  // product by an affine form (n + 1 products per coefficient of degree <= degree + 1) and a sum.
  const double horner =
      (degree + 2.0) * ((n + 1.0) * static_cast<double>(monomial_count(n, degree + 1)) +
                        2.0 * static_cast<double>(monomial_count(n, degree)));
  return along + horner;
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
  bool levels_exact = true;
  e.level_cells = integration_level_cells(spec, &levels_exact);
  e.cells_exact = levels_exact;
  const double per_cube = static_cast<double>(cube_cells);
  e.fundamental_cells =
      static_cast<std::size_t>(per_cube * static_cast<double>(spec.lattice.det_abs()));
  const double monomials = static_cast<double>(monomial_count(n, degree));
  const double stencil = cln::double_approx(box_spline_properties(spec).stencil_size);
  double knot_planes_count = 0;
  for (const auto& levels : knot_planes(spec.directions, n).levels)
    knot_planes_count += static_cast<double>(levels.size());
  const double cells = static_cast<double>(e.knot_cells),
               fine = static_cast<double>(e.fundamental_cells);
  CostEstimate::Work& w = e.work;
  w.plane_checks = cells * monomials * knot_planes_count;
  w.stencil = fine * stencil;
  w.fine = fine;
  // Level L (its cells carry polynomials of degree L, the first n + L columns) is integrated
  // along column n + L; each cell keeps its polynomial, its degree + 2 integrated terms G_e (each
  // of the full capacity, most entries zero) and about one jump of degree L + 1.
  const IntColumns columns = basis_first(spec.directions, n);
  for (std::size_t level = 0; level < e.level_cells.size(); ++level) {
    const int d = static_cast<int>(level);
    const double c = static_cast<double>(e.level_cells[level]);
    const double work = c * integration_work(n, d, columns[static_cast<std::size_t>(n) + level]);
    w.integration += work;
    w.integration_deg += work * d;
    const double stored = c * (static_cast<double>(monomial_count(n + 1, d)) +
                               static_cast<double>(monomial_count(n, d + 1)) +
                               static_cast<double>(monomial_count(n, d)));
    w.stored += stored;
  }
  // The fit is for the default checks; without them about half the plane work remains and no
  // second derivation runs; the full checks visit every cell of every symmetry orbit and every
  // fine cell's stencil.
  const double checks = verify ? (full_checks ? 2.0 : 1.0) : 0.5;
  const double integration = n == 2 ? w.integration * kSecondsPerIntegrationProduct2D +
                                          w.integration_deg * kSecondsPerIntegrationProductDegree2D
                                    : w.integration * kSecondsPerIntegrationProduct3D +
                                          w.integration_deg * kSecondsPerIntegrationProductDegree3D;
  // The symmetry group only where the default checks' share needs its order.
  const bool per_orbit = verify && !full_checks;
  const double integration_share = per_orbit ? kOrbitIntegrationShare : 1.0;
  const double stored_share =
      per_orbit ? std::min(1.0, kOrbitStoredPerRootGroupOrder /
                                    std::sqrt(static_cast<double>(symmetry_group(spec).size())))
                : 1.0;
  e.seconds = kSecondsStart + checks * w.plane_checks * kSecondsPerPlaneCoefficient +
              (verify ? integration_share * integration : 0.0) +
              (verify && full_checks ? 2.0 : 1.0) * w.stencil * kSecondsPerStencilPoint +
              w.fine * kSecondsPerFineCell;
  e.bytes = kBytesBase + kBytesPerKnotCell * cells +
            (verify ? stored_share * w.stored * kBytesPerStoredCoefficient : 0.0) +
            kBytesPerStencilPoint * w.stencil;
  return e;
}

void refuse_if_too_costly(const CostEstimate& e, double max_seconds, double max_bytes) {
  const double limit = max_seconds > 0 ? max_seconds : kDefaultMaxSeconds;
  const std::string cells =
      fmt::format("{} knot cells{}", e.knot_cells, e.cells_exact ? "" : " at most");
  if (e.seconds > limit)
    fail_input(fmt::format(
        "too costly to derive exactly: predicted {:.3g} s and {:.3g} MB ({}), beyond the limit "
        "of {:.3g} s; raise it with --max-seconds, or use fewer directions",
        e.seconds, e.bytes / 1e6, cells, limit));
  const bool given = max_bytes > 0;
  const double memory = given ? max_bytes : support::available_memory_bytes();
  if (memory > 0 && e.bytes > memory)
    fail_input(fmt::format(
        "too costly to derive exactly: predicted {:.3g} MB of memory ({}), beyond the {:.3g} MB "
        "{}; {}use fewer directions",
        e.bytes / 1e6, cells, memory / 1e6,
        given ? "of --max-memory" : "this process may still take (MemAvailable, ulimit -v, cgroup)",
        given ? "raise --max-memory, or " : ""));
}

}  // namespace boxgen::generator
