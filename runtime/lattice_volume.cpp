#include "runtime/lattice_volume.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>
#include <utility>

namespace boxgen::runtime {

using support::floor_div;

namespace {

std::uint64_t checked_count(const CosetLattice& lattice, const Sizes& sizes, const Vec3& h,
                            const Vec3& origin) {
  const int k = lattice.coset_count();
  std::uint64_t count = static_cast<std::uint64_t>(k);
  for (int a = 0; a < 3; ++a) {
    if (sizes[a] < 1 || sizes[a] > LatticeVolume<double>::kMaxSize)
      throw std::invalid_argument(fmt::format(
          "{} volume size {} x {} x {} per coset is out of range (each must be in 1..{})",
          lattice.label(), sizes[0], sizes[1], sizes[2], LatticeVolume<double>::kMaxSize));
    count *=
        static_cast<std::uint64_t>(sizes[a]);  // K <= 64^3, sizes <= 2^24: checked before overflow
    if (count > LatticeVolume<double>::kMaxSamples)
      throw std::invalid_argument(fmt::format(
          "{} volume of {} x {} x {} x {} samples is too large (at most {} samples)",
          lattice.label(), k, sizes[0], sizes[1], sizes[2], LatticeVolume<double>::kMaxSamples));
  }
  for (double x : h)
    if (!std::isfinite(x) || x <= 0)
      throw std::invalid_argument(
          fmt::format("{} volume spacing h = {} must be finite and positive", lattice.label(), x));
  if ((h[0] != h[1] || h[1] != h[2]) && (lattice.coset_count() != 1 || lattice.period() != 1))
    throw std::invalid_argument(fmt::format(
        "{} volume spacings ({}, {}, {}) differ: only Cartesian volumes may be anisotropic",
        lattice.label(), h[0], h[1], h[2]));
  for (double x : origin)
    if (!std::isfinite(x))
      throw std::invalid_argument(fmt::format("{} volume origin ({}, {}, {}) must be finite",
                                              lattice.label(), origin[0], origin[1], origin[2]));
  return count;
}

}  // namespace

template <class T>
LatticeVolume<T>::LatticeVolume(CosetLattice lattice, Sizes sizes, double h, Vec3 origin)
    : lattice_(std::move(lattice)),
      k_(lattice_.coset_count()),
      sizes_(sizes),
      h_{h, h, h},
      origin_(origin) {
  samples_.assign(static_cast<std::size_t>(checked_count(lattice_, sizes, h_, origin)), T{0});
}

template <class T>
LatticeVolume<T>::LatticeVolume(CosetLattice lattice, Sizes sizes, double h, Vec3 origin,
                                std::vector<T>&& samples)
    : LatticeVolume(std::move(lattice), sizes, Vec3{h, h, h}, origin, std::move(samples)) {}

template <class T>
LatticeVolume<T>::LatticeVolume(CosetLattice lattice, Sizes sizes, Vec3 spacing, Vec3 origin,
                                std::vector<T>&& samples)
    : lattice_(std::move(lattice)),
      k_(lattice_.coset_count()),
      sizes_(sizes),
      h_(spacing),
      origin_(origin) {
  if (samples.size() != checked_count(lattice_, sizes, h_, origin))
    throw std::invalid_argument(
        fmt::format("{} volume of {} x {} x {} x {} samples given {} samples", lattice_.label(), k_,
                    sizes[0], sizes[1], sizes[2], samples.size()));
  samples_ = std::move(samples);
}

template <class T>
double LatticeVolume<T>::spacing() const {
  if (!is_isotropic())
    throw std::logic_error(
        fmt::format("the {} volume is anisotropic (spacings {}, {}, {}): it has no one spacing",
                    lattice_.label(), h_[0], h_[1], h_[2]));
  return h_[0];
}

template <class T>
T& LatticeVolume<T>::at(int c, int i, int j, int k) {
  return const_cast<T&>(std::as_const(*this).at(c, i, j, k));
}

template <class T>
const T& LatticeVolume<T>::at(int c, int i, int j, int k) const {
  if (c < 0 || c >= k_ || i < 0 || i >= sizes_[0] || j < 0 || j >= sizes_[1] || k < 0 ||
      k >= sizes_[2])
    throw std::out_of_range(fmt::format(
        "sample (coset {}, {}, {}, {}) is outside the {} volume ({} cosets of {} x {} x {})", c, i,
        j, k, lattice_.label(), k_, sizes_[0], sizes_[1], sizes_[2]));
  return samples_[index(c, i, j, k)];
}

template <class T>
LatticePoint LatticeVolume<T>::lattice_point(int c, int i, int j, int k) const noexcept {
  const Offset& o = lattice_.offsets()[static_cast<std::size_t>(c)];
  const std::int64_t d = lattice_.period();
  return {o[0] + d * i, o[1] + d * j, o[2] + d * k};
}

template <class T>
bool LatticeVolume<T>::contains(std::int64_t x, std::int64_t y, std::int64_t z) const noexcept {
  const int c = lattice_.coset_of(x, y, z);
  if (c < 0) return false;
  const Offset& o = lattice_.offsets()[static_cast<std::size_t>(c)];
  const std::int64_t d = lattice_.period();
  const std::int64_t p[3] = {x, y, z};
  for (int a = 0; a < 3; ++a) {
    const std::int64_t i = floor_div(p[a] - o[a], d);  // exact: p - o is a multiple of d
    if (i < 0 || i >= sizes_[a]) return false;
  }
  return true;
}

template <class T>
bool LatticeVolume<T>::contains_box(const LatticePoint& lo, const LatticePoint& hi) const noexcept {
  for (int a = 0; a < 3; ++a)
    if (lo[a] > hi[a]) return true;  // empty box
  // Coset c's points in the box are a product over the axes of {x in [lo, hi] : x = off (mod d)}:
  // each must lie in off + d [0, N - 1].
  const std::int64_t d = lattice_.period();
  for (const Offset& o : lattice_.offsets()) {
    std::int64_t first[3], last[3];
    bool empty = false;
    for (int a = 0; a < 3; ++a) {
      first[a] =
          o[a] + d * floor_div(lo[a] - o[a] + d - 1, d);  // smallest x >= lo with x = off (mod d)
      last[a] = o[a] + d * floor_div(hi[a] - o[a], d);    // largest x <= hi
      if (first[a] > last[a]) empty = true;
    }
    if (empty) continue;
    for (int a = 0; a < 3; ++a)
      if (first[a] < o[a] || last[a] > o[a] + d * (static_cast<std::int64_t>(sizes_[a]) - 1))
        return false;
  }
  return true;
}

template <class T>
void LatticeVolume<T>::throw_outside(std::int64_t x, std::int64_t y, std::int64_t z) const {
  if (!lattice_.contains(x, y, z))
    throw std::out_of_range(
        fmt::format("({}, {}, {}) is not a {} lattice point", x, y, z, lattice_.label()));
  throw std::out_of_range(
      fmt::format("{} lattice point ({}, {}, {}) is outside the volume ({} cosets of {} x {} x {})",
                  lattice_.label(), x, y, z, k_, sizes_[0], sizes_[1], sizes_[2]));
}

template class LatticeVolume<float>;
template class LatticeVolume<double>;

}  // namespace boxgen::runtime
