#include "generator/spline_regions.h"

#include <algorithm>
#include <array>
#include <deque>
#include <limits>
#include <map>
#include <numeric>
#include <optional>
#include <set>
#include <unordered_map>

#include "generator/common_scale.h"
#include "generator/error.h"
#include "generator/piece_checks.h"
#include "generator/poly_sum.h"
#include "support/union_find.h"

namespace boxgen::generator {

RatVec SpaceGroupElement::apply(const RatVec& x) const {
  RatVec y = g.apply(x);
  for (size_t i = 0; i < y.size(); ++i) y[i] = y[i] + Rational(l[i]);
  return y;
}

namespace {

// A knot cell and a lattice point j: a term M(x - j) taken on that knot cell. Fixed-size, so the
// maps below (millions of terms for a large stencil) neither allocate nor hash a vector per key.
struct CellShift {
  int cell = -1;
  std::array<std::int32_t, 3> j{};
  CellShift(int c, const IntVec& shift) : cell(c) {
    for (size_t i = 0; i < shift.size(); ++i) {
      if (shift[i] < std::numeric_limits<std::int32_t>::min() ||
          shift[i] > std::numeric_limits<std::int32_t>::max())
        fail_internal("a stencil point beyond 32-bit coordinates");
      j[i] = static_cast<std::int32_t>(shift[i]);
    }
  }
  bool operator==(const CellShift&) const = default;
};
struct CellShiftHash {
  std::size_t operator()(const CellShift& key) const noexcept {
    std::uint64_t h = 1469598103934665603ull ^ static_cast<std::uint32_t>(key.cell);
    for (auto v : key.j) h = (h ^ static_cast<std::uint32_t>(v)) * 1099511628211ull;
    return static_cast<std::size_t>(h);
  }
};

CellKey shifted_key(const CellKey& k, const std::vector<IntVec>& normals, const IntVec& j) {
  CellKey out = k;
  for (size_t i = 0; i < normals.size(); ++i)
    out[i] -= static_cast<std::int32_t>(dot(normals[i], j));
  return out;
}

IntVec sub(const IntVec& a, const IntVec& b) {
  IntVec r(a.size());
  for (size_t i = 0; i < a.size(); ++i) r[i] = a[i] - b[i];
  return r;
}

// Everything about the fundamental region that the steps below share.
class Fundamental {
 public:
  explicit Fundamental(const PiecewiseForm& form) : form_(form), n_(form.dimension()) {
    for (auto& c : translate_cells(form.complex.unit_cells(), form.complex.normals(),
                                   form.spec.lattice.coset_representatives())) {
      index_.emplace(c.key, static_cast<int>(cells_.size()));
      FundamentalCell fc;
      fc.cell = std::move(c);
      cells_.push_back(std::move(fc));
    }
    // The lattice points any cube of F or next to it may fetch, enumerated once and grouped, per
    // knot normal, by nu . j (same_spline_piece looks up the points on a few planes).
    IntVec corner_lo, corner_hi;  // range of the cubes of F
    corner_lo = corner_hi =
        IntVec(cells_.front().cell.key.begin(), cells_.front().cell.key.begin() + n_);
    for (const auto& fc : cells_)
      for (int i = 0; i < n_; ++i) {
        corner_lo[i] = std::min<std::int64_t>(corner_lo[i], fc.cell.key[i]);
        corner_hi[i] = std::max<std::int64_t>(corner_hi[i], fc.cell.key[i]);
      }
    IntVec lo(n_), hi(n_);
    for (int i = 0; i < n_; ++i) {
      lo[i] = corner_lo[i] - form.complex.hi()[i];
      hi[i] = corner_hi[i] - form.complex.lo()[i] + 1;
    }
    near_points_ = form.spec.lattice.points_in_box(lo, hi);
    const auto& knot_normals = form.knots.planes().normals;
    points_by_level_.resize(knot_normals.size());
    for (size_t k = 0; k < knot_normals.size(); ++k)
      for (size_t p = 0; p < near_points_.size(); ++p)
        points_by_level_[k][dot(knot_normals[k], near_points_[p])].push_back(static_cast<int>(p));
    for (const auto& nu : normals()) {
      const auto it = std::find(knot_normals.begin(), knot_normals.end(), nu);
      knot_normal_of_.push_back(
          it == knot_normals.end() ? -1 : static_cast<int>(it - knot_normals.begin()));
    }
  }
  std::vector<FundamentalCell>& cells() { return cells_; }
  const PiecewiseForm& form() const { return form_; }
  const std::vector<IntVec>& normals() const { return form_.complex.normals(); }

  // The fundamental cell and lattice vector l such that the cell with this absolute key is F cell +
  // l.
  std::pair<int, IntVec> locate(const CellKey& absolute) const {
    IntVec corner(absolute.begin(), absolute.begin() + n_);
    IntVec rep = form_.spec.lattice.reduce(corner);
    IntVec l = sub(corner, rep);
    auto it = index_.find(shifted_key(absolute, normals(), l));
    if (it == index_.end())
      fail_internal("a cell of the arrangement is missing from the fundamental region");
    return {it->second, l};
  }
  std::pair<int, IntVec> locate_point(const RatVec& u) const {
    return locate(floor_key(normals(), u));
  }

  // True if the spline has one polynomial on a fine cell (located by at_a) and on its neighbour
  // across facet f, the fine cell b (located by at_cell_b) translated by l: the same terms
  // M(u - j) on both. A term can
  // differ only where the facet's plane nu.u = level, moved by -j, is a knot plane of M_Xi, i.e.
  // nu.j = level - L for a knot level L (docs/design.md §7); for every other j the two cells
  // minus j are neighbours inside one knot cell (or both outside the support), so only the j on
  // those few planes are compared, not the whole stencil.
  bool same_spline_piece(const ShiftLocator& at_a, const ShiftLocator& at_cell_b, const IntVec& l,
                         const Facet& f) const {
    const int k = knot_normal_of_[static_cast<size_t>(f.normal)];
    if (k < 0) return true;  // an axis that is no knot normal: no knot plane lies on the facet
    std::optional<ShiftLocator> at_b;  // made when a plane holds a lattice point
    const auto& by_level = points_by_level_[static_cast<size_t>(k)];
    for (const auto level : form_.knots.planes().levels[static_cast<size_t>(k)]) {
      const auto on_plane = by_level.find(f.level - level);
      if (on_plane == by_level.end()) continue;
      if (!at_b) at_b.emplace(at_cell_b.translated(l));
      for (const int p : on_plane->second) {
        const IntVec& j = near_points_[static_cast<size_t>(p)];
        const int ka = at_a.cell_at(j), kb = at_b->cell_at(j);
        const bool zero_a = ka < 0 || form_.polys[ka].is_zero();
        const bool zero_b = kb < 0 || form_.polys[kb].is_zero();
        if (zero_a != zero_b) return false;
        if (!zero_a && ka != kb && form_.polys[ka] != form_.polys[kb]) return false;
      }
    }
    return true;
  }

 private:
  const PiecewiseForm& form_;
  int n_;
  std::vector<FundamentalCell> cells_;
  std::unordered_map<CellKey, int, CellKeyHash> index_;
  std::vector<IntVec> near_points_;  // lattice points any of them may fetch (margin 1)
  std::vector<std::unordered_map<std::int64_t, std::vector<int>>> points_by_level_;
  std::vector<int> knot_normal_of_;  // per fine normal: its index among the knot normals, or -1
};

// Lattice points j with a chance of M_Xi(u - j) != 0 for u in the unit cube at a corner (u - j in
// the support's box), in scan order, enumerated once per cube.
class CubeCandidates {
 public:
  explicit CubeCandidates(const PiecewiseForm& form) : form_(form) {}
  const std::vector<IntVec>& at(const IntVec& corner) {
    auto it = boxes_.find(corner);
    if (it == boxes_.end()) {
      if (boxes_.size() >= kCubesKept) boxes_.clear();  // a scaled F has k^n cubes: keep a few
      IntVec lo(corner.size()), hi(corner.size());
      for (size_t i = 0; i < corner.size(); ++i) {
        lo[i] = corner[i] - form_.complex.hi()[i] + 1;
        hi[i] = corner[i] - form_.complex.lo()[i];
      }
      it = boxes_.emplace(corner, form_.spec.lattice.points_in_box(lo, hi)).first;
    }
    return it->second;
  }

 private:
  static constexpr size_t kCubesKept = 64;
  const PiecewiseForm& form_;
  std::map<IntVec, std::vector<IntVec>> boxes_;
};

void add_unique_plane(std::vector<Plane>& planes, const Plane& p) {
  for (const auto& q : planes)
    if (q.nu == p.nu && q.level == p.level) return;
  planes.push_back(p);
}

RatVec mean(const std::vector<RatVec>& pts) {
  RatVec m(pts[0].size(), Rational(0));
  for (const auto& p : pts)
    for (size_t i = 0; i < m.size(); ++i) m[i] = m[i] + p[i];
  for (auto& v : m) v = v / Rational(static_cast<long>(pts.size()));
  return m;
}

// Builds regions by breadth-first search over facets where the spline piece continues.
std::vector<SplineRegion> merge_regions(Fundamental& fund, const RatVec& c, int n) {
  auto& cells = fund.cells();
  std::vector<std::optional<IntVec>> placed(cells.size());
  std::vector<SplineRegion> regions;
  std::vector<ShiftLocator> locators;  // each cell's, made once (a neighbour's is translated)
  locators.reserve(cells.size());
  for (const auto& fc : cells) locators.emplace_back(fund.form().knots, fc.cell.interior);
  for (size_t start = 0; start < cells.size(); ++start) {
    if (placed[start]) continue;
    SplineRegion region;
    std::vector<RatVec> all_vertices;
    std::deque<int> queue{static_cast<int>(start)};
    placed[start] = IntVec(n, 0);
    while (!queue.empty()) {
      const int i = queue.front();
      queue.pop_front();
      const IntVec& p = *placed[i];
      cells[i].region = static_cast<int>(regions.size());
      cells[i].placement = p;
      region.cells.push_back(i);
      for (const auto& v : cells[i].cell.vertices) {
        RatVec x(n);
        for (int k = 0; k < n; ++k) x[k] = v[k] + Rational(p[k]) - c[k];
        all_vertices.push_back(std::move(x));
      }
      for (const auto& f : facets_of(cells[i].cell, fund.normals())) {
        CellKey other = cells[i].cell.key;
        other[f.normal] += f.upper ? 1 : -1;
        const IntVec& nu = fund.normals()[f.normal];
        auto [j, l] = fund.locate(other);
        if (!fund.same_spline_piece(locators[i], locators[j], l, f)) {
          add_unique_plane(region.planes,
                           {nu, Rational(f.level) + Rational(dot(nu, p)) - dot(nu, c)});
          continue;
        }
        IntVec where(n);
        for (int k = 0; k < n; ++k) where[k] = p[k] + l[k];
        if (!placed[j]) {
          placed[j] = where;
          queue.push_back(j);
        } else if (*placed[j] != where && cells[j].region == static_cast<int>(regions.size())) {
          fail_internal("a spline region meets its own lattice translate");
        }
      }
    }
    // Vertices of the convex region: points where n independent boundary planes are tight
    // (cells share vertices: sorted and made unique once, not searched per vertex).
    std::sort(all_vertices.begin(), all_vertices.end());
    all_vertices.erase(std::unique(all_vertices.begin(), all_vertices.end()), all_vertices.end());
    for (const auto& x : all_vertices) {
      IntColumns tight;
      for (const auto& pl : region.planes)
        if (dot(pl.nu, x) == pl.level) tight.push_back(pl.nu);
      if (!tight.empty() && rank(tight, n) == n) region.vertices.push_back(x);
    }
    std::sort(region.vertices.begin(), region.vertices.end());
    region.centroid = mean(region.vertices);
    regions.push_back(std::move(region));
  }
  return regions;
}

Rational norm2(const RatVec& v) {
  Rational s = 0;
  for (const auto& x : v) s = s + x * x;
  return s;
}

std::vector<RatVec> image_of(const SpaceGroupElement& e, const std::vector<RatVec>& pts) {
  std::vector<RatVec> out;
  for (const auto& p : pts) out.push_back(e.apply(p));
  std::sort(out.begin(), out.end());
  return out;
}

// Orbits of the regions under the space group: the image of a region's first cell under each
// symmetry lands in a region of the same orbit. Creates one (empty) reference per orbit.
void assign_orbits(SplineStructure& s, const Fundamental& fund) {
  support::UnionFind orbits(s.regions.size());
  for (size_t r = 0; r < s.regions.size(); ++r) {
    const auto& fc = s.cells[s.regions[r].cells.front()];
    for (const auto& g : s.group) {
      auto [j, l] = fund.locate_point(symmetry_image(g, fc.cell.interior, s.centre));
      orbits.unite(static_cast<int>(r), s.cells[j].region);
    }
  }
  std::vector<int> orbit_of_root(s.regions.size(), -1);
  for (size_t r = 0; r < s.regions.size(); ++r) {
    int root = orbits.find(static_cast<int>(r));
    if (orbit_of_root[root] < 0) {
      orbit_of_root[root] = static_cast<int>(s.references.size());
      s.references.emplace_back();
    }
    s.regions[r].orbit = orbit_of_root[root];
    ++s.references[s.regions[r].orbit].regions_in_orbit;
  }
}

// Reference region of each orbit: the image g R + l whose centroid is nearest the origin, ties
// broken towards the lexicographically largest centroid (x >= y >= z >= 0 when the group allows
// it). For M7 this is the paper's tetrahedron (0,0,0),(1,1,1),(1,0,0),(1,1,0).
void choose_references(SplineStructure& s, const Lattice& lattice, int n) {
  std::int64_t reach = 2;
  for (const auto& col : lattice.generator())
    for (auto v : col) reach = std::max<std::int64_t>(reach, std::llabs(v) + 1);
  // The regions of each orbit, listed once.
  std::vector<std::vector<int>> members(s.references.size());
  for (size_t r = 0; r < s.regions.size(); ++r)
    members[static_cast<size_t>(s.regions[r].orbit)].push_back(static_cast<int>(r));
  // A candidate image g R + l, its squared centroid norm in double first: only the candidates
  // within rounding of the smallest are compared exactly (the choice stays the exact one).
  struct Candidate {
    double norm;
    int region;
    size_t g;
    const IntVec* l;  // in `boxes`, whose vectors stay put
  };
  // The lattice points of a box depend only on its corner floor(-z) - reach, which few centroid
  // images share: each box is enumerated once.
  std::map<IntVec, std::vector<IntVec>> boxes;
  for (size_t o = 0; o < s.references.size(); ++o) {
    std::vector<Candidate> candidates;
    double smallest = std::numeric_limits<double>::infinity();
    for (int r : members[o]) {
      for (size_t gi = 0; gi < s.group.size(); ++gi) {
        const RatVec z = s.group[gi].apply(s.regions[static_cast<size_t>(r)].centroid);
        IntVec lo(n), hi(n);
        std::vector<double> zd(static_cast<size_t>(n));
        for (int i = 0; i < n; ++i) {
          lo[i] = floor_to_int64(-z[i]) - reach;
          hi[i] = floor_to_int64(-z[i]) + reach;
          zd[static_cast<size_t>(i)] = to_double(z[i]);
        }
        auto box = boxes.find(lo);
        if (box == boxes.end()) box = boxes.emplace(lo, lattice.points_in_box(lo, hi)).first;
        for (const auto& l : box->second) {
          double d = 0;
          for (int i = 0; i < n; ++i) {
            const double y = zd[static_cast<size_t>(i)] + static_cast<double>(l[i]);
            d += y * y;
          }
          if (d > smallest * (1 + 1e-9) + 1e-9) continue;  // beyond the cut below already
          smallest = std::min(smallest, d);
          candidates.push_back({d, r, gi, &l});
        }
      }
    }
    std::optional<std::pair<Rational, RatVec>> best;
    SpaceGroupElement best_map;
    int best_region = -1;
    const double cut = smallest * (1 + 1e-9) + 1e-9;
    for (const Candidate& c : candidates) {
      if (c.norm > cut) continue;
      RatVec y = s.group[c.g].apply(s.regions[static_cast<size_t>(c.region)].centroid);
      for (int i = 0; i < n; ++i) y[i] = y[i] + Rational((*c.l)[i]);
      Rational d = norm2(y);
      if (!best || d < best->first || (d == best->first && y > best->second)) {
        best = std::make_pair(d, y);
        best_map = {s.group[c.g], *c.l};
        best_region = c.region;
      }
    }
    ReferenceRegion& ref = s.references[o];
    const SplineRegion& src = s.regions[best_region];
    ref.vertices = image_of(best_map, src.vertices);
    for (const auto& pl : src.planes) {
      // nu.x = level maps to (g nu).(g x + l) = level + (g nu).l
      IntVec gnu = best_map.g.apply(pl.nu);
      ref.planes.push_back({gnu, pl.level + Rational(dot(gnu, best_map.l))});
    }
    const auto& first = s.cells[src.cells.front()];
    RatVec x(n);
    for (int k = 0; k < n; ++k)
      x[k] = first.cell.interior[k] + Rational(first.placement[k]) - s.centre[k];
    ref.interior = best_map.apply(x);
  }
}

// Every region's map onto its reference: g R + l = R_ref (vertex sets equal).
void map_regions_to_references(SplineStructure& s, const Lattice& lattice, int n) {
  for (auto& region : s.regions) {
    const ReferenceRegion& ref = s.references[region.orbit];
    const RatVec target = mean(ref.vertices);
    bool found = false;
    for (const auto& g : s.group) {
      RatVec z = g.apply(region.centroid);
      IntVec l(n);
      bool integral = true;
      for (int i = 0; i < n; ++i) {
        Rational d = target[i] - z[i];
        if (!is_integer(d))
          integral = false;
        else
          l[i] = floor_to_int64(d);
      }
      if (!integral || !lattice.contains(l)) continue;
      SpaceGroupElement e{g, l};
      if (image_of(e, region.vertices) == ref.vertices) {
        region.to_reference = e;
        found = true;
        break;
      }
    }
    if (!found) fail_internal("a region does not map onto its orbit's reference region");
  }
}

// Stencil and basis polynomials of each reference region (centred frame).
void reference_bases(SplineStructure& s, const PiecewiseForm& form) {
  const int n = form.dimension();
  const Lattice& lattice = form.spec.lattice;
  const Rational scale = Rational(lattice.det_abs());
  // M(x - j) = |det G| P_k(x + c - j): each knot piece is centred once (Q_k(y) = P_k(y + c), times
  // |det G|), then moved by the integer j, which keeps the translation's tables integral.
  RatVec minus_c(n);
  for (int k = 0; k < n; ++k) minus_c[k] = -s.centre[k];
  std::vector<std::optional<Poly>> centred(form.polys.size());
  // Neighbouring regions share most (knot piece, stencil point) pairs: translate each pair once.
  std::unordered_map<CellShift, Poly, CellShiftHash> moved;
  CubeCandidates candidates(form);  // the references lie in a few cubes near the centre
  for (auto& ref : s.references) {
    RatVec u(n);
    IntVec corner(n);
    for (int k = 0; k < n; ++k) {
      u[k] = ref.interior[k] + s.centre[k];
      corner[k] = floor_to_int64(u[k]);
    }
    const ShiftLocator locate(form.knots, u);
    for (const auto& j : candidates.at(corner)) {
      const int cell = locate.cell_at(j);
      if (cell < 0 || form.polys[cell].is_zero()) continue;
      auto [it, fresh] = moved.try_emplace(CellShift(cell, j));
      if (fresh) {
        if (!centred[cell]) centred[cell] = form.polys[cell].translated(minus_c) * scale;
        it->second = centred[cell]->translated(to_ratvec(j));
      }
      ref.stencil.push_back(j);
      ref.stencil_knot_cells.push_back(cell);
      ref.basis.push_back(it->second);
    }
  }
}

}  // namespace

namespace {

SplineStructure structure_in_unit_cubes(const PiecewiseForm& form) {
  const int n = form.dimension();
  SplineStructure s;
  s.centre = spline_centre(form.spec);
  s.group = symmetry_group(form.spec);
  Fundamental fund(form);
  s.regions = merge_regions(fund, s.centre, n);
  s.cells = std::move(fund.cells());
  assign_orbits(s, fund);
  choose_references(s, form.spec.lattice, n);
  map_regions_to_references(s, form.spec.lattice, n);
  reference_bases(s, form);
  // Every fine cell of a region has its reference's stencil, mapped (merge_regions joins cells
  // only where every term is the same; a symmetry and a translation keep the count).
  s.stencil_min = s.stencil_max = static_cast<int>(s.references.front().stencil.size());
  for (const auto& ref : s.references) {
    s.stencil_min = std::min(s.stencil_min, static_cast<int>(ref.stencil.size()));
    s.stencil_max = std::max(s.stencil_max, static_cast<int>(ref.stencil.size()));
  }
  return s;
}

}  // namespace

SplineStructure spline_structure(const PiecewiseForm& form) {
  // F has k^n times the unit cubes of the reduced pair's, each split the same way: derive there.
  if (const std::int64_t k = common_scale(form.spec); k > 1)
    return scaled_up(structure_in_unit_cubes(scaled_down(form, k)), k);
  return structure_in_unit_cubes(form);
}

namespace {

// The distinct stencil terms (knot cell, j) of many sums, each numbered once.
class StencilTerms {
 public:
  // The index of the term (cell, j); `make` gives its polynomial the first time it is seen.
  template <typename Make>
  int index(int cell, const IntVec& j, Make make) {
    auto [it, fresh] = index_.try_emplace(CellShift(cell, j), static_cast<int>(polys_.size()));
    if (fresh) polys_.push_back(make());
    return it->second;
  }
  const std::vector<const Poly*>& polys() const { return polys_; }

 private:
  std::unordered_map<CellShift, int, CellShiftHash> index_;
  std::vector<const Poly*> polys_;
};

}  // namespace

void check_partition_of_unity(const PiecewiseForm& form, const SplineStructure& s, bool full) {
  const int n = form.dimension();
  StencilTerms terms;
  std::vector<std::vector<int>> sums;
  if (!full) {
    for (const auto& ref : s.references) {
      if (ref.stencil.size() != ref.basis.size() ||
          ref.stencil_knot_cells.size() != ref.basis.size())
        fail_internal("a reference region's stencil and basis differ in length");
      std::vector<int>& sum = sums.emplace_back();
      for (size_t k = 0; k < ref.basis.size(); ++k) {
        sum.push_back(
            terms.index(ref.stencil_knot_cells[k], ref.stencil[k], [&] { return &ref.basis[k]; }));
        // A term met before is the same M(x - j) on the same knot cell: it must be the same
        // polynomial, so every basis polynomial takes part in the check.
        if (*terms.polys()[static_cast<size_t>(sum.back())] != ref.basis[k])
          fail_internal("a basis polynomial differs between reference regions");
      }
    }
    const CommonDenominatorTerms exact(n, terms.polys());
    for (const auto& sum : sums)
      if (!exact.sum_is_constant(sum, 1))
        fail_internal("partition of unity fails on a reference region");
    return;
  }
  // Every fine cell's own stencil, found afresh: the terms M(u - j) nonzero at its interior u.
  std::deque<Poly> translated;  // stable addresses
  CubeCandidates candidates(form);
  for (const auto& fc : s.cells) {
    IntVec corner(n);
    for (int k = 0; k < n; ++k) corner[k] = floor_to_int64(fc.cell.interior[k]);
    const ShiftLocator locate(form.knots, fc.cell.interior);
    std::vector<int>& sum = sums.emplace_back();
    for (const auto& j : candidates.at(corner)) {
      const int cell = locate.cell_at(j);
      if (cell < 0 || form.polys[cell].is_zero()) continue;
      sum.push_back(terms.index(cell, j, [&] {
        return &translated.emplace_back(form.polys[cell].translated(to_ratvec(j)));
      }));
    }
    if (sum.empty()) fail_internal("a cell of the fundamental region has an empty stencil");
  }
  const CommonDenominatorTerms exact(n, terms.polys());
  const Rational expected = Rational(1) / Rational(form.spec.lattice.det_abs());
  for (const auto& sum : sums)
    if (!exact.sum_is_constant(sum, expected))
      fail_internal("partition of unity fails on a cell of the fundamental region");
}

}  // namespace boxgen::generator
