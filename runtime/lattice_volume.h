// A volume sampled on any lattice h L + o, L = G Z^3 (coset_lattice.h), stored as K interleaved
// cosets of the Cartesian lattice d Z^3 with N0 x N1 x N2 samples each.
//
// Sample (c, i, j, k) sits at the world point o + h (d i + off_c.x, d j + off_c.y, d k + off_c.z);
// its lattice coordinates are off_c + d (i, j, k). Storage: the coset index fastest, then i, j, k
// (the NRRD layout of nrrd_io.h). The one volume type of the runtime: BCC is the lattice with
// d = 2, K = 2, offsets (0,0,0) (1,1,1) (sample (c, i, j, k) at o + h (2i + c, 2j + c, 2k + c)).
//
// Border policy: nothing outside the stored samples is invented. value() throws
// std::out_of_range (one line) for a point outside the volume or not on the lattice; value_or()
// returns the caller's value there; contains_box() says beforehand whether a box is held.
// Callers that must not fail sample with enough margin (SplineFilter::required_margin).
#pragma once
#include <array>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <span>
#include <type_traits>
#include <utility>
#include <vector>

#include "runtime/coset_lattice.h"
#include "support/integer_math.h"

namespace boxgen::runtime {

using Vec3 = std::array<double, 3>;
// Second derivatives in world units: the upper triangle {xx, xy, xz, yy, yz, zz}.
using Hessian = std::array<double, 6>;
using LatticePoint = std::array<std::int64_t, 3>;
using Sizes = std::array<int, 3>;

// x rounded to T, overflowing to +-infinity as IEEE arithmetic would (converting a finite double
// beyond float's range with a plain cast is undefined behaviour).
template <class T>
T to_sample(double x) noexcept {
  if constexpr (std::is_same_v<T, float>) {
    constexpr double kMax = std::numeric_limits<float>::max();
    if (x > kMax) return std::numeric_limits<float>::infinity();
    if (x < -kMax) return -std::numeric_limits<float>::infinity();
  }
  return static_cast<T>(x);
}

template <class T>
class LatticeVolume {
  static_assert(std::is_same_v<T, float> || std::is_same_v<T, double>,
                "LatticeVolume holds float or double");

 public:
  using value_type = T;
  // Largest number of samples per coset along one axis, and in the whole volume: keeps d N and
  // every index product far from overflow. (Memory runs out well before the second limit; the
  // allocation then throws std::bad_alloc.)
  static constexpr int kMaxSize = 1 << 24;
  static constexpr std::uint64_t kMaxSamples = std::uint64_t{1} << 34;

  // A zero-filled volume. Throws std::invalid_argument (one line) unless every size is in
  // [1, kMaxSize], K N0 N1 N2 <= kMaxSamples, h is finite and > 0 and the origin is finite.
  LatticeVolume(CosetLattice lattice, Sizes sizes, double h, Vec3 origin);
  // Takes the samples of `samples` (K N0 N1 N2 of them, in storage order).
  LatticeVolume(CosetLattice lattice, Sizes sizes, double h, Vec3 origin, std::vector<T>&& samples);
  // A volume with a spacing per axis: lattice point p sits at o + (h0 p.x, h1 p.y, h2 p.z). Only
  // the Cartesian lattice Z^3 may have unequal spacings (scanners' anisotropic voxels); on any
  // other lattice they would distort it into another lattice, and are std::invalid_argument.
  LatticeVolume(CosetLattice lattice, Sizes sizes, Vec3 spacing, Vec3 origin,
                std::vector<T>&& samples);

  const CosetLattice& lattice() const noexcept { return lattice_; }
  int coset_count() const noexcept { return k_; }
  int period() const noexcept { return lattice_.period(); }
  const Sizes& sizes() const noexcept { return sizes_; }
  // The one spacing h of an isotropic volume; std::logic_error for an anisotropic one, whose
  // callers use axis_spacing().
  double spacing() const;
  // The spacing along each axis (all equal unless the volume is anisotropic).
  const Vec3& axis_spacing() const noexcept { return h_; }
  bool is_isotropic() const noexcept { return h_[0] == h_[1] && h_[1] == h_[2]; }
  const Vec3& origin() const noexcept { return origin_; }
  std::size_t sample_count() const noexcept { return samples_.size(); }
  std::span<T> samples() noexcept { return samples_; }
  std::span<const T> samples() const noexcept { return samples_; }
  // The storage, for moving it elsewhere; the volume is empty afterwards.
  std::vector<T> release() && { return std::move(samples_); }

  // Position of sample (c, i, j, k) in samples(): c + K (i + N0 (j + N1 k)). Unchecked.
  std::size_t index(int c, int i, int j, int k) const noexcept {
    return static_cast<std::size_t>(c) +
           static_cast<std::size_t>(k_) *
               (static_cast<std::size_t>(i) +
                static_cast<std::size_t>(sizes_[0]) *
                    (static_cast<std::size_t>(j) +
                     static_cast<std::size_t>(sizes_[1]) * static_cast<std::size_t>(k)));
  }
  T& operator()(int c, int i, int j, int k) noexcept { return samples_[index(c, i, j, k)]; }
  const T& operator()(int c, int i, int j, int k) const noexcept {
    return samples_[index(c, i, j, k)];
  }
  // Checked access: throws std::out_of_range (one line) unless 0 <= c < K, 0 <= i < N0, ...
  T& at(int c, int i, int j, int k);
  const T& at(int c, int i, int j, int k) const;

  // Lattice coordinates of sample (c, i, j, k): off_c + d (i, j, k).
  LatticePoint lattice_point(int c, int i, int j, int k) const noexcept;
  bool is_lattice_point(std::int64_t x, std::int64_t y, std::int64_t z) const noexcept {
    return lattice_.contains(x, y, z);
  }
  bool contains(std::int64_t x, std::int64_t y, std::int64_t z) const noexcept;
  bool contains(const LatticePoint& p) const noexcept { return contains(p[0], p[1], p[2]); }
  // Does the volume hold every lattice point of the box lo <= p <= hi? True for an empty box.
  bool contains_box(const LatticePoint& lo, const LatticePoint& hi) const noexcept;

  T value(std::int64_t x, std::int64_t y, std::int64_t z) const {
    if (!contains(x, y, z)) throw_outside(x, y, z);
    return samples_[lattice_index(x, y, z)];
  }
  T value(const LatticePoint& p) const { return value(p[0], p[1], p[2]); }
  // c + K (i + N0 (j + N1 k)) for lattice point p = off_c + d (i, j, k), also outside the volume
  // (then negative or beyond the storage). Unchecked: p must be a lattice point.
  std::int64_t storage_offset(const LatticePoint& p) const noexcept {
    const int c = lattice_.coset_of(p[0], p[1], p[2]);
    const Offset& o = lattice_.offsets()[static_cast<std::size_t>(c)];
    const std::int64_t d = lattice_.period();
    using support::floor_div;
    return c + k_ * (floor_div(p[0] - o[0], d) +
                     sizes_[0] * (floor_div(p[1] - o[1], d) + static_cast<std::int64_t>(sizes_[1]) *
                                                                  floor_div(p[2] - o[2], d)));
  }
  // A lattice point the caller has shown to be inside: no check.
  T value_unchecked(const LatticePoint& p) const noexcept {
    return samples_[lattice_index(p[0], p[1], p[2])];
  }
  T value_or(std::int64_t x, std::int64_t y, std::int64_t z, T outside) const noexcept {
    return contains(x, y, z) ? samples_[lattice_index(x, y, z)] : outside;
  }
  T value_or(const LatticePoint& p, T outside) const noexcept {
    return value_or(p[0], p[1], p[2], outside);
  }

  Vec3 to_lattice(const Vec3& world) const noexcept {
    return {(world[0] - origin_[0]) / h_[0], (world[1] - origin_[1]) / h_[1],
            (world[2] - origin_[2]) / h_[2]};
  }
  Vec3 to_world(const Vec3& lattice) const noexcept {
    return {origin_[0] + h_[0] * lattice[0], origin_[1] + h_[1] * lattice[1],
            origin_[2] + h_[2] * lattice[2]};
  }
  Vec3 sample_position(int c, int i, int j, int k) const noexcept {
    const LatticePoint p = lattice_point(c, i, j, k);
    return to_world(
        {static_cast<double>(p[0]), static_cast<double>(p[1]), static_cast<double>(p[2])});
  }

 private:
  std::size_t lattice_index(std::int64_t x, std::int64_t y, std::int64_t z) const noexcept {
    return static_cast<std::size_t>(storage_offset({x, y, z}));
  }
  [[noreturn]] void throw_outside(std::int64_t x, std::int64_t y, std::int64_t z) const;

  CosetLattice lattice_;
  int k_;
  Sizes sizes_;
  Vec3 h_;
  Vec3 origin_;
  std::vector<T> samples_;
};

extern template class LatticeVolume<float>;
extern template class LatticeVolume<double>;

}  // namespace boxgen::runtime
