#include "generator/cell_complex.h"

#include <algorithm>
#include <iterator>
#include <optional>

#include "generator/error.h"
#include "generator/int_linalg.h"

namespace boxgen::generator {

namespace {

struct Slab {
  IntVec nu;
  Rational lo, hi;  // lo <= nu.x <= hi
};

// A constraint of a polytope: side 0 (nu.x = lo) or 1 (nu.x = hi) of slab s, numbered 2 s + side.
using Constraint = int;

// A convex polytope during splitting: its defining slabs, exact vertices (each with the sorted
// constraints tight there) and key so far.
struct Polytope {
  std::vector<Slab> slabs;
  std::vector<RatVec> vertices;
  std::vector<std::vector<Constraint>> tight;  // per vertex
  CellKey key;
};

// One interval lo <= nu.x <= hi of an arrangement, with its key entry.
struct Interval {
  std::int32_t key;
  Rational lo, hi;
};

// The box [lo, hi] as a polytope: its 2^n corners and the axis slabs.
Polytope box_polytope(const IntVec& lo, const IntVec& hi) {
  const int n = static_cast<int>(lo.size());
  Polytope box;
  for (int i = 0; i < n; ++i) {
    IntVec e(n, 0);
    e[i] = 1;
    box.slabs.push_back({e, Rational(lo[i]), Rational(hi[i])});
  }
  for (int mask = 0; mask < (1 << n); ++mask) {
    RatVec v(n);
    std::vector<Constraint> tight;
    for (int i = 0; i < n; ++i) {
      const bool upper = ((mask >> i) & 1) != 0;
      v[i] = Rational(upper ? hi[i] : lo[i]);
      tight.push_back(2 * i + (upper ? 1 : 0));
    }
    box.vertices.push_back(v);
    box.tight.push_back(std::move(tight));
  }
  return box;
}

// True if the segment between vertices with these tight constraints is an edge of the polytope:
// the constraints tight at both have rank n - 1. (A point strictly inside a segment between two
// vertices is tight exactly where both ends are, and it is a vertex of a slice through it only if
// the segment is an edge: a chord through a point of an edge lies in that edge.)
bool is_edge(const std::vector<Constraint>& a, const std::vector<Constraint>& b,
             const std::vector<Slab>& slabs, int n, std::vector<Constraint>& common) {
  common.clear();
  std::set_intersection(a.begin(), a.end(), b.begin(), b.end(), std::back_inserter(common));
  if (static_cast<int>(common.size()) < n - 1) return false;
  if (n == 1) return true;
  IntColumns normals;
  for (Constraint c : common) normals.push_back(slabs[static_cast<size_t>(c / 2)].nu);
  return rank(normals, n) == n - 1;
}

// The part of w inside the slab `cut` (nullopt if it is not n-dimensional). Its vertices are
// w's vertices in the slab and the crossings of the slab's planes with w's edges.
std::optional<Polytope> slice(const Polytope& w, const IntVec& nu, const Interval& cut, int n) {
  Polytope sub;
  sub.slabs = w.slabs;
  sub.slabs.push_back({nu, cut.lo, cut.hi});
  const Constraint lower = 2 * static_cast<Constraint>(w.slabs.size()), upper = lower + 1;
  sub.key = w.key;
  sub.key.push_back(cut.key);
  // nu.v and its side of each plane are computed once per vertex.
  std::vector<Rational> level;
  level.reserve(w.vertices.size());
  for (const auto& v : w.vertices) level.push_back(dot(nu, v));
  std::vector<int> side_lo, side_hi;
  for (size_t a = 0; a < w.vertices.size(); ++a) {
    side_lo.push_back(cln::compare(level[a], cut.lo));
    side_hi.push_back(cln::compare(level[a], cut.hi));
    if (side_lo[a] >= 0 && side_hi[a] <= 0) {
      sub.vertices.push_back(w.vertices[a]);
      auto& tight = sub.tight.emplace_back(w.tight[a]);
      if (side_lo[a] == 0) tight.push_back(lower);
      if (side_hi[a] == 0) tight.push_back(upper);
    }
  }
  std::vector<Constraint> common;
  for (const bool at_hi : {false, true}) {
    const Rational& c = at_hi ? cut.hi : cut.lo;
    const std::vector<int>& side = at_hi ? side_hi : side_lo;
    for (size_t a = 0; a < w.vertices.size(); ++a)
      for (size_t b = a + 1; b < w.vertices.size(); ++b) {
        if (side[a] * side[b] >= 0) continue;  // no strict crossing
        if (!is_edge(w.tight[a], w.tight[b], w.slabs, n, common)) continue;
        const Rational da = level[a] - c, s = da / (da - (level[b] - c));
        const RatVec& va = w.vertices[a];
        const RatVec& vb = w.vertices[b];
        RatVec x(va.size());
        for (size_t i = 0; i < va.size(); ++i) x[i] = va[i] + s * (vb[i] - va[i]);
        sub.vertices.push_back(std::move(x));
        common.push_back(at_hi ? upper : lower);
        sub.tight.push_back(common);
      }
  }
  if (affine_rank(sub.vertices) != n) return std::nullopt;
  return sub;
}

// Cuts every polytope by the intervals of each normal in turn; `intervals(i, lo, hi)` lists
// the intervals of normal i that meet the open range (lo, hi) of nu_i.x over a polytope.
template <typename Intervals>
std::vector<FineCell> split(Polytope start, const std::vector<IntVec>& normals,
                            Intervals intervals) {
  const int n = static_cast<int>(start.vertices[0].size());
  std::vector<Polytope> work{std::move(start)};
  for (size_t i = 0; i < normals.size(); ++i) {
    std::vector<Polytope> next;
    for (const auto& w : work) {
      Rational lo = dot(normals[i], w.vertices[0]), hi = lo;
      for (const auto& v : w.vertices) {
        const Rational d = dot(normals[i], v);
        lo = cln::min(lo, d);
        hi = cln::max(hi, d);
      }
      for (const Interval& cut : intervals(i, lo, hi))
        if (auto sub = slice(w, normals[i], cut, n)) next.push_back(std::move(*sub));
    }
    work = std::move(next);
  }
  std::vector<FineCell> out;
  for (auto& w : work) {
    FineCell c;
    c.key = std::move(w.key);
    c.vertices = std::move(w.vertices);
    c.interior.assign(n, Rational(0));
    for (const auto& v : c.vertices)
      for (int k = 0; k < n; ++k) c.interior[k] = c.interior[k] + v[k];
    for (auto& x : c.interior) x = x / Rational(static_cast<long>(c.vertices.size()));
    out.push_back(std::move(c));
  }
  return out;
}

}  // namespace

namespace {

// Row echelon rank of the differences p - p0 (any dimension).
int elimination_rank(const std::vector<RatVec>& points) {
  const size_t n = points[0].size();
  std::vector<RatVec> rows;
  for (size_t i = 1; i < points.size(); ++i) {
    RatVec d(n);
    for (size_t k = 0; k < n; ++k) d[k] = points[i][k] - points[0][k];
    rows.push_back(d);
  }
  int r = 0;
  for (size_t col = 0; col < n && r < static_cast<int>(rows.size()); ++col) {
    int pivot = -1;
    for (size_t i = r; i < rows.size(); ++i)
      if (!cln::zerop(rows[i][col])) {
        pivot = static_cast<int>(i);
        break;
      }
    if (pivot < 0) continue;
    std::swap(rows[pivot], rows[r]);
    for (size_t i = r + 1; i < rows.size(); ++i) {
      if (cln::zerop(rows[i][col])) continue;
      Rational f = rows[i][col] / rows[r][col];
      for (size_t k = col; k < n; ++k) rows[i][k] = rows[i][k] - f * rows[r][k];
    }
    ++r;
  }
  return r;
}

}  // namespace

int affine_rank(const std::vector<RatVec>& points, int cap) {
  if (points.size() <= 1 || cap == 0) return 0;
  const size_t n = points[0].size();
  if (n != 2 && n != 3)
    return cap < 0 ? elimination_rank(points) : std::min(elimination_rank(points), cap);
  // In 2-D and 3-D, incrementally and without divisions (this runs for every slice and facet):
  // the first point off p0 gives a direction d1, the first off that line a second direction
  // (2-D: rank 2), and in 3-D the first point off that plane rank 3.
  const RatVec& p0 = points[0];
  auto from_p0 = [&](const RatVec& p) {
    RatVec d(n);
    for (size_t k = 0; k < n; ++k) d[k] = p[k] - p0[k];
    return d;
  };
  size_t i = 1;
  while (i < points.size() && points[i] == p0) ++i;
  if (i == points.size()) return 0;
  if (cap == 1) return 1;
  const RatVec d1 = from_p0(points[i]);
  RatVec normal;  // 3-D: d1 x d2
  for (++i; i < points.size(); ++i) {
    const RatVec d = from_p0(points[i]);
    if (n == 2) {
      if (d1[0] * d[1] != d1[1] * d[0]) return 2;
      continue;
    }
    RatVec c{d1[1] * d[2] - d1[2] * d[1], d1[2] * d[0] - d1[0] * d[2], d1[0] * d[1] - d1[1] * d[0]};
    if (!cln::zerop(c[0]) || !cln::zerop(c[1]) || !cln::zerop(c[2])) {
      normal = std::move(c);
      break;
    }
  }
  if (i >= points.size()) return 1;
  if (cap == 2) return 2;
  for (++i; i < points.size(); ++i) {
    const RatVec d = from_p0(points[i]);
    if (!cln::zerop(normal[0] * d[0] + normal[1] * d[1] + normal[2] * d[2])) return 3;
  }
  return 2;
}

std::vector<FineCell> split_cube(const std::vector<IntVec>& normals, const IntVec& corner) {
  IntVec upper = corner;
  for (auto& v : upper) ++v;
  // Integer levels l <= nu.x <= l + 1, keyed by l.
  auto unit_intervals = [](size_t, const Rational& lo, const Rational& hi) {
    std::vector<Interval> out;
    std::int64_t last = floor_to_int64(hi);
    if (Rational(last) == hi) --last;
    for (std::int64_t l = floor_to_int64(lo); l <= last; ++l)
      out.push_back({static_cast<std::int32_t>(l), Rational(l), Rational(l + 1)});
    return out;
  };
  return split(box_polytope(corner, upper), normals, unit_intervals);
}

std::vector<FineCell> split_cubes(const std::vector<IntVec>& normals,
                                  const std::vector<IntVec>& corners) {
  if (corners.empty()) return {};
  return translate_cells(split_cube(normals, IntVec(corners.front().size(), 0)), normals, corners);
}

std::vector<FineCell> translate_cells(const std::vector<FineCell>& unit,
                                      const std::vector<IntVec>& normals,
                                      const std::vector<IntVec>& corners) {
  std::vector<FineCell> out;
  out.reserve(unit.size() * corners.size());
  for (const IntVec& corner : corners) {
    const RatVec shift = to_ratvec(corner);
    std::vector<std::int32_t> key_shift;
    for (const auto& nu : normals) key_shift.push_back(static_cast<std::int32_t>(dot(nu, corner)));
    for (const FineCell& c : unit) {
      FineCell t = c;
      for (size_t i = 0; i < t.key.size(); ++i) t.key[i] += key_shift[i];
      for (auto& v : t.vertices)
        for (size_t k = 0; k < v.size(); ++k) v[k] = v[k] + shift[k];
      for (size_t k = 0; k < t.interior.size(); ++k) t.interior[k] = t.interior[k] + shift[k];
      out.push_back(std::move(t));
    }
  }
  return out;
}

KnotComplex::KnotComplex(KnotPlanes planes, IntVec lo, IntVec hi)
    : planes_(std::move(planes)), lo_(std::move(lo)), hi_(std::move(hi)) {
  // Between consecutive knot levels L_(k-1) <= nu.x <= L_k, keyed by k; outside the first and
  // last level the box spline vanishes, so those intervals are never cells.
  auto knot_intervals = [this](size_t i, const Rational& from, const Rational& to) {
    const auto& levels = planes_.levels[i];
    std::vector<Interval> out;
    for (size_t k = 1; k < levels.size(); ++k)
      if (Rational(levels[k - 1]) < to && Rational(levels[k]) > from)
        out.push_back({static_cast<std::int32_t>(k), Rational(levels[k - 1]), Rational(levels[k])});
    return out;
  };
  cells_ = split(box_polytope(lo_, hi_), planes_.normals, knot_intervals);
  for (size_t i = 0; i < cells_.size(); ++i) index_.emplace(cells_[i].key, static_cast<int>(i));
}

KnotComplex KnotComplex::scaled_down(std::int64_t k) const {
  KnotComplex out = *this;
  auto divide = [k](std::int64_t v) {
    if (v % k != 0) fail_internal("scaled_down: a knot level is not a multiple of the scale");
    return v / k;
  };
  for (auto& levels : out.planes_.levels)
    for (auto& level : levels) level = divide(level);
  for (auto& v : out.lo_) v = divide(v);
  for (auto& v : out.hi_) v = divide(v);
  const Rational factor = Rational(1) / Rational(k);
  for (auto& cell : out.cells_) {
    for (auto& vertex : cell.vertices)
      for (auto& x : vertex) x = x * factor;
    for (auto& x : cell.interior) x = x * factor;
  }
  return out;
}

int KnotComplex::find(const CellKey& key) const {
  auto it = index_.find(key);
  return it == index_.end() ? -1 : it->second;
}

ShiftLocator::ShiftLocator(const KnotComplex& knots, const RatVec& p) : knots_(&knots), p_(p) {
  // Per normal, t = nu.p once in rationals; then nu.(p - j) = t - nu.j, and the levels L below it
  // are those with L + nu.j <= floor(t) (t not an integer) or L + nu.j < t (t an integer).
  const Integer limit = cln::expt_pos(Integer(2), 60);
  small_ = true;
  for (const auto& nu : knots.planes().normals) {
    const Rational t = dot(nu, p);
    const Integer f = cln::floor1(t);
    small_ = small_ && cln::abs(f) < limit;
    floor_nu_p_.push_back(small_ ? cln::cl_I_to_Q(f) : 0);
    nu_p_integral_.push_back(is_integer(t));
  }
}

ShiftLocator ShiftLocator::translated(const IntVec& l) const {
  RatVec q = p_;
  for (size_t k = 0; k < q.size(); ++k) q[k] = q[k] + Rational(l[k]);
  if (!small_) return ShiftLocator(*knots_, q);
  ShiftLocator out = *this;
  out.p_ = std::move(q);
  const auto& normals = knots_->planes().normals;
  for (size_t i = 0; i < normals.size(); ++i) out.floor_nu_p_[i] += dot(normals[i], l);
  return out;
}

int ShiftLocator::cell_at(const IntVec& j) const {
  if (!small_) {
    RatVec q = p_;
    for (size_t k = 0; k < q.size(); ++k) q[k] = q[k] - Rational(j[k]);
    return knots_->locate(q);
  }
  const KnotPlanes& planes = knots_->planes();
  CellKey& key = key_;
  key.resize(planes.normals.size());
  for (size_t i = 0; i < planes.normals.size(); ++i) {
    const std::int64_t f = floor_nu_p_[i] - dot(planes.normals[i], j);  // floor(nu.(p - j))
    const auto& levels = planes.levels[i];
    const auto below = nu_p_integral_[i] ? std::lower_bound(levels.begin(), levels.end(), f)
                                         : std::upper_bound(levels.begin(), levels.end(), f);
    if (below == levels.begin() || below == levels.end()) return -1;  // outside the support
    key[i] = static_cast<std::int32_t>(below - levels.begin());
  }
  return knots_->find(key);
}

namespace {

// Facets of a cell among these normals; level_of(i, upper) is the plane nu_i . x = level on the
// cell's lower or upper side.
template <typename LevelOf>
std::vector<Facet> facets_among(const FineCell& cell, const std::vector<IntVec>& normals,
                                LevelOf level_of) {
  const int n = static_cast<int>(cell.interior.size());
  std::vector<Facet> out;
  std::vector<Rational> at(cell.vertices.size());  // nu.v, once per normal and vertex
  std::vector<size_t> on_plane;
  for (int i = 0; i < static_cast<int>(normals.size()); ++i) {
    for (size_t k = 0; k < cell.vertices.size(); ++k) at[k] = dot(normals[i], cell.vertices[k]);
    for (bool upper : {false, true}) {
      const std::int64_t level = level_of(i, upper);
      const Rational at_level(level);
      on_plane.clear();
      for (size_t k = 0; k < cell.vertices.size(); ++k)
        if (at[k] == at_level) on_plane.push_back(k);
      // A cell's vertices are its extreme points (slicing adds only edge crossings), and no three
      // extreme points of a convex set are collinear: in 2-D and 3-D, n of them on a bounding
      // plane span it, so only the count is needed there.
      if (on_plane.size() < static_cast<size_t>(n)) continue;
      Facet f{i, level, upper, {}};
      for (size_t k : on_plane) f.vertices.push_back(cell.vertices[k]);
      if (n > 3 && affine_rank(f.vertices, n - 1) != n - 1) continue;
      out.push_back(std::move(f));
    }
  }
  return out;
}

}  // namespace

std::vector<Facet> facets_of(const FineCell& cell, const std::vector<IntVec>& normals) {
  return facets_among(cell, normals, [&](int i, bool upper) -> std::int64_t {
    return cell.key[i] + (upper ? 1 : 0);
  });
}

std::vector<Facet> facets_of(const FineCell& cell, const KnotPlanes& planes) {
  return facets_among(cell, planes.normals, [&](int i, bool upper) {
    return planes.levels[i][cell.key[i] - (upper ? 0 : 1)];
  });
}

namespace {

// Pulling triangulation of the convex hull of `pts` (dimension d) whose faces lie on `planes`.
void pull(const std::vector<RatVec>& pts, int d, const std::vector<Plane>& planes,
          std::vector<RatVec> apex, std::vector<std::vector<RatVec>>& out) {
  if (static_cast<int>(pts.size()) == d + 1) {
    apex.insert(apex.end(), pts.begin(), pts.end());
    out.push_back(std::move(apex));
    return;
  }
  const RatVec& v0 = pts[0];
  std::vector<std::vector<RatVec>> seen;
  for (const auto& [nu, level] : planes) {
    std::vector<RatVec> face;
    for (const auto& p : pts)
      if (dot(nu, p) == level) face.push_back(p);
    if (face.size() == pts.size() || std::find(face.begin(), face.end(), v0) != face.end())
      continue;
    if (affine_rank(face, d - 1) != d - 1) continue;  // the face lies on a plane
    std::sort(face.begin(), face.end());
    if (std::find(seen.begin(), seen.end(), face) != seen.end()) continue;
    seen.push_back(face);
    auto next_apex = apex;
    next_apex.push_back(v0);
    pull(face, d - 1, planes, next_apex, out);
  }
}

}  // namespace

std::vector<std::vector<RatVec>> triangulate_polytope(const std::vector<RatVec>& vertices,
                                                      const std::vector<Plane>& planes) {
  std::vector<std::vector<RatVec>> out;
  pull(vertices, static_cast<int>(vertices[0].size()), planes, {}, out);
  return out;
}

std::vector<std::vector<RatVec>> triangulate(const FineCell& cell, const KnotComplex& complex) {
  const auto& planes = complex.planes();
  const int n = complex.dimension();
  std::vector<Plane> faces;
  for (size_t i = 0; i < planes.normals.size(); ++i)
    for (int up = 0; up <= 1; ++up)
      faces.push_back({planes.normals[i], Rational(planes.levels[i][cell.key[i] - 1 + up])});
  for (int i = 0; i < n; ++i) {  // the box's faces, where they bound a cell
    IntVec e(n, 0);
    e[i] = 1;
    faces.push_back({e, Rational(complex.lo()[i])});
    faces.push_back({e, Rational(complex.hi()[i])});
  }
  return triangulate_polytope(cell.vertices, faces);
}
}  // namespace boxgen::generator
