#include "generator/lattice.h"

#include <algorithm>
#include <cstdlib>
#include <map>

#include "generator/error.h"
#include "support/integer_math.h"

namespace boxgen::generator {

namespace {

using support::floor_div;

// Column-style Hermite normal form: unimodular column operations make G lower triangular
// with a positive diagonal.
IntColumns hermite_form(IntColumns h, int n) {
  for (int row = 0; row < n; ++row) {
    // Euclid on entries h[row..n-1][row] until only column `row` is nonzero in this row.
    for (;;) {
      int best = -1;
      for (int j = row; j < n; ++j)
        if (h[j][row] != 0 && (best < 0 || std::llabs(h[j][row]) < std::llabs(h[best][row])))
          best = j;
      if (best < 0) fail_internal("hermite_form: singular lattice");
      std::swap(h[best], h[row]);
      bool done = true;
      for (int j = row + 1; j < n; ++j) {
        if (h[j][row] == 0) continue;
        std::int64_t q = h[j][row] / h[row][row];
        for (int i = 0; i < n; ++i) h[j][i] -= q * h[row][i];
        if (h[j][row] != 0) done = false;
      }
      if (done) break;
    }
    if (h[row][row] < 0)
      for (int i = 0; i < n; ++i) h[row][i] = -h[row][i];
  }
  return h;
}

}  // namespace

Lattice::Lattice(std::string name, IntColumns generator)
    : name_(std::move(name)), g_(std::move(generator)) {
  n_ = static_cast<int>(g_.size());
  if (n_ < 2 || n_ > 3)
    fail_input("lattice must be 2- or 3-dimensional, got dimension " + std::to_string(n_));
  for (const auto& c : g_)
    if (static_cast<int>(c.size()) != n_) fail_input("lattice generator must be square");
  for (const auto& c : g_)
    for (auto v : c)
      if (std::llabs(v) > 1000)
        fail_input("lattice generator entries must be at most 1000 in magnitude");
  std::int64_t d = det(g_);
  if (d == 0) fail_input("singular lattice: the generator matrix has determinant 0");
  det_abs_ = std::llabs(d);
  hermite_ = hermite_form(g_, n_);
}

Lattice Lattice::cartesian(int n) {
  IntColumns g(n, IntVec(n, 0));
  for (int i = 0; i < n; ++i) g[i][i] = 1;
  return Lattice("cartesian", g);
}

Lattice Lattice::bcc() { return Lattice("bcc", {{-1, 1, 1}, {1, -1, 1}, {1, 1, -1}}); }

Lattice Lattice::fcc() { return Lattice("fcc", {{1, 1, 0}, {1, 0, 1}, {0, 1, 1}}); }

IntColumns Lattice::generator_rows() const {
  IntColumns rows(n_, IntVec(n_));
  for (int i = 0; i < n_; ++i)
    for (int j = 0; j < n_; ++j) rows[i][j] = g_[j][i];
  return rows;
}

IntVec Lattice::reduce(const IntVec& x) const {
  IntVec r = x;
  for (int j = 0; j < n_; ++j) {
    std::int64_t q = floor_div(r[j], hermite_[j][j]);
    if (q != 0)
      for (int i = 0; i < n_; ++i) r[i] -= q * hermite_[j][i];
  }
  return r;
}

bool Lattice::contains(const IntVec& x) const {
  IntVec r = reduce(x);
  return std::all_of(r.begin(), r.end(), [](std::int64_t v) { return v == 0; });
}

std::vector<IntVec> Lattice::coset_representatives() const {
  std::vector<IntVec> reps{IntVec(n_, 0)};
  for (int j = 0; j < n_; ++j) {
    std::vector<IntVec> next;
    for (const auto& r : reps)
      for (std::int64_t a = 0; a < hermite_[j][j]; ++a) {
        IntVec v = r;
        v[j] = a;
        next.push_back(v);
      }
    reps = std::move(next);
  }
  std::sort(reps.begin(), reps.end());
  return reps;
}

std::vector<IntVec> Lattice::points_in_box(const IntVec& lo, const IntVec& hi) const {
  // x = sum_j z_j h_j with the lower-triangular Hermite basis: x_i depends on z_0..z_i only, so
  // each z_i runs over exactly the range that keeps x_i in [lo_i, hi_i] (the work follows the
  // points found, not the box: a scaled lattice k L has few points in a large box).
  std::vector<IntVec> out;
  IntVec z(n_, 0), x(n_, 0);
  auto visit = [&](auto& self, int i) -> void {
    if (i == n_) {
      out.push_back(x);
      return;
    }
    std::int64_t partial = 0;  // x_i without the term of z_i
    for (int j = 0; j < i; ++j) partial += z[j] * hermite_[j][i];
    const std::int64_t h = hermite_[i][i];
    for (z[i] = -floor_div(partial - lo[i], h); partial + z[i] * h <= hi[i]; ++z[i]) {
      x[i] = partial + z[i] * h;
      self(self, i + 1);
    }
  };
  visit(visit, 0);
  // The order of a scan with x_0 fastest (callers' stencils and emitted tables follow it).
  std::sort(out.begin(), out.end(), [this](const IntVec& a, const IntVec& b) {
    for (int i = n_ - 1; i >= 0; --i)
      if (a[i] != b[i]) return a[i] < b[i];
    return false;
  });
  return out;
}

std::vector<std::vector<IntVec>> Lattice::shells(int count) const {
  // Grow a box until it holds `count` complete shells (points of norm <= r^2 lie in [-r, r]^n).
  for (std::int64_t r = 2;; r *= 2) {
    IntVec lo(n_, -r), hi(n_, r);
    std::map<std::int64_t, std::vector<IntVec>> by_norm;
    for (const auto& p : points_in_box(lo, hi)) by_norm[dot(p, p)].push_back(p);
    std::vector<std::vector<IntVec>> out;
    for (auto& [norm, pts] : by_norm) {
      if (norm > r * r) break;  // beyond this radius the box may miss points
      out.push_back(pts);
      if (static_cast<int>(out.size()) == count) return out;
    }
    if (r > 4096) fail_input("too many shells requested");
  }
}

}  // namespace boxgen::generator
