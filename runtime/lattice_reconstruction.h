// Reconstruction with ANY emitted evaluator on a volume of its lattice: the filters of
// generated/registry.hpp and a user's own `boxgen emit` / boxgen_emit() header alike. The class is
// a template on the evaluator's Traits (the struct every emitted header defines, see
// support/evaluator_support.hpp), so nothing here lists filters or knows a coefficient.
//
// Example (a header from `boxgen emit "<your matrix>" --name my_filter`, and its prefilters):
//   auto v = sample_lattice<double>(f, cube_lattice_grid(filter_lattice<my_filter::Traits>(),
//                                                         33, 4));
//   v = prefilter(v, prefilter_from(my_filter::q1));
//   LatticeReconstructor<my_filter::Traits, double> r(v);
//   double s = r.value({0.1, 0.2, 0.3});
//
// The filter's lattice is read from the evaluator's Hermite basis (Traits::kHermite); a volume
// on another lattice is refused with one line (std::invalid_argument). Evaluation is the
// runtime's one engine, EmittedSpline (emitted_spline.h), with this volume's LatticeStencils:
// border policy, threads and the SIMD batch path as for Reconstructor (reconstruction.h).
#pragma once
#include <fmt/format.h>

#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <span>
#include <stdexcept>
#include <vector>

#include "runtime/coset_lattice.h"
#include "runtime/emitted_spline.h"
#include "runtime/lattice_volume.h"
#include "runtime/prefilter.h"
#include "support/evaluator_support.hpp"

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

// Where the stencil of a point lies in a LatticeVolume (emitted_spline.h says what a Stencils
// provides). table_[(r, cell, k)]: for a corner of residue class r (corner mod d per axis, x
// fastest, r = rx + d (ry + d rz)) in block q (corner = d q + r), the stencil sample
// j = corner + kOffsets[cell][k] = d q + p, p = r + offset, lies in coset c of p at
// (i, j, k) = q + (p - off_c) / d (an exact division): storage index K (q_x + N0 (q_y + N1 q_z))
// plus c + K ((p - off_c)_x / d + N0 (...)), the table's entry. Left empty (every fetch through
// the lattice lookup) when the table would be large (a custom lattice of large period).
// Throws std::invalid_argument (one line) unless `volume_lattice` holds the points of the lattice
// the evaluator was derived on.
template <class Tr>
void require_filter_lattice(const CosetLattice& volume_lattice) {
  const CosetLattice lattice = filter_lattice<Tr>();
  if (!same_points(lattice, volume_lattice))
    throw std::invalid_argument(
        fmt::format("filter {} is for the {} lattice, but the volume is on the {} lattice",
                    Tr::kName, lattice.name(), volume_lattice.name()));
}

template <class Tr, class T>
class LatticeStencils {
 public:
  using Sample = T;
  using Index = std::int64_t;

  explicit LatticeStencils(const LatticeVolume<T>& volume) : volume_(&volume) { tabulate(); }

  const LatticeVolume<T>& volume() const { return *volume_; }
  // The samples' lattice coordinates lie in [0, d N_a - 1]: coset offsets lie in [0, d)^3.
  double extent(int a) const {
    return static_cast<double>(volume_->period()) * (volume_->sizes()[a] + 1);
  }
  double last(int a) const {
    return static_cast<double>(volume_->period()) * volume_->sizes()[a] - 1;
  }
  bool has_offsets() const { return !table_.empty(); }
  const T* samples() const { return volume_->samples().data(); }
  Fetch<Index> fetch(const std::int64_t* corner, int cell) const {
    // corner = d q + r, 0 <= r < d per axis: the block q's first sample, plus the table's
    // offset for the residue class r and the cell.
    const std::int64_t d = volume_->period();
    std::int64_t q[3];
    std::int64_t residue = 0;
    for (int a = 2; a >= 0; --a) {
      const std::int64_t r = ((corner[a] % d) + d) % d;
      q[a] = (corner[a] - r) / d;
      residue = residue * d + r;
    }
    const std::int64_t base =
        volume_->coset_count() *
        (q[0] +
         volume_->sizes()[0] * (q[1] + static_cast<std::int64_t>(volume_->sizes()[1]) * q[2]));
    return {base, &table_[(static_cast<std::size_t>(residue) * Tr::kCellCount +
                           static_cast<std::size_t>(cell)) *
                          Tr::kStencilSize]};
  }
  T sample(const LatticePoint& j, bool inside) const {
    return inside ? volume_->value_unchecked(j) : volume_->value(j);
  }

 private:
  void tabulate() {
    const CosetLattice& lattice = volume_->lattice();
    const std::int64_t d = lattice.period(), k_cosets = lattice.coset_count();
    const std::int64_t n0 = volume_->sizes()[0], n1 = volume_->sizes()[1];
    constexpr std::int64_t kMaxEntries = std::int64_t{1} << 22;
    if (d * d * d * Tr::kCellCount * Tr::kStencilSize > kMaxEntries) return;
    std::vector<std::int64_t> table(static_cast<std::size_t>(d * d * d) * Tr::kCellCount *
                                    Tr::kStencilSize);
    auto floor_div = [](std::int64_t a, std::int64_t b) {
      const std::int64_t q = a / b;
      return (a % b != 0 && a < 0) ? q - 1 : q;
    };
    std::size_t at = 0;
    for (std::int64_t rz = 0; rz < d; ++rz)
      for (std::int64_t ry = 0; ry < d; ++ry)
        for (std::int64_t rx = 0; rx < d; ++rx)
          for (int cell = 0; cell < Tr::kCellCount; ++cell)
            for (int k = 0; k < Tr::kStencilSize; ++k, ++at) {
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

  const LatticeVolume<T>* volume_;
  std::vector<std::int64_t> table_;
};

template <class Tr, class T>
class LatticeReconstructor {
  static_assert(Tr::kDimension == 3, "volumes are 3-D");

 public:
  // Throws std::invalid_argument (one line) if the volume is not on the filter's lattice.
  explicit LatticeReconstructor(const LatticeVolume<T>& volume) : spline_(checked(volume)) {}

  // The spline at a world point; with `gradient` its gradient and with `hessian` its second
  // derivatives {xx, xy, xz, yy, yz, zz}, in world units.
  T value(const Vec3& world, Vec3* gradient = nullptr, Hessian* hessian = nullptr) const {
    return spline_.at(world, gradient, hessian);
  }

  // value() for many points on up to batch_threads() threads (the registry's filters take the
  // SIMD batch path through RegistryReconstructor, lattice_filters.h). `gradients` and
  // `hessians` empty (not computed) or as long as `points`; hessians need gradients. Throws the
  // first error, naming the point's index (from 1).
  void evaluate(std::span<const Vec3> points, std::span<T> values, std::span<Vec3> gradients = {},
                std::span<Hessian> hessians = {}) const {
    spline_.batch(points, values, gradients, hessians);
  }

 private:
  static LatticeStencils<Tr, T> checked(const LatticeVolume<T>& volume) {
    require_filter_lattice<Tr>(volume.lattice());
    return LatticeStencils<Tr, T>(volume);
  }

  EmittedSpline<Tr, LatticeStencils<Tr, T>> spline_;
};

}  // namespace boxgen::runtime
