// Reconstruction with ANY emitted evaluator on a volume of its lattice: the filters of
// generated/registry.hpp and a user's own `boxgen emit` / boxgen_emit() header alike. The class is
// a template on the evaluator's Traits (the struct every emitted header defines, see
// generated/evaluator_support.hpp), so nothing here lists filters or knows a coefficient.
//
//   #include "my_filter.hpp"              // boxgen emit "<your matrix>" --name my_filter
//   #include "my_filter_prefilters.hpp"
//   LatticeVolume<double> v = sample_lattice<double>(f,
//   cube_lattice_grid(filter_lattice<my_filter::Traits>(), 33, 4)); v = prefilter(v,
//   prefilter_from(my_filter::q1)); LatticeReconstructor<my_filter::Traits, double> r(v); double s
//   = r.value({0.1, 0.2, 0.3});
//
// The filter's lattice is read from the evaluator's Hermite basis (Traits::kHermite); a volume
// on another lattice is refused with one line (std::invalid_argument). Border policy as
// Reconstructor (reconstruction.h): a point whose stencil leaves the volume is
// std::out_of_range (one line), a non-finite coordinate std::invalid_argument; the whole stencil
// box is checked once per point, then fetched without further checks, through linear offsets
// precomputed per volume (see table_ below).
#pragma once
#include <fmt/format.h>

#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <span>
#include <stdexcept>
#include <vector>

#include "generated/evaluator_support.hpp"
#include "runtime/coset_lattice.h"
#include "runtime/lattice_volume.h"
#include "runtime/prefilter.h"

namespace boxgen::runtime {

// The lattice an emitted evaluator was derived on: its Hermite basis holds the columns of G.
template <class Tr>
CosetLattice filter_lattice() {
  static_assert(Tr::kDimension == 3, "volumes are 3-D");
  IntRows rows{};
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c) rows[r][c] = Tr::kHermite[c][r];
  return CosetLattice::from_rows(rows);
}

// An emitted prefilter table (q1 or q2 of a *_prefilters.hpp) as taps for prefilter().
template <class Tap, std::size_t N>
DiscreteFilter prefilter_from(const Tap (&table)[N]) {
  DiscreteFilter out;
  for (const auto& t : table) out.push_back({{t.offset[0], t.offset[1], t.offset[2]}, t.weight});
  return out;
}

// Do two lattices hold the same points (whatever the order of their cosets)?
inline bool same_points(const CosetLattice& a, const CosetLattice& b) {
  if (a.period() != b.period() || a.determinant() != b.determinant()) return false;
  for (const Offset& o : a.offsets())
    if (!b.contains(o[0], o[1], o[2])) return false;
  return true;
}

template <class Tr, class T>
class LatticeReconstructor {
  static_assert(Tr::kDimension == 3, "volumes are 3-D");
  static constexpr int kStencil = Tr::kStencilSize;

 public:
  // Throws std::invalid_argument (one line) if the volume is not on the filter's lattice.
  explicit LatticeReconstructor(const LatticeVolume<T>& volume) : volume_(volume) {
    const CosetLattice lattice = filter_lattice<Tr>();
    if (!same_points(lattice, volume.lattice()))
      throw std::invalid_argument(
          fmt::format("filter {} is for the {} lattice, but the volume is on the {} lattice",
                      Tr::kName, lattice.name(), volume.lattice().name()));
    tabulate_offsets();
  }

  // The spline at a world point; with `gradient` its gradient and with `hessian` its second
  // derivatives {xx, xy, xz, yy, yz, zz}, in world units.
  T value(const Vec3& world, Vec3* gradient = nullptr,
          std::array<double, 6>* hessian = nullptr) const {
    if (hessian) return point<generated::support::kHessian>(world, gradient, hessian);
    if (gradient) return point<generated::support::kGradient>(world, gradient, nullptr);
    return point<generated::support::kValue>(world, nullptr, nullptr);
  }

  // value() for many points (`gradients` empty: values only). Throws the first error.
  void evaluate(std::span<const Vec3> points, std::span<T> values,
                std::span<Vec3> gradients = {}) const {
    if (values.size() != points.size() || (!gradients.empty() && gradients.size() != points.size()))
      throw std::invalid_argument("evaluate: values and gradients must be as long as points");
    for (std::size_t i = 0; i < points.size(); ++i)
      values[i] = value(points[i], gradients.empty() ? nullptr : &gradients[i]);
  }

 private:
  template <int Order>
  T point(const Vec3& world, Vec3* gradient, std::array<double, 6>* hessian) const {
    namespace support = generated::support;
    for (double c : world)
      if (!std::isfinite(c)) throw std::invalid_argument("point has a non-finite coordinate");
    const Vec3 lattice = volume_.to_lattice(world);
    // Far outside, stop before floor(x) becomes an integer that could overflow.
    constexpr double kFar = 64;
    for (int a = 0; a < 3; ++a)
      if (!(lattice[a] > -kFar &&
            lattice[a] < static_cast<double>(volume_.period()) * (volume_.sizes()[a] + 1) + kFar))
        throw std::out_of_range(fmt::format("world point ({}, {}, {}) is outside the volume",
                                            world[0], world[1], world[2]));
    const std::array<T, 3> x{static_cast<T>(lattice[0]), static_cast<T>(lattice[1]),
                             static_cast<T>(lattice[2])};
    const support::Located<3, T> located = support::locate<Tr>(x);
    const int size = Tr::kOrbitStencilSize[Tr::kCells[located.cell].orbit];
    T v[kStencil];
    LatticePoint lo, hi;
    for (int a = 0; a < 3; ++a) {
      lo[a] = located.corner[a] + Tr::kStencilReachLo[a];
      hi[a] = located.corner[a] + Tr::kStencilReachHi[a];
    }
    const bool inside = volume_.contains_box(lo, hi);
    if (inside && !table_.empty()) {
      // corner = d q + r, 0 <= r < d per axis: the block q's first sample, plus the table's
      // offset for the residue class r and the cell.
      const std::int64_t d = volume_.period();
      std::int64_t q[3];
      int residue = 0;
      for (int a = 2; a >= 0; --a) {
        const std::int64_t c = located.corner[a];
        const std::int64_t r = ((c % d) + d) % d;
        q[a] = (c - r) / d;
        residue = residue * static_cast<int>(d) + static_cast<int>(r);
      }
      const std::int64_t base =
          volume_.coset_count() *
          (q[0] +
           volume_.sizes()[0] * (q[1] + static_cast<std::int64_t>(volume_.sizes()[1]) * q[2]));
      const T* samples = volume_.samples().data();
      const std::int64_t* offsets =
          &table_[(static_cast<std::size_t>(residue) * Tr::kCellCount + located.cell) * kStencil];
      for (int k = 0; k < size; ++k) v[k] = samples[base + offsets[k]];
    } else {
      fetch_checked(located, world, inside, size, v);
    }
    T d[3 + 6] = {};
    const T value = support::evaluate_located<Order, Tr>(located, v, d);
    const double h = volume_.spacing();
    if constexpr (Order >= support::kGradient)
      if (gradient)
        for (int i = 0; i < 3; ++i) (*gradient)[i] = static_cast<double>(d[i]) / h;
    if constexpr (Order >= support::kHessian)
      for (int i = 0; i < 6; ++i) (*hessian)[i] = static_cast<double>(d[3 + i]) / (h * h);
    return value;
  }

  // The stencil through the volume's lattice lookup: unchecked when `inside`, else every sample
  // checked (a sample outside is std::out_of_range naming the point).
  void fetch_checked(const generated::support::Located<3, T>& located, const Vec3& world,
                     bool inside, int size, T* v) const {
    try {
      for (int k = 0; k < size; ++k) {
        LatticePoint j;
        for (int a = 0; a < 3; ++a) j[a] = located.corner[a] + Tr::kOffsets[located.cell][k][a];
        v[k] = inside ? volume_.value_unchecked(j) : volume_.value(j);
      }
    } catch (const std::out_of_range& e) {  // name the point the user asked for, then the sample
      throw std::out_of_range(
          fmt::format("world point ({}, {}, {}) needs a sample outside the volume: {}", world[0],
                      world[1], world[2], e.what()));
    }
  }

  // table_[(r, cell, k)]: for a corner of residue class r (corner mod d per axis, x fastest,
  // r = rx + d (ry + d rz)) in block q (corner = d q + r), the stencil sample
  // j = corner + kOffsets[cell][k] = d q + p, p = r + offset, lies in coset c of p at
  // (i, j, k) = q + (p - off_c) / d (an exact division): storage index K (q_x + N0 (q_y + N1 q_z))
  // plus c + K ((p - off_c)_x / d + N0 (...)), the table's entry. Left empty (every fetch through
  // the lattice lookup) when the table would be large (a custom lattice of large period).
  void tabulate_offsets() {
    const CosetLattice& lattice = volume_.lattice();
    const std::int64_t d = lattice.period(), k_cosets = lattice.coset_count();
    const std::int64_t n0 = volume_.sizes()[0], n1 = volume_.sizes()[1];
    constexpr std::int64_t kMaxEntries = std::int64_t{1} << 22;
    if (d * d * d * Tr::kCellCount * kStencil > kMaxEntries) return;
    std::vector<std::int64_t> table(static_cast<std::size_t>(d * d * d) * Tr::kCellCount *
                                    kStencil);
    auto floor_div = [](std::int64_t a, std::int64_t b) {
      const std::int64_t q = a / b;
      return (a % b != 0 && a < 0) ? q - 1 : q;
    };
    std::size_t at = 0;
    for (std::int64_t rz = 0; rz < d; ++rz)
      for (std::int64_t ry = 0; ry < d; ++ry)
        for (std::int64_t rx = 0; rx < d; ++rx)
          for (int cell = 0; cell < Tr::kCellCount; ++cell)
            for (int k = 0; k < kStencil; ++k, ++at) {
              if (k >= Tr::kOrbitStencilSize[Tr::kCells[cell].orbit]) continue;  // never read
              const auto& o = Tr::kOffsets[cell][k];
              const std::int64_t p[3] = {rx + o[0], ry + o[1], rz + o[2]};
              const int c = lattice.coset_of(p[0], p[1], p[2]);
              // Not a lattice point: a cell of another cube type than this residue class has
              // (locate never pairs them; the lookup path assumes the same). Never read.
              if (c < 0) continue;
              const Offset& off = lattice.offsets()[static_cast<std::size_t>(c)];
              const std::int64_t i = floor_div(p[0] - off[0], d), j = floor_div(p[1] - off[1], d),
                                 l = floor_div(p[2] - off[2], d);
              table[at] = c + k_cosets * (i + n0 * (j + n1 * l));
            }
    table_ = std::move(table);
  }

  const LatticeVolume<T>& volume_;
  std::vector<std::int64_t> table_;
};

}  // namespace boxgen::runtime
