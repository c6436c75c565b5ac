#include "generator/cell_complex.h"

#include <algorithm>

#include "generator/error.h"
#include "generator/int_linalg.h"

namespace boxgen {

namespace {

struct Slab {
  IntVec nu;
  std::int64_t level;  // level <= nu.x <= level + 1
};

bool inside(const std::vector<Slab>& slabs, const RatVec& x) {
  for (const auto& s : slabs) {
    Rational v = dot(s.nu, x);
    if (v < Rational(s.level) || v > Rational(s.level + 1)) return false;
  }
  return true;
}

int tight_rank(const std::vector<Slab>& slabs, const RatVec& x, int n) {
  IntColumns tight;
  for (const auto& s : slabs) {
    Rational v = dot(s.nu, x);
    if (v == Rational(s.level) || v == Rational(s.level + 1)) tight.push_back(s.nu);
  }
  return tight.empty() ? 0 : rank(tight, n);
}

void add_unique(std::vector<RatVec>& pts, RatVec p) {
  if (std::find(pts.begin(), pts.end(), p) == pts.end()) pts.push_back(std::move(p));
}

}  // namespace

int affine_rank(const std::vector<RatVec>& points) {
  if (points.size() <= 1) return 0;
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
      if (!cln::zerop(rows[i][col])) { pivot = static_cast<int>(i); break; }
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

std::vector<FineCell> CellComplex::split_cube(const std::vector<IntVec>& normals, const IntVec& corner) {
  const int n = static_cast<int>(corner.size());
  struct Work {
    std::vector<Slab> slabs;
    std::vector<RatVec> vertices;
    CellKey key;
  };
  Work cube;
  for (int mask = 0; mask < (1 << n); ++mask) {
    RatVec v(n);
    for (int i = 0; i < n; ++i) v[i] = Rational(corner[i] + ((mask >> i) & 1));
    cube.vertices.push_back(v);
  }
  std::vector<Work> work{cube};
  for (const auto& nu : normals) {
    std::vector<Work> next;
    for (auto& w : work) {
      Rational lo = dot(nu, w.vertices[0]), hi = lo;
      for (const auto& v : w.vertices) {
        Rational d = dot(nu, v);
        lo = cln::min(lo, d);
        hi = cln::max(hi, d);
      }
      const std::int64_t first = floor_to_int64(lo);
      std::int64_t last = floor_to_int64(hi);
      if (Rational(last) == hi) --last;
      for (std::int64_t l = first; l <= last; ++l) {
        Work sub;
        sub.slabs = w.slabs;
        sub.slabs.push_back({nu, l});
        sub.key = w.key;
        sub.key.push_back(static_cast<std::int32_t>(l));
        std::vector<RatVec> candidates;
        for (const auto& v : w.vertices)
          if (inside(sub.slabs, v)) add_unique(candidates, v);
        for (std::int64_t plane : {l, l + 1}) {
          const Rational c = Rational(plane);
          for (size_t a = 0; a < w.vertices.size(); ++a)
            for (size_t b = a + 1; b < w.vertices.size(); ++b) {
              const Rational da = dot(nu, w.vertices[a]) - c, db = dot(nu, w.vertices[b]) - c;
              if (!(cln::minusp(da) && cln::plusp(db)) && !(cln::plusp(da) && cln::minusp(db))) continue;
              const Rational s = da / (da - db);
              RatVec x(n);
              for (int i = 0; i < n; ++i) x[i] = w.vertices[a][i] + s * (w.vertices[b][i] - w.vertices[a][i]);
              if (inside(sub.slabs, x)) add_unique(candidates, x);
            }
        }
        // Keep true vertices only: points where n independent constraints (cube faces included) are tight.
        std::vector<Slab> all = sub.slabs;
        for (int i = 0; i < n; ++i) {
          IntVec e(n, 0);
          e[i] = 1;
          all.push_back({e, corner[i]});
        }
        for (const auto& x : candidates)
          if (tight_rank(all, x, n) == n) sub.vertices.push_back(x);
        if (affine_rank(sub.vertices) == n) next.push_back(std::move(sub));
      }
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
      for (int i = 0; i < n; ++i) c.interior[i] = c.interior[i] + v[i];
    for (auto& x : c.interior) x = x / Rational(static_cast<long>(c.vertices.size()));
    out.push_back(std::move(c));
  }
  return out;
}

CellComplex::CellComplex(std::vector<IntVec> normals, IntVec lo, IntVec hi)
    : n_(static_cast<int>(lo.size())), normals_(std::move(normals)), lo_(std::move(lo)), hi_(std::move(hi)) {
  IntVec corner = lo_;
  for (;;) {
    for (auto& c : split_cube(normals_, corner)) {
      index_.emplace(c.key, static_cast<int>(cells_.size()));
      cells_.push_back(std::move(c));
    }
    int i = 0;
    while (i < n_ && corner[i] + 1 >= hi_[i]) corner[i] = lo_[i], ++i;
    if (i == n_) break;
    ++corner[i];
  }
}

int CellComplex::find(const CellKey& key) const {
  auto it = index_.find(key);
  return it == index_.end() ? -1 : it->second;
}

std::vector<Facet> facets_of(const FineCell& cell, const std::vector<IntVec>& normals) {
  const int n = static_cast<int>(cell.interior.size());
  std::vector<Facet> out;
  for (int i = 0; i < static_cast<int>(normals.size()); ++i)
    for (bool upper : {false, true}) {
      const std::int32_t level = cell.key[i] + (upper ? 1 : 0);
      Facet f{i, level, upper, {}};
      for (const auto& v : cell.vertices)
        if (dot(normals[i], v) == Rational(level)) f.vertices.push_back(v);
      if (affine_rank(f.vertices) == n - 1) out.push_back(std::move(f));
    }
  return out;
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
    if (face.size() == pts.size() || std::find(face.begin(), face.end(), v0) != face.end()) continue;
    if (affine_rank(face) != d - 1) continue;
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

std::vector<std::vector<RatVec>> triangulate(const FineCell& cell, const std::vector<IntVec>& normals) {
  std::vector<Plane> planes;
  for (size_t i = 0; i < normals.size(); ++i)
    for (int up = 0; up <= 1; ++up) planes.push_back({normals[i], Rational(cell.key[i] + up)});
  return triangulate_polytope(cell.vertices, planes);
}

}  // namespace boxgen
