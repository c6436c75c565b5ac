#include "generator/piecewise_form.h"

#include <fmt/format.h>

#include <chrono>

#include "generator/error.h"
#include "generator/knot_normals.h"

namespace boxgen {

Zonotope::Zonotope(const IntColumns& directions, int n) : lo_(n, 0), hi_(n, 0) {
  normals_ = knot_normals(directions, n);
  for (const auto& xi : directions)
    for (int i = 0; i < n; ++i) (xi[i] < 0 ? lo_[i] : hi_[i]) += xi[i];
  for (const auto& nu : normals_) {
    std::int64_t centre2 = 0, width = 0;
    for (const auto& xi : directions) {
      const std::int64_t d = dot(nu, xi);
      centre2 += d;
      width += d < 0 ? -d : d;
    }
    centre_dot_.push_back(Rational(centre2) / 2);
    half_width_.push_back(Rational(width) / 2);
  }
}

bool Zonotope::contains_interior(const RatVec& x) const {
  for (size_t i = 0; i < normals_.size(); ++i)
    if (cln::abs(dot(normals_[i], x) - centre_dot_[i]) >= half_width_[i]) return false;
  return true;
}

const Poly& PiecewiseForm::poly_for_key(const CellKey& key) const {
  const int i = complex.find(key);
  return i < 0 ? zero_ : polys[i];
}

Rational PiecewiseForm::value_at(const RatVec& x, const std::array<int, 3>& derivative) const {
  const auto& normals = complex.normals();
  // Every cell whose closure holds x: keys floor(nu.x), or nu.x - 1 where nu.x is an integer.
  CellKey base = floor_key(normals, x);
  std::vector<size_t> on_plane;
  for (size_t i = 0; i < normals.size(); ++i)
    if (is_integer(dot(normals[i], x))) on_plane.push_back(i);
  std::optional<Rational> value;
  bool found = false;
  for (std::uint64_t mask = 0; mask < (std::uint64_t{1} << on_plane.size()); ++mask) {
    CellKey k = base;
    for (size_t b = 0; b < on_plane.size(); ++b)
      if ((mask >> b) & 1) --k[on_plane[b]];
    const int idx = complex.find(k);
    Poly p;
    if (idx >= 0) {
      // Only cells that really exist and hold x in their closure count.
      p = polys[idx];
    } else {
      bool outside_box = false;
      for (int i = 0; i < dimension(); ++i)
        if (k[i] < complex.lo()[i] || k[i] >= complex.hi()[i]) outside_box = true;
      if (!outside_box) continue;  // an empty cell of the arrangement
      p = Poly::constant(dimension(), 0);
    }
    for (int v = 0; v < dimension(); ++v)
      for (int r = 0; r < derivative[v]; ++r) p = p.derivative(v);
    Rational val = p.eval(x);
    if (value && *value != val)
      fail_input("the point lies on a knot plane where this " +
                 std::string(derivative == std::array<int, 3>{0, 0, 0} ? "value" : "derivative") +
                 " is discontinuous (one-sided values " + to_string(*value) + " and " + to_string(val) + ")");
    value = val;
    found = true;
  }
  if (!found) fail_internal("value_at: no cell holds the point");
  return *value;
}

void check_derivation_size(const BoxSplineSpec& spec) {
  // Refuse up front what would not finish: the number of fine cells in the bounding box is at
  // most (unit cubes) x (cells of an arrangement of P planes, P = knot planes crossing a cube),
  // and each cell holds a polynomial of monomial_count(n, degree) exact coefficients.
  const int n = spec.dimension();
  constexpr int kMaxDegree = 24;  // 24 tensor directions (degree 21) take about 15 s here
  if (spec.count() - n > kMaxDegree)
    fail_input(fmt::format("too large to derive exactly: degree {} (limit {}); use fewer directions", spec.count() - n,
                           kMaxDegree));
  Zonotope support(spec.directions, n);
  double cubes = 1;
  for (int i = 0; i < n; ++i) cubes *= static_cast<double>(support.box_hi()[i] - support.box_lo()[i]);
  double planes = 0;
  for (const auto& nu : knot_normals(spec.directions, n)) {
    std::int64_t width = 0;
    for (auto v : nu) width += v < 0 ? -v : v;
    planes += static_cast<double>(width - 1);
  }
  double per_cube = 1 + planes + planes * (planes - 1) / 2;
  if (n == 3) per_cube += planes * (planes - 1) * (planes - 2) / 6;
  const double work =
      cubes * per_cube * static_cast<double>(monomial_count(n, spec.count() - n));
  constexpr double kLimit = 2e7;  // about 30 times the work of M8
  if (work > kLimit)
    fail_input(fmt::format("too large to derive exactly: about {:.2g} cell coefficients (limit {:.0g}; M8 needs 7e5); "
                           "use fewer directions or smaller entries",
                           work, kLimit));
}

PiecewiseForm derive_piecewise(const BoxSplineSpec& spec, DerivationMethod method) {
  check_derivation_size(spec);
  const auto start = std::chrono::steady_clock::now();
  const int n = spec.dimension();
  Zonotope support(spec.directions, n);
  PiecewiseForm form(spec, method,
                     CellComplex(arrangement_normals(spec.directions, n), support.box_lo(), support.box_hi()));
  auto derivation = BoxSplineDerivation::make(spec.directions, n, method);
  form.polys.reserve(form.complex.cells().size());
  for (const auto& cell : form.complex.cells()) {
    if (!support.contains_interior(cell.interior)) {
      form.polys.push_back(Poly(n, 0));
      continue;
    }
    form.polys.push_back(derivation->polynomial_at(cell.interior));
  }
  form.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return form;
}

}  // namespace boxgen
