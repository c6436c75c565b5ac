// A volume sampled on the body-centred cubic lattice h Z_bcc + o, stored as two interleaved
// Cartesian cosets of N0 x N1 x N2 samples each.
//
// Sample (c, i, j, k), c in {0, 1}, sits at the world point o + h (2i + c, 2j + c, 2k + c): coset 0
// holds the even lattice points, coset 1 the odd ones. Its lattice coordinates are
// (x, y, z) = (2i + c, 2j + c, 2k + c), all even or all odd; world = o + h * lattice.
// Storage: the coset index fastest, then i, then j, then k (the NRRD layout of nrrd_io.h).
//
// Border policy: the volume holds exactly the lattice points 0 <= x <= 2 N0 - 1 (and likewise for
// y, z) whose coordinates have one parity. Nothing outside is invented:
//   value(x, y, z)            throws std::out_of_range (one line) for a point outside or a point
//                             that is not on the lattice;
//   value_or(x, y, z, outside) returns `outside` there instead;
//   contains / contains_box   say beforehand whether a point or a whole stencil box is inside.
// Callers that must not fail sample with enough margin (sampling.h says how much).
#pragma once
#include <array>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <span>
#include <type_traits>
#include <utility>
#include <vector>

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
class BccVolume {
  static_assert(std::is_same_v<T, float> || std::is_same_v<T, double>,
                "BccVolume holds float or double");

 public:
  using value_type = T;
  // Largest number of samples per coset along one axis, and in the whole volume: keeps 2 N - 1
  // and every index product far from overflow. (Memory runs out well before the second limit;
  // the allocation then throws std::bad_alloc.)
  static constexpr int kMaxSize = 1 << 24;
  static constexpr std::uint64_t kMaxSamples = std::uint64_t{1} << 34;

  // A zero-filled volume. Throws std::invalid_argument (one line) unless every size is in
  // [1, kMaxSize], 2 N0 N1 N2 <= kMaxSamples, h is finite and > 0 and the origin is finite.
  BccVolume(Sizes sizes, double h, Vec3 origin);
  // Takes `samples` (2 N0 N1 N2 of them, in storage order) instead of zeros; throws
  // std::invalid_argument as above or when their number is wrong.
  BccVolume(Sizes sizes, double h, Vec3 origin, std::vector<T>&& samples);

  const Sizes& sizes() const noexcept { return sizes_; }
  double spacing() const noexcept { return h_; }
  const Vec3& origin() const noexcept { return origin_; }
  // 2 N0 N1 N2.
  std::size_t sample_count() const noexcept { return samples_.size(); }
  std::span<T> samples() noexcept { return samples_; }
  std::span<const T> samples() const noexcept { return samples_; }
  // The storage, for moving it into a LatticeVolume (lattice_volume.h); the volume is empty
  // afterwards.
  std::vector<T> release() && { return std::move(samples_); }

  // Position of sample (c, i, j, k) in samples(): c + 2 (i + N0 (j + N1 k)). Unchecked.
  std::size_t index(int c, int i, int j, int k) const noexcept {
    return static_cast<std::size_t>(c) +
           2 * (static_cast<std::size_t>(i) +
                static_cast<std::size_t>(sizes_[0]) *
                    (static_cast<std::size_t>(j) +
                     static_cast<std::size_t>(sizes_[1]) * static_cast<std::size_t>(k)));
  }
  // Unchecked access by coset and coset index.
  T& operator()(int c, int i, int j, int k) noexcept { return samples_[index(c, i, j, k)]; }
  const T& operator()(int c, int i, int j, int k) const noexcept {
    return samples_[index(c, i, j, k)];
  }
  // Checked access: throws std::out_of_range (one line) unless c in {0,1}, 0 <= i < N0, ...
  T& at(int c, int i, int j, int k);
  const T& at(int c, int i, int j, int k) const;

  // Is (x, y, z) a point of Z_bcc (all coordinates even or all odd)?
  static bool is_lattice_point(std::int64_t x, std::int64_t y, std::int64_t z) noexcept {
    return ((x ^ y) & 1) == 0 && ((x ^ z) & 1) == 0;
  }
  // Is (x, y, z) a lattice point held by this volume?
  bool contains(std::int64_t x, std::int64_t y, std::int64_t z) const noexcept {
    return is_lattice_point(x, y, z) && in_range(x, sizes_[0]) && in_range(y, sizes_[1]) &&
           in_range(z, sizes_[2]);
  }
  bool contains(const LatticePoint& p) const noexcept { return contains(p[0], p[1], p[2]); }
  // Does the volume hold every lattice point of the box lo <= p <= hi (componentwise)? True for
  // an empty box. Because each parity class fills 0..2N-1 up to its own parity, this holds
  // exactly when 0 <= lo and hi <= 2N - 1 on every non-empty axis.
  bool contains_box(const LatticePoint& lo, const LatticePoint& hi) const noexcept;

  // The sample at lattice point (x, y, z); throws std::out_of_range (one line) if the point is
  // outside the volume or not a BCC lattice point.
  T value(std::int64_t x, std::int64_t y, std::int64_t z) const {
    if (!contains(x, y, z)) throw_outside(x, y, z);
    return samples_[lattice_index(x, y, z)];
  }
  T value(const LatticePoint& p) const { return value(p[0], p[1], p[2]); }
  // The sample at a BCC lattice point the caller has already shown to be inside (contains_box
  // around a whole stencil): no check, for the reconstruction's inner loop.
  T value_unchecked(const LatticePoint& p) const noexcept {
    return samples_[lattice_index(p[0], p[1], p[2])];
  }
  // The sample at (x, y, z), or `outside` where value() would throw.
  T value_or(std::int64_t x, std::int64_t y, std::int64_t z, T outside) const noexcept {
    return contains(x, y, z) ? samples_[lattice_index(x, y, z)] : outside;
  }
  T value_or(const LatticePoint& p, T outside) const noexcept {
    return value_or(p[0], p[1], p[2], outside);
  }

  // World <-> lattice coordinates: lattice = (world - o) / h, world = o + h * lattice.
  Vec3 to_lattice(const Vec3& world) const noexcept {
    return {(world[0] - origin_[0]) / h_, (world[1] - origin_[1]) / h_,
            (world[2] - origin_[2]) / h_};
  }
  Vec3 to_world(const Vec3& lattice) const noexcept {
    return {origin_[0] + h_ * lattice[0], origin_[1] + h_ * lattice[1],
            origin_[2] + h_ * lattice[2]};
  }
  // World position of sample (c, i, j, k).
  Vec3 sample_position(int c, int i, int j, int k) const noexcept {
    return to_world({static_cast<double>(2 * i + c), static_cast<double>(2 * j + c),
                     static_cast<double>(2 * k + c)});
  }

 private:
  static bool in_range(std::int64_t x, int n) noexcept {
    return x >= 0 && x <= 2 * static_cast<std::int64_t>(n) - 1;
  }
  // x = 2i + c with c = x & 1 (C++20 integers are two's complement, so this also holds for x < 0).
  std::size_t lattice_index(std::int64_t x, std::int64_t y, std::int64_t z) const noexcept {
    return index(static_cast<int>(x & 1), static_cast<int>(x >> 1), static_cast<int>(y >> 1),
                 static_cast<int>(z >> 1));
  }
  [[noreturn]] void throw_outside(std::int64_t x, std::int64_t y, std::int64_t z) const;

  Sizes sizes_;
  double h_;
  Vec3 origin_;
  std::vector<T> samples_;
};

extern template class BccVolume<float>;
extern template class BccVolume<double>;

}  // namespace boxgen::runtime
