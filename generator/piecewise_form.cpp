#include "generator/piecewise_form.h"

#include <fmt/format.h>

#include <algorithm>
#include <chrono>

#include "generator/cost_estimate.h"
#include "generator/error.h"
#include "generator/knot_normals.h"

namespace boxgen::generator {

const Poly& PiecewiseForm::poly_at(const RatVec& x) const {
  const int i = knots.locate(x);
  return i < 0 ? zero_ : polys[i];
}

Rational PiecewiseForm::value_at(const RatVec& x, const std::array<int, 3>& derivative) const {
  const KnotPlanes& planes = knots.planes();
  // Every cell whose closure holds x: on a knot plane L_k = nu.x, the cells below (key k) and
  // above (key k + 1); interval_key gives the one below.
  const CellKey base = interval_key(planes, x);
  std::vector<size_t> on_plane;
  for (size_t i = 0; i < planes.normals.size(); ++i) {
    const Rational v = dot(planes.normals[i], x);
    if (is_integer(v) &&
        std::binary_search(planes.levels[i].begin(), planes.levels[i].end(), floor_to_int64(v)))
      on_plane.push_back(i);
  }
  std::optional<Rational> value;
  for (std::uint64_t mask = 0; mask < (std::uint64_t{1} << on_plane.size()); ++mask) {
    CellKey k = base;
    for (size_t b = 0; b < on_plane.size(); ++b)
      if ((mask >> b) & 1) ++k[on_plane[b]];
    const int idx = knots.find(k);
    Poly p;
    if (idx >= 0) {
      p = polys[idx];
    } else {
      bool outside = false;  // beyond the first or last knot level of some normal
      for (size_t i = 0; i < k.size(); ++i)
        if (k[i] <= 0 || k[i] >= static_cast<std::int32_t>(planes.levels[i].size())) outside = true;
      if (!outside) continue;  // an empty cell of the arrangement
      p = Poly::constant(dimension(), 0);
    }
    for (int v = 0; v < dimension(); ++v)
      for (int r = 0; r < derivative[v]; ++r) p = p.derivative(v);
    Rational val = p.eval(x);
    if (value && *value != val)
      fail_input("the point lies on a knot plane where this " +
                 std::string(derivative == std::array<int, 3>{0, 0, 0} ? "value" : "derivative") +
                 " is discontinuous (one-sided values " + to_string(*value) + " and " +
                 to_string(val) + ")");
    value = val;
  }
  if (!value) fail_internal("value_at: no cell holds the point");
  return *value;
}

namespace {

// The pieces on every cell of `knots`, or on the listed ones only.
std::vector<Poly> derive_on_cells(const BoxSplineSpec& spec, const KnotComplex& knots,
                                  DerivationMethod method, const ProgressFn& progress,
                                  const std::vector<int>* listed = nullptr) {
  auto derivation = BoxSplineDerivation::make(spec.directions, spec.dimension(), method);
  const auto& cells = knots.cells();
  const std::size_t count = listed ? listed->size() : cells.size();
  const char* stage = method == DerivationMethod::TruncatedPower
                          ? "deriving (truncated power)"
                          : "deriving (directional integration)";
  std::vector<Poly> polys;
  polys.reserve(count);
  for (std::size_t i = 0; i < count; ++i) {
    const std::size_t cell = listed ? static_cast<std::size_t>((*listed)[i]) : i;
    polys.push_back(derivation->polynomial_at(cells[cell].interior));
    if (progress) progress(stage, polys.size(), count);
  }
  return polys;
}

}  // namespace

PiecewiseForm derive_piecewise(const BoxSplineSpec& spec, DerivationMethod method,
                               const ProgressFn& progress, const DerivationBudget& budget) {
  const auto start = std::chrono::steady_clock::now();
  const int n = spec.dimension();
  refuse_if_too_many_cells(spec);
  refuse_up_front_if_too_costly(spec, budget.with_checks, budget.full_checks, budget.max_seconds,
                                budget.max_bytes);
  Zonotope support(spec.directions, n);
  if (progress) progress("knot-plane cells", 0, 0);
  PiecewiseForm form(
      spec, method,
      KnotComplex(knot_planes(spec.directions, n), support.box_lo(), support.box_hi()),
      FineArrangement(arrangement_normals(spec.directions, n), support.box_lo(), support.box_hi()));
  refuse_if_too_costly(
      estimate_cost(spec, form.knots.cells().size(), form.complex.unit_cells().size(),
                    budget.with_checks, budget.full_checks),
      budget.max_seconds, budget.max_bytes);
  form.polys = derive_on_cells(spec, form.knots, method, progress);
  form.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return form;
}

std::vector<Poly> rederive(const PiecewiseForm& form, DerivationMethod method,
                           const ProgressFn& progress, const std::vector<int>* cells) {
  return derive_on_cells(form.spec, form.knots, method, progress, cells);
}

}  // namespace boxgen::generator
