#include "analysis/dual_lattice.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>
#include <utility>

namespace boxgen::analysis {

namespace {

double dot(const Vec& a, const Vec& b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }
Vec sub(const Vec& a, const Vec& b) { return {a[0] - b[0], a[1] - b[1], a[2] - b[2]}; }
Vec cross(const Vec& a, const Vec& b) {
  return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
}

// Solves the k x k system rows[i] . x = rhs[i] (k <= 3) by Gaussian elimination with partial
// pivoting; false if (nearly) singular.
bool solve_small(std::vector<Vec> rows, std::vector<double> rhs, int k, Vec& x) {
  for (int c = 0; c < k; ++c) {
    int p = c;
    for (int r = c + 1; r < k; ++r)
      if (std::abs(rows[r][c]) > std::abs(rows[p][c])) p = r;
    if (std::abs(rows[p][c]) < 1e-12) return false;
    std::swap(rows[p], rows[c]);
    std::swap(rhs[p], rhs[c]);
    for (int r = 0; r < k; ++r) {
      if (r == c) continue;
      const double f = rows[r][c] / rows[c][c];
      for (int j = c; j < k; ++j) rows[r][j] -= f * rows[c][j];
      rhs[r] -= f * rhs[c];
    }
  }
  x = {0, 0, 0};
  for (int c = 0; c < k; ++c) x[c] = rhs[c] / rows[c][c];
  return true;
}

}  // namespace

bool VoronoiCell::contains(const Vec& w, double tolerance) const {
  for (const auto& f : faces)
    if (dot(f.normal, w) > f.offset + tolerance * (1 + f.offset)) return false;
  return true;
}

std::vector<Vec> polytope_vertices(const std::vector<HalfSpace>& constraints, int n,
                                   double tolerance) {
  std::vector<Vec> out;
  const int m = static_cast<int>(constraints.size());
  std::vector<int> pick(n);
  auto feasible = [&](const Vec& x) {
    for (const auto& h : constraints)
      if (dot(h.normal, x) > h.offset + tolerance * (1 + std::abs(h.offset))) return false;
    return true;
  };
  auto add = [&](const Vec& x) {
    for (const auto& v : out)
      if (std::abs(v[0] - x[0]) + std::abs(v[1] - x[1]) + std::abs(v[2] - x[2]) <
          1e-9 * (1 + std::abs(x[0]) + std::abs(x[1]) + std::abs(x[2])))
        return;
    out.push_back(x);
  };
  // Enumerate n-subsets i0 < i1 < ... of the constraints.
  std::vector<int> idx(n);
  for (int i = 0; i < n; ++i) idx[i] = i;
  if (m < n) return out;
  while (true) {
    std::vector<Vec> rows(n);
    std::vector<double> rhs(n);
    for (int i = 0; i < n; ++i) {
      rows[i] = constraints[idx[i]].normal;
      rhs[i] = constraints[idx[i]].offset;
    }
    Vec x;
    if (solve_small(rows, rhs, n, x) && feasible(x)) add(x);
    int i = n - 1;
    while (i >= 0 && idx[i] == m - n + i) --i;
    if (i < 0) break;
    ++idx[i];
    for (int j = i + 1; j < n; ++j) idx[j] = idx[j - 1] + 1;
  }
  return out;
}

namespace {

// G as a double matrix g[row][col] (identity beyond n), checked square and non-singular.
struct DoubleMatrix {
  double g[3][3] = {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
  double det = 0;
};

DoubleMatrix generator_matrix(const IntDirections& generator, int n) {
  DoubleMatrix m;
  for (int c = 0; c < n; ++c) {
    if (static_cast<int>(generator[c].size()) != n)
      throw std::invalid_argument("the lattice generator must be square");
    for (int r = 0; r < n; ++r) m.g[r][c] = static_cast<double>(generator[c][r]);
  }
  const auto& g = m.g;
  m.det = g[0][0] * (g[1][1] * g[2][2] - g[1][2] * g[2][1]) -
          g[0][1] * (g[1][0] * g[2][2] - g[1][2] * g[2][0]) +
          g[0][2] * (g[1][0] * g[2][1] - g[1][1] * g[2][0]);
  if (std::abs(m.det) < 0.5) throw std::invalid_argument("the lattice generator is singular");
  return m;
}

// Dual basis d_i with d_i . g_j = 2 pi delta_ij: the rows of 2 pi G^-1 (by the adjugate).
std::vector<Vec> dual_basis(const DoubleMatrix& m, int n) {
  const auto& g = m.g;
  const Vec c0{g[0][0], g[1][0], g[2][0]}, c1{g[0][1], g[1][1], g[2][1]},
      c2{g[0][2], g[1][2], g[2][2]};
  const double scale = 2 * std::numbers::pi / m.det;
  const Vec r0 = cross(c1, c2), r1 = cross(c2, c0), r2 = cross(c0, c1);  // rows of det * G^-1
  if (n == 2) return {Vec{scale * r0[0], scale * r0[1], 0}, Vec{scale * r1[0], scale * r1[1], 0}};
  return {Vec{scale * r0[0], scale * r0[1], scale * r0[2]},
          Vec{scale * r1[0], scale * r1[1], scale * r1[2]},
          Vec{scale * r2[0], scale * r2[1], scale * r2[2]}};
}

// The facets of the polytope with these vertices among the half-spaces hs: those touched by n
// affinely independent vertices; in 3-D each face's vertices in cyclic order about its centroid.
void keep_facets(const std::vector<HalfSpace>& hs, const std::vector<Vec>& vertices, int n,
                 VoronoiCell& cell) {
  for (const auto& h : hs) {
    std::vector<int> on;
    for (int v = 0; v < static_cast<int>(vertices.size()); ++v)
      if (std::abs(dot(h.normal, vertices[v]) - h.offset) < 1e-9 * (1 + h.offset)) on.push_back(v);
    if (static_cast<int>(on.size()) < n) continue;
    cell.faces.push_back(h);
    if (n == 3) {
      Vec m{0, 0, 0};
      for (int v : on)
        for (int i = 0; i < 3; ++i) m[i] += vertices[v][i] / static_cast<double>(on.size());
      const Vec e1 = sub(vertices[on[0]], m);
      const Vec e2 = cross(h.normal, e1);
      const auto angle = [&](int v) {
        const Vec d = sub(vertices[v], m);
        return std::atan2(dot(d, e2), dot(d, e1));
      };
      std::sort(on.begin(), on.end(), [&](int a, int b) { return angle(a) < angle(b); });
    }
    cell.face_vertices.push_back(on);
  }
}

// Volume by the fan of simplices from 0 over the ordered faces.
double fan_volume(const VoronoiCell& cell) {
  double volume = 0;
  const auto& vertices = cell.vertices;
  for (const auto& f : cell.face_vertices) {
    if (cell.n == 2) {
      const Vec& a = vertices[f[0]];
      const Vec& b = vertices[f[1]];
      volume += 0.5 * std::abs(a[0] * b[1] - a[1] * b[0]);
      continue;
    }
    for (std::size_t j = 1; j + 1 < f.size(); ++j)
      volume += std::abs(dot(vertices[f[0]], cross(vertices[f[j]], vertices[f[j + 1]]))) / 6;
  }
  return volume;
}

}  // namespace

DualLattice::DualLattice(const IntDirections& generator) {
  n_ = static_cast<int>(generator.size());
  if (n_ < 2 || n_ > 3) throw std::invalid_argument("the lattice must be 2- or 3-dimensional");
  const DoubleMatrix g = generator_matrix(generator, n_);
  det_g_ = std::abs(g.det);
  basis_ = dual_basis(g, n_);
  build_voronoi_cell();
}

std::vector<Vec> DualLattice::short_points(int range) const {
  std::vector<Vec> out;
  std::vector<std::int64_t> c(n_, -range);
  while (true) {
    if (std::any_of(c.begin(), c.end(), [](std::int64_t v) { return v != 0; }))
      out.push_back(point(c));
    int i = 0;
    while (i < n_ && c[i] == range) c[i++] = -range;
    if (i == n_) break;
    ++c[i];
  }
  std::sort(out.begin(), out.end(),
            [](const Vec& a, const Vec& b) { return dot(a, a) < dot(b, b); });
  return out;
}

// The Voronoi cell: half-spaces of the shortest dual points, grown shell by shell until every
// point that could cut the cell (|k| <= 2 * circumradius) is among them.
void DualLattice::build_voronoi_cell() {
  const std::vector<Vec> candidates = short_points(4);
  const auto norm2 = [&](std::size_t i) { return dot(candidates[i], candidates[i]); };
  std::size_t used = std::min<std::size_t>(candidates.size(), n_ == 3 ? 26 : 8);
  while (true) {
    while (used < candidates.size() && std::abs(norm2(used) - norm2(used - 1)) < 1e-9)
      ++used;  // whole shells
    std::vector<HalfSpace> hs;
    for (std::size_t i = 0; i < used; ++i) hs.push_back({candidates[i], 0.5 * norm2(i)});
    std::vector<Vec> vertices = polytope_vertices(hs, n_);
    double r = 0;
    for (const auto& v : vertices) r = std::max(r, std::sqrt(dot(v, v)));
    if (used == candidates.size() || std::sqrt(norm2(used)) > 2 * r * (1 + 1e-9)) {
      covering_radius_ = r;
      keep_facets(hs, vertices, n_, cell_);
      cell_.n = n_;
      cell_.vertices = std::move(vertices);
      cell_.volume = fan_volume(cell_);
      return;
    }
    used = std::min(candidates.size(), used + 1);
  }
}

Vec DualLattice::point(const std::vector<std::int64_t>& c) const {
  Vec p{0, 0, 0};
  for (int i = 0; i < n_; ++i)
    for (int r = 0; r < 3; ++r) p[r] += static_cast<double>(c[i]) * basis_[i][r];
  return p;
}

std::vector<Vec> DualLattice::points_within(double radius) const {
  std::vector<Vec> out;
  double shortest = 1e300;
  for (const auto& b : basis_) shortest = std::min(shortest, std::sqrt(dot(b, b)));
  // A generous coefficient range for the nearly orthogonal bases boxgen's lattices have.
  const int range = static_cast<int>(std::ceil(radius / shortest)) * 3 + 2;
  std::vector<std::int64_t> c(n_, -range);
  while (true) {
    const Vec p = point(c);
    if (dot(p, p) <= radius * radius) out.push_back(p);
    int i = 0;
    while (i < n_ && c[i] == range) c[i++] = -range;
    if (i == n_) break;
    ++c[i];
  }
  return out;
}

Vec DualLattice::nearest(const Vec& w, double* gap) const {
  // Search the coefficients around those of w in the dual basis (enough for the nearly
  // orthogonal bases of bcc, fcc and cartesian; images only need the boundaries).
  double best = 1e300, second = 1e300;
  Vec best_point{0, 0, 0};
  // Solve basis^T-system: sum c_i basis_i = w  (n x n).
  std::vector<Vec> a(n_);
  for (int r = 0; r < n_; ++r)
    for (int i = 0; i < n_; ++i) a[r][i] = basis_[i][r];
  std::vector<double> rhs(w.begin(), w.begin() + n_);
  Vec c{0, 0, 0};
  solve_small(a, rhs, n_, c);
  const int reach = 2;
  std::vector<std::int64_t> k(n_), lo(n_);
  for (int i = 0; i < n_; ++i) lo[i] = static_cast<std::int64_t>(std::floor(c[i])) - reach;
  std::vector<int> off(n_, 0);
  while (true) {
    for (int i = 0; i < n_; ++i) k[i] = lo[i] + off[i];
    const Vec p = point(k);
    const Vec d = sub(w, p);
    const double dist = std::sqrt(dot(d, d));
    if (dist < best) {
      second = best;
      best = dist;
      best_point = p;
    } else if (dist < second) {
      second = dist;
    }
    int i = 0;
    while (i < n_ && off[i] == 2 * reach + 1) off[i++] = 0;
    if (i == n_) break;
    ++off[i];
  }
  if (gap) *gap = second - best;
  return best_point;
}

}  // namespace boxgen::analysis
