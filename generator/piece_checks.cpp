#include "generator/piece_checks.h"

#include <numeric>
#include <set>
#include <unordered_map>

#include "generator/error.h"
#include "generator/simplex_integral.h"
#include "support/union_find.h"

namespace boxgen::generator {

namespace {

// Polynomials by value (trailing zero coefficients do not count), for sharing work between cells
// with one polynomial.
struct PolyHash {
  std::size_t operator()(const Poly* p) const noexcept {
    std::uint64_t h = 1469598103934665603ull;
    const auto& c = p->coefficients();
    for (std::size_t k = 0; k < c.size(); ++k)
      if (!cln::zerop(c[k]))
        h = (h ^ (k * 0x9e3779b97f4a7c15ull ^ cln::equal_hashcode(c[k]))) * 1099511628211ull;
    return static_cast<std::size_t>(h);
  }
};
struct PolyEqual {
  bool operator()(const Poly* a, const Poly* b) const { return *a == *b; }
};

CellKey neighbour_key(const FineCell& cell, const Facet& f) {
  CellKey k = cell.key;
  k[f.normal] += f.upper ? 1 : -1;
  return k;
}

std::string describe_face(const IntVec& nu, std::int64_t level) {
  std::string s = "(";
  for (size_t i = 0; i < nu.size(); ++i) {
    if (i) s += ',';
    s += std::to_string(nu[i]);
  }
  s += ").x = ";
  s += std::to_string(level);
  return s;
}

// Axis-aligned boxes (every cell of a tensor-product spline) integrate monomial by monomial. A
// cell is such a box exactly when it has 2^n vertices, all on the corners of the box spanned by
// its extreme coordinates. (2^n vertices alone is not enough: a line of slope 1/2 cuts a unit
// square into a triangle and a quadrilateral.)
bool box_corners(const FineCell& cell, RatVec& lo, RatVec& hi) {
  const size_t n = cell.interior.size();
  if (cell.vertices.size() != (std::size_t{1} << n)) return false;
  lo = hi = cell.vertices[0];
  for (const auto& v : cell.vertices)
    for (size_t k = 0; k < n; ++k) {
      lo[k] = cln::min(lo[k], v[k]);
      hi[k] = cln::max(hi[k], v[k]);
    }
  for (const auto& v : cell.vertices)
    for (size_t k = 0; k < n; ++k)
      if (v[k] != lo[k] && v[k] != hi[k]) return false;
  for (size_t k = 0; k < n; ++k)
    if (lo[k] == hi[k]) return false;
  return true;
}

Rational integrate_over_box(const Poly& p, const RatVec& lo, const RatVec& hi) {
  const int n = static_cast<int>(lo.size());
  RatVec minus_corner(n);
  for (int i = 0; i < n; ++i) minus_corner[i] = -lo[i];
  const Poly local = p.translated(minus_corner);  // local(y) = p(y + lo), y in [0, hi - lo]
  const auto& ex = monomial_exponents(n, local.capacity());
  Rational total = 0;
  for (std::size_t i = 0; i < local.coefficients().size(); ++i) {
    if (cln::zerop(local.coefficients()[i])) continue;
    Rational t = local.coefficients()[i];
    for (int k = 0; k < n; ++k)
      t = t * cln::expt(hi[k] - lo[k], ex[i][k] + 1) / Rational(ex[i][k] + 1);
    total = total + t;
  }
  return total;
}

}  // namespace

RatVec spline_centre(const BoxSplineSpec& spec) {
  RatVec c(spec.dimension(), Rational(0));
  for (const auto& xi : spec.directions)
    for (int i = 0; i < spec.dimension(); ++i) c[i] = c[i] + Rational(xi[i]);
  for (auto& v : c) v = v / 2;
  return c;
}

RatVec symmetry_image(const SignedPermutation& g, const RatVec& y, const RatVec& centre) {
  RatVec d(y.size());
  for (size_t i = 0; i < y.size(); ++i) d[i] = y[i] - centre[i];
  RatVec out = g.apply(d);
  for (size_t i = 0; i < y.size(); ++i) out[i] = out[i] + centre[i];
  return out;
}

int count_pieces(const PiecewiseForm& form) {
  const auto& cells = form.knots.cells();
  support::UnionFind uf(cells.size());
  for (size_t i = 0; i < cells.size(); ++i) {
    if (form.polys[i].is_zero()) continue;
    for (const auto& f : facets_of(cells[i], form.knots.planes())) {
      const int j = form.knots.find(neighbour_key(cells[i], f));
      if (j >= 0 && !form.polys[j].is_zero() && form.polys[j] == form.polys[i])
        uf.unite(static_cast<int>(i), j);
    }
  }
  std::set<int> roots;
  for (size_t i = 0; i < cells.size(); ++i)
    if (!form.polys[i].is_zero()) roots.insert(uf.find(static_cast<int>(i)));
  return static_cast<int>(roots.size());
}

static Rational integral_of_cell(const PiecewiseForm& form, int i) {
  const auto& cell = form.knots.cells()[i];
  const Poly& p = form.polys[i];
  if (p.is_zero()) return 0;
  RatVec lo, hi;
  if (box_corners(cell, lo, hi)) return integrate_over_box(p, lo, hi);
  const SimplexIntegrator integrate(p);
  Rational total = 0;
  for (const auto& simplex : triangulate(cell, form.knots)) total = total + integrate.over(simplex);
  return total;
}

Rational total_integral(const PiecewiseForm& form) {
  Rational total = 0;
  for (size_t i = 0; i < form.knots.cells().size(); ++i)
    total = total + integral_of_cell(form, static_cast<int>(i));
  return total;
}

Rational total_integral(const PiecewiseForm& form, const CellOrbits& orbits) {
  Rational total = 0;
  for (size_t o = 0; o < orbits.representatives.size(); ++o)
    total = total + Rational(orbits.sizes[o]) * integral_of_cell(form, orbits.representatives[o]);
  return total;
}

CellOrbits cell_orbits(const PiecewiseForm& form, const std::vector<SignedPermutation>& group) {
  const RatVec c = spline_centre(form.spec);
  const auto& cells = form.knots.cells();
  std::vector<bool> seen(cells.size(), false);
  CellOrbits orbits;
  for (size_t i = 0; i < cells.size(); ++i) {
    if (seen[i]) continue;
    int size = 0;
    for (const auto& g : group) {
      const int j = form.knots.locate(symmetry_image(g, cells[i].interior, c));
      if (j < 0)
        fail_internal("symmetry check failed: the image of a cell of the support lies outside it");
      if (!seen[j]) seen[j] = true, ++size;
    }
    orbits.representatives.push_back(static_cast<int>(i));
    orbits.sizes.push_back(size);
  }
  return orbits;
}

ContinuityReport check_continuity(const PiecewiseForm& form, int order,
                                  const std::vector<int>& subset) {
  ContinuityReport report;
  report.smoothness = order;
  const auto& cells = form.knots.cells();
  const auto& normals = form.knots.planes().normals;
  const Poly zero(form.dimension(), 0);
  const bool all = subset.size() == cells.size();
  for (int i : subset) {
    if (form.polys[i].is_zero()) continue;
    for (const auto& f : facets_of(cells[i], form.knots.planes())) {
      const int j = form.knots.find(neighbour_key(cells[i], f));
      const Poly& other = j >= 0 ? form.polys[j] : zero;
      if (all && !f.upper && !other.is_zero())
        continue;  // that face is checked from the other side
      ++report.faces_checked;
      const IntVec& nu = normals[f.normal];
      int var = 0;
      while (nu[var] == 0) ++var;
      // x_var on the face, as an affine form in the other coordinates.
      RatVec on_face(form.dimension() + 1, Rational(0));
      on_face[0] = Rational(f.level) / Rational(nu[var]);
      for (int k = 0; k < form.dimension(); ++k)
        if (k != var) on_face[k + 1] = Rational(-nu[k]) / Rational(nu[var]);
      Poly jump = form.polys[i] - other;
      for (int e = 0; e <= order; ++e) {
        const bool vanishes = jump.substituted(var, on_face).is_zero();
        if (e < order && !vanishes)
          fail_internal("continuity check failed: derivative of order " + std::to_string(e) +
                        " jumps across the face " + describe_face(nu, f.level));
        if (e == order && !vanishes) report.sharp = true;
        jump = jump.derivative(var);
      }
    }
  }
  return report;
}

ContinuityReport check_continuity(const PiecewiseForm& form, int order) {
  std::vector<int> all(form.knots.cells().size());
  std::iota(all.begin(), all.end(), 0);
  return check_continuity(form, order, all);
}

std::vector<SignedPermutation> generators(const std::vector<SignedPermutation>& group) {
  std::vector<SignedPermutation> gens;
  std::set<std::pair<std::vector<int>, std::vector<int>>> closure{
      {group.front().perm, group.front().sign}};
  for (const auto& g : group) {
    if (closure.count({g.perm, g.sign})) continue;
    gens.push_back(g);
    // Close under multiplication by the generators.
    std::vector<SignedPermutation> frontier;
    for (const auto& [p, s] : closure) frontier.push_back({p, s});
    while (!frontier.empty()) {
      std::vector<SignedPermutation> next;
      for (const auto& h : frontier)
        for (const auto& k : gens) {
          SignedPermutation prod = k.compose(h);
          if (closure.insert({prod.perm, prod.sign}).second) next.push_back(prod);
        }
      frontier = std::move(next);
    }
  }
  return gens;
}

void check_symmetry(const PiecewiseForm& form, const std::vector<SignedPermutation>& group) {
  const int n = form.dimension();
  const RatVec c = spline_centre(form.spec);
  std::vector<SignedPermutation> checks = generators(group);
  checks.push_back({std::vector<int>(n), std::vector<int>(n, -1)});
  std::iota(checks.back().perm.begin(), checks.back().perm.end(), 0);
  const auto& cells = form.knots.cells();
  // Centred pieces Q_i(y) = P_i(y + c), once each; then M^c(g y) = M^c(y) on cell i reads
  // Q_t(g y) = Q_i(y) with t the cell holding the image.
  RatVec minus_c(n);
  for (int i = 0; i < n; ++i) minus_c[i] = -c[i];
  // Cells often share a polynomial (the knot complex is finer than the pieces): centre each
  // distinct polynomial once.
  std::unordered_map<const Poly*, int, PolyHash, PolyEqual> distinct;
  std::vector<Poly> centred_distinct;
  std::vector<const Poly*> centred;
  std::vector<int> centred_index;
  for (const auto& p : form.polys) {
    auto [it, fresh] = distinct.emplace(&p, static_cast<int>(centred_distinct.size()));
    if (fresh) centred_distinct.push_back(p.translated(minus_c));
    centred_index.push_back(it->second);
  }
  for (const int k : centred_index) centred.push_back(&centred_distinct[static_cast<size_t>(k)]);
  for (const auto& g : checks)
    for (size_t i = 0; i < cells.size(); ++i) {
      const int t = form.knots.locate(symmetry_image(g, cells[i].interior, c));
      if (t < 0) {
        if (form.polys[i].is_zero()) continue;
        fail_internal("symmetry check failed: the image of a cell of the support lies outside it");
      }
      if (centred[t]->signed_permuted(g.perm, g.sign) != *centred[i])
        fail_internal("symmetry check failed: M^c(g x) != M^c(x) on a cell");
    }
}

}  // namespace boxgen::generator
