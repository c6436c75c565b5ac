// A volume sampled on any lattice h L + o, L = G Z^3 (coset_lattice.h), stored as K interleaved
// cosets of the Cartesian lattice d Z^3 with N0 x N1 x N2 samples each.
//
// Sample (c, i, j, k) sits at the world point o + h (d i + off_c.x, d j + off_c.y, d k + off_c.z);
// its lattice coordinates are off_c + d (i, j, k). Storage: the coset index fastest, then i, j, k
// (the NRRD layout of nrrd_io.h). BCC (d = 2, K = 2, offsets (0,0,0) (1,1,1)) is exactly the
// layout of BccVolume<T>, which stays the BCC type of the reconstruction code; the two convert
// into each other without copying samples (to_lattice_volume, to_bcc_volume).
//
// Border policy as BccVolume: nothing outside the stored samples is invented. value() throws
// std::out_of_range (one line) for a point outside the volume or not on the lattice; value_or()
// returns the caller's value there; contains_box() says beforehand whether a box is held.
#pragma once
#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include "runtime/bcc_volume.h"
#include "runtime/coset_lattice.h"

namespace boxgen::runtime {

template <class T>
class LatticeVolume {
  static_assert(std::is_same_v<T, float> || std::is_same_v<T, double>,
                "LatticeVolume holds float or double");

 public:
  using value_type = T;
  static constexpr int kMaxSize = BccVolume<double>::kMaxSize;
  static constexpr std::uint64_t kMaxSamples = BccVolume<double>::kMaxSamples;

  // A zero-filled volume. Throws std::invalid_argument (one line) unless every size is in
  // [1, kMaxSize], K N0 N1 N2 <= kMaxSamples, h is finite and > 0 and the origin is finite.
  LatticeVolume(CosetLattice lattice, Sizes sizes, double h, Vec3 origin);
  // Takes the samples of `samples` (K N0 N1 N2 of them, in storage order).
  LatticeVolume(CosetLattice lattice, Sizes sizes, double h, Vec3 origin, std::vector<T>&& samples);

  const CosetLattice& lattice() const noexcept { return lattice_; }
  int coset_count() const noexcept { return k_; }
  int period() const noexcept { return lattice_.period(); }
  const Sizes& sizes() const noexcept { return sizes_; }
  double spacing() const noexcept { return h_; }
  const Vec3& origin() const noexcept { return origin_; }
  std::size_t sample_count() const noexcept { return samples_.size(); }
  std::span<T> samples() noexcept { return samples_; }
  std::span<const T> samples() const noexcept { return samples_; }
  // The storage, for moving it elsewhere (to_bcc_volume); the volume is empty afterwards.
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
    return {(world[0] - origin_[0]) / h_, (world[1] - origin_[1]) / h_,
            (world[2] - origin_[2]) / h_};
  }
  Vec3 to_world(const Vec3& lattice) const noexcept {
    return {origin_[0] + h_ * lattice[0], origin_[1] + h_ * lattice[1],
            origin_[2] + h_ * lattice[2]};
  }
  Vec3 sample_position(int c, int i, int j, int k) const noexcept {
    const LatticePoint p = lattice_point(c, i, j, k);
    return to_world(
        {static_cast<double>(p[0]), static_cast<double>(p[1]), static_cast<double>(p[2])});
  }

 private:
  static std::int64_t floor_div(std::int64_t a, std::int64_t b) noexcept {
    const std::int64_t q = a / b;
    return (a % b != 0 && a < 0) ? q - 1 : q;
  }
  // Unchecked: (x, y, z) must be a lattice point.
  std::size_t lattice_index(std::int64_t x, std::int64_t y, std::int64_t z) const noexcept {
    const int c = lattice_.coset_of(x, y, z);
    const Offset& o = lattice_.offsets()[static_cast<std::size_t>(c)];
    const int d = lattice_.period();
    return index(c, static_cast<int>(floor_div(x - o[0], d)),
                 static_cast<int>(floor_div(y - o[1], d)),
                 static_cast<int>(floor_div(z - o[2], d)));
  }
  [[noreturn]] void throw_outside(std::int64_t x, std::int64_t y, std::int64_t z) const;

  CosetLattice lattice_;
  int k_;
  Sizes sizes_;
  double h_;
  Vec3 origin_;
  std::vector<T> samples_;
};

// The BCC volume as a lattice volume (the samples move; `volume` is left empty), and back.
// to_bcc_volume throws std::invalid_argument (one line) unless the volume is on the BCC lattice
// with the offsets (0,0,0), (1,1,1).
template <class T>
LatticeVolume<T> to_lattice_volume(BccVolume<T>&& volume);
template <class T>
BccVolume<T> to_bcc_volume(LatticeVolume<T>&& volume);

extern template class LatticeVolume<float>;
extern template class LatticeVolume<double>;
extern template LatticeVolume<float> to_lattice_volume(BccVolume<float>&&);
extern template LatticeVolume<double> to_lattice_volume(BccVolume<double>&&);
extern template BccVolume<float> to_bcc_volume(LatticeVolume<float>&&);
extern template BccVolume<double> to_bcc_volume(LatticeVolume<double>&&);

}  // namespace boxgen::runtime
