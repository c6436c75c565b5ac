#include "runtime/bcc_volume.h"

#include <fmt/format.h>

#include <cmath>
#include <stdexcept>
#include <utility>

namespace boxgen::runtime {

namespace {

// The number of samples 2 N0 N1 N2 of a valid volume; throws std::invalid_argument (one line).
std::uint64_t checked_count(const Sizes& sizes, double h, const Vec3& origin) {
  std::uint64_t count = 2;
  for (int a = 0; a < 3; ++a) {
    if (sizes[a] < 1 || sizes[a] > BccVolume<double>::kMaxSize)
      throw std::invalid_argument(fmt::format(
          "BCC volume size {} x {} x {} per coset is out of range (each must be in 1..{})",
          sizes[0], sizes[1], sizes[2], BccVolume<double>::kMaxSize));
    count *= static_cast<std::uint64_t>(sizes[a]);  // <= 2^34 * 2^24: no overflow
    if (count > BccVolume<double>::kMaxSamples)
      throw std::invalid_argument(
          fmt::format("BCC volume of 2 x {} x {} x {} samples is too large (at most {} samples)",
                      sizes[0], sizes[1], sizes[2], BccVolume<double>::kMaxSamples));
  }
  if (!std::isfinite(h) || h <= 0)
    throw std::invalid_argument(
        fmt::format("BCC volume spacing h = {} must be finite and positive", h));
  for (double x : origin)
    if (!std::isfinite(x))
      throw std::invalid_argument(fmt::format("BCC volume origin ({}, {}, {}) must be finite",
                                              origin[0], origin[1], origin[2]));
  return count;
}

}  // namespace

template <class T>
BccVolume<T>::BccVolume(Sizes sizes, double h, Vec3 origin)
    : sizes_(sizes), h_(h), origin_(origin) {
  samples_.assign(static_cast<std::size_t>(checked_count(sizes, h, origin)), T{0});
}

template <class T>
BccVolume<T>::BccVolume(Sizes sizes, double h, Vec3 origin, std::vector<T>&& samples)
    : sizes_(sizes), h_(h), origin_(origin) {
  if (samples.size() != checked_count(sizes, h, origin))
    throw std::invalid_argument(
        fmt::format("BCC volume of 2 x {} x {} x {} samples given {} samples", sizes[0], sizes[1],
                    sizes[2], samples.size()));
  samples_ = std::move(samples);
}

template <class T>
T& BccVolume<T>::at(int c, int i, int j, int k) {
  return const_cast<T&>(std::as_const(*this).at(c, i, j, k));
}

template <class T>
const T& BccVolume<T>::at(int c, int i, int j, int k) const {
  if (c < 0 || c > 1 || i < 0 || i >= sizes_[0] || j < 0 || j >= sizes_[1] || k < 0 ||
      k >= sizes_[2])
    throw std::out_of_range(fmt::format(
        "BCC sample (coset {}, {}, {}, {}) is outside the volume (2 cosets of {} x {} x {})", c, i,
        j, k, sizes_[0], sizes_[1], sizes_[2]));
  return samples_[index(c, i, j, k)];
}

template <class T>
bool BccVolume<T>::contains_box(const LatticePoint& lo, const LatticePoint& hi) const noexcept {
  for (int a = 0; a < 3; ++a)
    if (lo[a] > hi[a]) return true;  // empty box
  for (int a = 0; a < 3; ++a)
    if (lo[a] < 0 || hi[a] > 2 * static_cast<std::int64_t>(sizes_[a]) - 1) return false;
  return true;
}

template <class T>
void BccVolume<T>::throw_outside(std::int64_t x, std::int64_t y, std::int64_t z) const {
  if (!is_lattice_point(x, y, z))
    throw std::out_of_range(fmt::format(
        "({}, {}, {}) is not a BCC lattice point (coordinates must be all even or all odd)", x, y,
        z));
  throw std::out_of_range(fmt::format(
      "BCC lattice point ({}, {}, {}) is outside the volume (lattice coordinates 0..{} x 0..{} x "
      "0..{})",
      x, y, z, 2 * static_cast<std::int64_t>(sizes_[0]) - 1,
      2 * static_cast<std::int64_t>(sizes_[1]) - 1, 2 * static_cast<std::int64_t>(sizes_[2]) - 1));
}

template class BccVolume<float>;
template class BccVolume<double>;

}  // namespace boxgen::runtime
