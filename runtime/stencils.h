// Where the stencil of a point lies in a LatticeVolume's storage: the Stencils policies of the
// engine (emitted_spline.h says what one provides). EmittedFilter (emitted_filter.h) picks one
// per volume: BccStencils on BCC volumes with the offsets (0,0,0) (1,1,1), LatticeStencils on
// every other lattice.
#pragma once
#include <algorithm>
#include <array>
#include <bit>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <optional>
#include <vector>

#include "runtime/lattice_volume.h"

namespace boxgen::runtime {

// Where a volume keeps lattice point j when its storage is linear up to the coset parity: at
// j . stride - (j_0 & 1) coset_shift. BCC volumes with the cosets (0,0,0) (1,1,1) are (coset_shift
// N0 + N0 N1), and so are Cartesian ones (coset_shift 0); the SIMD path then computes every
// stencil index in vector lanes and gathers with the vector unit (simd_batch.h, LinearVolume).
struct LinearLayout {
  std::int64_t stride[3];
  std::int64_t coset_shift;
};

// A point's stencil in storage: sample k is samples()[base + offsets[k]].
template <class Offset>
struct Fetch {
  std::int64_t base;
  const Offset* offsets;
};

// Any lattice. table_[(r, cell, k)]: for a corner of residue class r (corner mod d per axis, x
// fastest, r = rx + d (ry + d rz)) in block q (corner = d q + r), the stencil sample
// j = corner + kOffsets[cell][k] = d q + p, p = r + offset, lies in coset c of p at
// (i, j, k) = q + (p - off_c) / d (an exact division): storage index K (q_x + N0 (q_y + N1 q_z))
// plus c + K ((p - off_c)_x / d + N0 (...)), the table's entry. Left empty (every fetch through
// the lattice lookup) when the table would be large (a custom lattice of large period).
template <class Tr, class T>
class LatticeStencils {
 public:
  using Sample = T;
  using Index = std::int64_t;

  explicit LatticeStencils(const LatticeVolume<T>& volume) : volume_(&volume) {
    const auto d = static_cast<std::uint64_t>(volume.period());
    if (std::has_single_bit(d)) period_shift_ = std::countr_zero(d);
    tabulate();
  }

  const LatticeVolume<T>& volume() const { return *volume_; }
  // The samples' lattice coordinates lie in [0, d N_a - 1]: coset offsets lie in [0, d)^3.
  double extent(int a) const {
    return static_cast<double>(volume_->period()) * (volume_->sizes()[a] + 1);
  }
  double last(int a) const {
    return static_cast<double>(volume_->period()) * volume_->sizes()[a] - 1;
  }
  bool contains_box(const LatticePoint& lo, const LatticePoint& hi) const {
    return volume_->contains_box(lo, hi);
  }
  bool has_offsets() const { return !table_.empty(); }
  // A Cartesian volume's storage is linear: j . (1, N0, N0 N1).
  std::optional<LinearLayout> linear() const {
    if (volume_->period() != 1) return std::nullopt;
    const std::int64_t origin = volume_->storage_offset({0, 0, 0});
    if (origin != 0) return std::nullopt;
    return LinearLayout{{volume_->storage_offset({1, 0, 0}), volume_->storage_offset({0, 1, 0}),
                         volume_->storage_offset({0, 0, 1})},
                        0};
  }
  const T* samples() const { return volume_->samples().data(); }
  Fetch<Index> fetch(const std::int64_t* corner, int cell) const {
    // corner = d q + r, 0 <= r < d per axis: the block q's first sample, plus the table's
    // offset for the residue class r and the cell.
    const std::int64_t d = volume_->period();
    std::int64_t q[3];
    std::int64_t residue = 0;
    for (int a = 2; a >= 0; --a) {
      // Every registry lattice has a period that is a power of two (Cartesian 1, BCC and FCC
      // 2): a mask and a shift (which floors in C++20) instead of two divisions per axis.
      const std::int64_t r = period_shift_ >= 0 ? corner[a] & (d - 1) : ((corner[a] % d) + d) % d;
      q[a] = period_shift_ >= 0 ? corner[a] >> period_shift_ : (corner[a] - r) / d;
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
    const std::int64_t d = lattice.period();
    constexpr std::int64_t kMaxEntries = std::int64_t{1} << 22;
    if (d * d * d * Tr::kCellCount * Tr::kStencilSize > kMaxEntries) return;
    std::vector<std::int64_t> table(static_cast<std::size_t>(d * d * d) * Tr::kCellCount *
                                    Tr::kStencilSize);
    std::size_t at = 0;
    for (std::int64_t rz = 0; rz < d; ++rz)
      for (std::int64_t ry = 0; ry < d; ++ry)
        for (std::int64_t rx = 0; rx < d; ++rx)
          for (int cell = 0; cell < Tr::kCellCount; ++cell)
            for (int k = 0; k < Tr::kStencilSize; ++k, ++at) {
              if (k >= Tr::kOrbitStencilSize[Tr::kCells[cell].orbit]) continue;  // never read
              const auto& o = Tr::kOffsets[cell][k];
              const LatticePoint p = {rx + o[0], ry + o[1], rz + o[2]};
              // Not a lattice point: a cell of another cube type than this residue class has
              // (locate never pairs them; the lookup path assumes the same). Never read.
              if (!lattice.contains(p[0], p[1], p[2])) continue;
              table[at] = volume_->storage_offset(p);  // relative to block q = 0
            }
    table_ = std::move(table);
  }

  const LatticeVolume<T>* volume_;
  int period_shift_ = -1;  // log2 of the period where it is a power of two, else -1
  std::vector<std::int64_t> table_;
};

// BCC volumes with the offsets (0,0,0) (1,1,1): offsets into samples() precomputed per cell and
// per parity of the corner's x, and the box check by parity (each parity class fills
// 0..2N-1). Offset is std::int32_t where every offset fits (a smaller table stays in the L1
// cache), else std::int64_t.
template <class Tr, class T, class O>
class BccStencils {
 public:
  using Sample = T;
  using Index = O;

  explicit BccStencils(const LatticeVolume<T>& volume) : volume_(&volume) {
    // Sample (x, y, z) sits at x + N0 y + N0 N1 z - c (N0 + N0 N1), c = x & 1 its coset: linear
    // in the point apart from the coset term. For j = corner + d the coset is
    // (corner_x & 1) ^ (d_x & 1), so one table per corner parity.
    const std::int64_t n0 = volume.sizes()[0], n1 = volume.sizes()[1];
    stride_ = {1, n0, n0 * n1};
    const std::int64_t coset_shift = n0 + n0 * n1;
    offsets_.resize(2 * Tr::kCellCount * Tr::kStencilSize);
    for (int parity = 0; parity < 2; ++parity)
      for (int cell = 0; cell < Tr::kCellCount; ++cell)
        for (int k = 0; k < Tr::kStencilSize; ++k) {
          const auto& d = Tr::kOffsets[cell][k];
          const int coset = parity ^ (d[0] & 1);
          offsets_[(parity * Tr::kCellCount + cell) * Tr::kStencilSize + k] =
              static_cast<O>(d[0] + n0 * d[1] + n0 * n1 * d[2] - coset * coset_shift);
        }
  }

  // Do all offsets fit in O for a volume of these sizes? |offset| <= (max reach + 1) (1 + N0 +
  // N0 N1).
  static bool fits(const Sizes& sizes) {
    int reach = 0;
    for (int a = 0; a < 3; ++a)
      reach = std::max({reach, -Tr::kStencilReachLo[a], Tr::kStencilReachHi[a]});
    const double n0 = sizes[0], n1 = sizes[1];
    return (reach + 1.0) * (1.0 + n0 + n0 * n1) <
           static_cast<double>(std::numeric_limits<O>::max());
  }

  const LatticeVolume<T>& volume() const { return *volume_; }
  double extent(int a) const { return 2.0 * volume_->sizes()[a]; }
  double last(int a) const { return 2.0 * volume_->sizes()[a] - 1; }
  bool contains_box(const LatticePoint& lo, const LatticePoint& hi) const {
    for (int a = 0; a < 3; ++a)
      if (lo[a] > hi[a]) return true;  // empty box
    for (int a = 0; a < 3; ++a)
      if (lo[a] < 0 || hi[a] > 2 * static_cast<std::int64_t>(volume_->sizes()[a]) - 1) return false;
    return true;
  }
  bool has_offsets() const { return true; }
  std::optional<LinearLayout> linear() const {
    return LinearLayout{{stride_[0], stride_[1], stride_[2]}, stride_[1] + stride_[2]};
  }
  const T* samples() const { return volume_->samples().data(); }
  Fetch<O> fetch(const std::int64_t* corner, int cell) const {
    return {corner[0] * stride_[0] + corner[1] * stride_[1] + corner[2] * stride_[2],
            &offsets_[((corner[0] & 1) * Tr::kCellCount + cell) * Tr::kStencilSize]};
  }
  T sample(const LatticePoint& j, bool inside) const {
    return inside ? volume_->value_unchecked(j) : volume_->value(j);
  }

 private:
  const LatticeVolume<T>* volume_;
  std::array<std::int64_t, 3> stride_{};
  std::vector<O> offsets_;  // [corner parity][cell][k]
};

}  // namespace boxgen::runtime
