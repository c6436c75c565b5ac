#include "runtime/coset_lattice.h"

#include <fmt/format.h>

#include <algorithm>
#include <numeric>
#include <set>
#include <stdexcept>

#include "runtime/lattice_limits.h"

namespace boxgen::runtime {

namespace {

std::int64_t det3(const IntRows& g) {
  return g[0][0] * (g[1][1] * g[2][2] - g[1][2] * g[2][1]) -
         g[0][1] * (g[1][0] * g[2][2] - g[1][2] * g[2][0]) +
         g[0][2] * (g[1][0] * g[2][1] - g[1][1] * g[2][0]);
}

// adj(G) = det(G) G^{-1}: p = G z has z = adj(G) p / det(G).
IntRows adjugate(const IntRows& g) {
  IntRows a{};
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) {
      const int r0 = (j + 1) % 3, r1 = (j + 2) % 3, c0 = (i + 1) % 3, c1 = (i + 2) % 3;
      a[i][j] = g[r0][c0] * g[r1][c1] -
                g[r0][c1] * g[r1][c0];  // cofactor of (j, i), signs by the cyclic order
    }
  return a;
}

}  // namespace

CosetLattice CosetLattice::bcc() {
  CosetLattice l;
  l.name_ = "bcc";
  l.rows_ = {{{-1, 1, 1}, {1, -1, 1}, {1, 1, -1}}};
  l.d_ = 2;
  l.det_ = 4;
  l.offsets_ = {{0, 0, 0}, {1, 1, 1}};
  l.tabulate();
  return l;
}

CosetLattice CosetLattice::fcc() {
  CosetLattice l;
  l.name_ = "fcc";
  l.rows_ = {{{1, 1, 0}, {1, 0, 1}, {0, 1, 1}}};
  l.d_ = 2;
  l.det_ = 2;
  l.offsets_ = {{0, 0, 0}, {1, 1, 0}, {1, 0, 1}, {0, 1, 1}};
  l.tabulate();
  return l;
}

CosetLattice CosetLattice::cartesian() {
  CosetLattice l;
  l.name_ = "cartesian";
  l.rows_ = {{{1, 0, 0}, {0, 1, 0}, {0, 0, 1}}};
  l.d_ = 1;
  l.det_ = 1;
  l.offsets_ = {{0, 0, 0}};
  l.tabulate();
  return l;
}

CosetLattice CosetLattice::from_rows(const IntRows& rows) {
  for (const auto& row : rows)
    for (std::int64_t v : row)
      if (v < -kMaxLatticeEntry || v > kMaxLatticeEntry)
        throw std::invalid_argument(fmt::format(
            "lattice matrix entry {} is too large (at most {} in magnitude)", v, kMaxLatticeEntry));
  const std::int64_t det = det3(rows);
  if (det == 0)
    throw std::invalid_argument("the lattice matrix is singular (its rows do not span 3-D space)");
  const std::int64_t det_abs = det < 0 ? -det : det;
  const IntRows adj = adjugate(rows);
  std::int64_t g = det_abs;
  for (const auto& row : adj)
    for (std::int64_t v : row) g = std::gcd(g, v);
  const std::int64_t d = det_abs / g;  // the smallest d with d adj(G) = 0 (mod det)
  if (d > kMaxPeriod)
    throw std::invalid_argument(
        fmt::format("the lattice's coset period d = {} exceeds {} (d^3 residues are tabulated)", d,
                    kMaxPeriod));

  CosetLattice l;
  l.rows_ = rows;
  l.d_ = static_cast<int>(d);
  l.det_ = det_abs;
  for (int z = 0; z < d; ++z)
    for (int y = 0; y < d; ++y)
      for (int x = 0; x < d; ++x) {
        bool member = true;
        for (int i = 0; i < 3 && member; ++i)
          member = (adj[i][0] * x + adj[i][1] * y + adj[i][2] * z) % det == 0;
        if (member) l.offsets_.push_back({x, y, z});
      }
  l.tabulate();
  // The named lattices keep their documented offsets and order.
  for (const CosetLattice& named : {bcc(), fcc(), cartesian()})
    if (named.d_ == l.d_ && named.det_ == l.det_ &&
        std::all_of(named.offsets_.begin(), named.offsets_.end(),
                    [&](const Offset& o) { return l.contains(o[0], o[1], o[2]); })) {
      CosetLattice same = named;
      same.rows_ = rows;
      return same;
    }
  l.name_ = "custom";
  return l;
}

CosetLattice CosetLattice::with_offsets(const std::vector<Offset>& offsets) const {
  if (offsets.size() != offsets_.size())
    throw std::invalid_argument(
        fmt::format("{} coset offsets given; the lattice has {} cosets of {} Z^3", offsets.size(),
                    offsets_.size(), d_));
  std::set<int> seen;
  for (const Offset& o : offsets) {
    for (int v : o)
      if (v < -kMaxLatticeEntry || v > kMaxLatticeEntry)
        throw std::invalid_argument(fmt::format("coset offset coordinate {} is too large", v));
    const int c = coset_of(o[0], o[1], o[2]);
    if (c < 0)
      throw std::invalid_argument(
          fmt::format("coset offset ({},{},{}) is not a lattice point", o[0], o[1], o[2]));
    if (!seen.insert(c).second)
      throw std::invalid_argument(
          fmt::format("coset offset ({},{},{}) lies in the same coset of {} Z^3 as another", o[0],
                      o[1], o[2], d_));
  }
  CosetLattice l = *this;
  l.offsets_ = offsets;
  l.tabulate();
  return l;
}

void CosetLattice::tabulate() {
  table_.assign(static_cast<std::size_t>(d_) * d_ * d_, -1);
  for (std::size_t c = 0; c < offsets_.size(); ++c) {
    const Offset& o = offsets_[c];
    table_[index_of(residue(o[0]), residue(o[1]), residue(o[2]))] = static_cast<int>(c);
  }
}

std::string CosetLattice::label() const {
  if (name_ == "bcc" || name_ == "fcc") return name_ == "bcc" ? "BCC" : "FCC";
  return name_ == "cartesian" ? "Cartesian" : name_;
}

std::string CosetLattice::rows_text() const {
  return fmt::format("{},{},{}; {},{},{}; {},{},{}", rows_[0][0], rows_[0][1], rows_[0][2],
                     rows_[1][0], rows_[1][1], rows_[1][2], rows_[2][0], rows_[2][1], rows_[2][2]);
}

std::string CosetLattice::offsets_text() const {
  std::string text;
  for (const Offset& o : offsets_)
    text += fmt::format("{}({},{},{})", text.empty() ? "" : " ", o[0], o[1], o[2]);
  return text;
}

bool same_points(const CosetLattice& a, const CosetLattice& b) {
  if (a.period() != b.period() || a.determinant() != b.determinant()) return false;
  for (const Offset& o : a.offsets())
    if (!b.contains(o[0], o[1], o[2])) return false;
  return true;
}

}  // namespace boxgen::runtime
