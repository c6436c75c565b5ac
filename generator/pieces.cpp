#include "generator/pieces.h"

#include <algorithm>
#include <map>
#include <numeric>

#include <fmt/core.h>

#include "generator/error.h"
#include "generator/piece_checks.h"
#include "support/union_find.h"

namespace boxgen::generator {

PiecesOf parse_pieces_of(std::string_view text) {
  if (text == "spline") return PiecesOf::Spline;
  if (text == "filter") return PiecesOf::Filter;
  fail_input(fmt::format("--of must be 'spline' or 'filter', got '{}'", text));
}

PieceSelection parse_piece_selection(std::string_view text) {
  if (text == "reference") return {PieceSelection::Reference, 0};
  if (text == "all") return {PieceSelection::All, 0};
  const bool digits =
      !text.empty() && text.size() <= 6 &&
      std::all_of(text.begin(), text.end(), [](char ch) { return ch >= '0' && ch <= '9'; });
  if (!digits)
    fail_input(
        fmt::format("--region must be 'reference', 'all' or an orbit index, got '{}'", text));
  return {PieceSelection::Orbit, std::stoi(std::string(text))};
}

namespace {

RatVec mean(const std::vector<RatVec>& pts) {
  RatVec m(pts.front().size(), Rational(0));
  for (const auto& p : pts)
    for (size_t i = 0; i < m.size(); ++i) m[i] = m[i] + p[i];
  for (auto& v : m) v = v / Rational(static_cast<long>(pts.size()));
  return m;
}

RatVec plus(const RatVec& a, const RatVec& b, int sign = 1) {
  RatVec r(a.size());
  for (size_t i = 0; i < a.size(); ++i) r[i] = sign > 0 ? a[i] + b[i] : a[i] - b[i];
  return r;
}

// The plane nu.x = level as the inequality that holds at `inside` (which lies off the plane).
Inequality oriented(const Plane& plane, const RatVec& inside) {
  if (dot(plane.nu, inside) < plane.level) return {plane.nu, plane.level};
  IntVec minus(plane.nu.size());
  for (size_t i = 0; i < minus.size(); ++i) minus[i] = -plane.nu[i];
  return {minus, -plane.level};
}

std::vector<Inequality> inequalities(const std::vector<Plane>& planes, const RatVec& inside) {
  std::vector<Inequality> out;
  for (const auto& p : planes) out.push_back(oriented(p, inside));
  return out;
}

// The points of `candidates` where n linearly independent planes are tight: the vertices of the
// convex polytope bounded by `planes`, if the candidates include them.
std::vector<RatVec> polytope_vertices(const std::vector<RatVec>& candidates,
                                      const std::vector<Plane>& planes, int n) {
  std::vector<RatVec> out;
  for (const auto& x : candidates) {
    IntColumns tight;
    for (const auto& pl : planes)
      if (dot(pl.nu, x) == pl.level) tight.push_back(pl.nu);
    if (!tight.empty() && rank(tight, n) == n && std::find(out.begin(), out.end(), x) == out.end())
      out.push_back(x);
  }
  std::sort(out.begin(), out.end());
  return out;
}

// --- the spline ---------------------------------------------------------------------------

// M(x - j) on the spline region around the centred point x, for every lattice point j where it
// is not zero (the same search as the reference regions of spline_structure).
void spline_basis_at(const PiecewiseForm& form, const RatVec& centre, const RatVec& x,
                     Piece& piece) {
  const int n = form.dimension();
  const Rational scale = Rational(form.spec.lattice.det_abs());
  const RatVec u = plus(x, centre);
  IntVec lo(n), hi(n);
  for (int k = 0; k < n; ++k) {
    const std::int64_t corner = floor_to_int64(u[k]);
    lo[k] = corner - form.complex.hi()[k] + 1;
    hi[k] = corner - form.complex.lo()[k];
  }
  for (const auto& j : form.spec.lattice.points_in_box(lo, hi)) {
    const Poly& p = form.poly_at(plus(u, to_ratvec(j), -1));
    if (p.is_zero()) continue;
    piece.stencil.push_back(j);
    piece.polynomials.push_back(p.translated(plus(to_ratvec(j), centre, -1)) * scale);
  }
}

Piece reference_spline_piece(const SplineStructure& s, int orbit) {
  const ReferenceRegion& ref = s.references[orbit];
  Piece p;
  p.vertices = ref.vertices;
  std::sort(p.vertices.begin(), p.vertices.end());
  p.inequalities = inequalities(ref.planes, ref.interior);
  p.interior = ref.interior;
  p.orbit = orbit;
  p.orbit_size = ref.regions_in_orbit;
  p.stencil = ref.stencil;
  p.polynomials = ref.basis;
  return p;
}

void check_orbit(int orbit, int orbits) {
  if (orbit >= orbits)
    fail_input(
        fmt::format("--region must be 'reference', 'all' or an orbit index from 0 to {}, got {}",
                    orbits - 1, orbit));
}

// --- the filter ---------------------------------------------------------------------------

// A candidate piece of M: a set of fine cells with one polynomial.
struct CellUnion {
  std::vector<int> cells;
  bool split = false;  // a non-convex union listed cell by cell
};

CellKey neighbour_key(const FineCell& cell, const Facet& f) {
  CellKey k = cell.key;
  k[f.normal] += f.upper ? 1 : -1;
  return k;
}

// The region of a union of cells in the centred frame, or false if the union is not convex
// (some boundary plane has cell vertices strictly on both sides).
bool region_of(const PiecewiseForm& form, const std::vector<int>& members, const RatVec& centre,
               Piece& piece) {
  const int n = form.dimension();
  const auto& cells = form.knots.cells();
  const auto& normals = form.knots.planes().normals;
  std::vector<Plane> planes;
  std::vector<RatVec> points;
  for (int i : members) {
    for (const auto& v : cells[i].vertices) points.push_back(plus(v, centre, -1));
    for (const auto& f : facets_of(cells[i], form.knots.planes())) {
      const int j = form.knots.find(neighbour_key(cells[i], f));
      if (j >= 0 && std::find(members.begin(), members.end(), j) != members.end()) continue;
      const Plane plane{normals[f.normal], Rational(f.level) - dot(normals[f.normal], centre)};
      if (std::none_of(planes.begin(), planes.end(),
                       [&](const Plane& q) { return q.nu == plane.nu && q.level == plane.level; }))
        planes.push_back(plane);
    }
  }
  for (const auto& pl : planes) {
    bool below = false, above = false;
    for (const auto& v : points) {
      const Rational d = dot(pl.nu, v) - pl.level;
      below = below || cln::minusp(d);
      above = above || cln::plusp(d);
    }
    if (below && above) return false;
  }
  piece.vertices = polytope_vertices(points, planes, n);
  piece.interior = mean(piece.vertices);
  piece.inequalities = inequalities(planes, piece.interior);
  return true;
}

// Connected unions of nonzero cells with one polynomial (as count_pieces), each split into its
// cells if it is not convex, so that every piece is a convex polytope.
std::vector<CellUnion> filter_cell_unions(const PiecewiseForm& form) {
  const auto& cells = form.knots.cells();
  support::UnionFind uf(cells.size());
  for (size_t i = 0; i < cells.size(); ++i) {
    if (form.polys[i].is_zero()) continue;
    for (const auto& f : facets_of(cells[i], form.knots.planes())) {
      const int j = form.knots.find(neighbour_key(cells[i], f));
      if (j >= 0 && form.polys[j] == form.polys[i]) uf.unite(static_cast<int>(i), j);
    }
  }
  std::map<int, int> union_of_root;
  std::vector<CellUnion> unions;
  for (size_t i = 0; i < cells.size(); ++i) {
    if (form.polys[i].is_zero()) continue;
    const auto [it, fresh] =
        union_of_root.emplace(uf.find(static_cast<int>(i)), static_cast<int>(unions.size()));
    if (fresh) unions.emplace_back();
    unions[it->second].cells.push_back(static_cast<int>(i));
  }
  return unions;
}

}  // namespace

Pieces spline_pieces(const PiecewiseForm& form, const SplineStructure& s,
                     const PieceSelection& selection) {
  Pieces out;
  out.of = PiecesOf::Spline;
  out.dimension = form.dimension();
  out.degree = form.spec.count() - form.dimension();
  out.orbits = static_cast<int>(s.references.size());
  switch (selection.kind) {
    case PieceSelection::Reference:
      for (int o = 0; o < out.orbits; ++o) out.pieces.push_back(reference_spline_piece(s, o));
      break;
    case PieceSelection::Orbit:
      check_orbit(selection.orbit, out.orbits);
      out.pieces.push_back(reference_spline_piece(s, selection.orbit));
      break;
    case PieceSelection::All:
      for (const auto& region : s.regions) {
        const FundamentalCell& first = s.cells[region.cells.front()];
        Piece p;
        p.interior = plus(plus(first.cell.interior, to_ratvec(first.placement)), s.centre, -1);
        p.vertices = region.vertices;
        p.inequalities = inequalities(region.planes, p.interior);
        p.orbit = region.orbit;
        p.orbit_size = s.references[region.orbit].regions_in_orbit;
        spline_basis_at(form, s.centre, p.interior, p);
        out.pieces.push_back(std::move(p));
      }
      break;
  }
  return out;
}

Pieces filter_pieces(const PiecewiseForm& form, const PieceSelection& selection) {
  const RatVec centre = spline_centre(form.spec);
  const Rational scale = Rational(form.spec.lattice.det_abs());
  const auto& cells = form.knots.cells();
  RatVec minus_centre = centre;
  for (auto& v : minus_centre) v = -v;
  // Every piece with its region and polynomial; pieces of a split union stay alone in their orbit.
  std::vector<Piece> all;
  std::vector<bool> alone;
  std::vector<int> piece_of_cell(cells.size(), -1);
  for (const auto& u : filter_cell_unions(form)) {
    std::vector<std::vector<int>> parts{u.cells};
    Piece p;
    if (!region_of(form, u.cells, centre, p)) {
      parts.clear();
      for (int c : u.cells) parts.push_back({c});
    }
    for (const auto& part : parts) {
      if (parts.size() > 1 && !region_of(form, part, centre, p))
        fail_internal("a fine cell is not convex");
      p.polynomials = {form.polys[part.front()].translated(minus_centre) * scale};
      for (int c : part) piece_of_cell[c] = static_cast<int>(all.size());
      all.push_back(p);
      alone.push_back(parts.size() > 1);
    }
  }
  // Orbits under the symmetry group: the image of a piece's interior point lies in its image piece.
  support::UnionFind orbits(all.size());
  const std::vector<SignedPermutation> group = symmetry_group(form.spec);
  for (size_t i = 0; i < all.size(); ++i) {
    if (alone[i]) continue;
    for (const auto& g : group) {
      const int cell = form.knots.locate(plus(g.apply(all[i].interior), centre));
      const int image = cell >= 0 ? piece_of_cell[cell] : -1;
      if (image < 0) fail_internal("a symmetry maps a piece of the filter outside its support");
      if (!alone[image]) orbits.unite(static_cast<int>(i), image);
    }
  }
  // Orbit numbers in order of first appearance; the reference piece of an orbit is its member
  // with the lexicographically largest interior point.
  std::map<int, int> orbit_of_root;
  std::vector<int> reference;
  std::vector<int> size;
  for (size_t i = 0; i < all.size(); ++i) {
    const auto [it, fresh] =
        orbit_of_root.emplace(orbits.find(static_cast<int>(i)), static_cast<int>(reference.size()));
    if (fresh) {
      reference.push_back(static_cast<int>(i));
      size.push_back(0);
    }
    const int o = it->second;
    all[i].orbit = o;
    ++size[o];
    if (all[i].interior > all[reference[o]].interior) reference[o] = static_cast<int>(i);
  }
  for (auto& p : all) p.orbit_size = size[p.orbit];

  Pieces out;
  out.of = PiecesOf::Filter;
  out.dimension = form.dimension();
  out.degree = form.spec.count() - form.dimension();
  out.orbits = static_cast<int>(reference.size());
  switch (selection.kind) {
    case PieceSelection::Reference:
      for (int r : reference) out.pieces.push_back(all[r]);
      break;
    case PieceSelection::Orbit:
      check_orbit(selection.orbit, out.orbits);
      out.pieces.push_back(all[reference[selection.orbit]]);
      break;
    case PieceSelection::All:
      out.pieces = std::move(all);
      break;
  }
  return out;
}

}  // namespace boxgen::generator
