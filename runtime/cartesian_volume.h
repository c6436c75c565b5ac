// A plain Cartesian grid of samples (the target of resampling a BCC volume): sample (i, j, k)
// sits at origin + (i sx, j sy, k sz); storage x fastest, then y, then z.
#pragma once
#include <array>
#include <cstddef>
#include <optional>
#include <type_traits>
#include <vector>

#include "runtime/affine.h"
#include "runtime/lattice_volume.h"

namespace boxgen::runtime {

template <class T>
struct CartesianVolume {
  static_assert(std::is_same_v<T, float> || std::is_same_v<T, double>,
                "CartesianVolume holds float or double");
  Sizes sizes{};  // samples along x, y, z
  Vec3 spacing{};
  Vec3 origin{};
  std::vector<T> values;  // sizes[0] * sizes[1] * sizes[2], x fastest
  // An oblique grid's map from the frame of `position` to world (as SourceSamples::frame);
  // nothing when that frame is the world. Writers store the composed affine.
  std::optional<Affine> frame{};

  std::size_t index(int i, int j, int k) const noexcept {
    return static_cast<std::size_t>(i) +
           static_cast<std::size_t>(sizes[0]) *
               (static_cast<std::size_t>(j) +
                static_cast<std::size_t>(sizes[1]) * static_cast<std::size_t>(k));
  }
  Vec3 position(int i, int j, int k) const noexcept {
    return {origin[0] + i * spacing[0], origin[1] + j * spacing[1], origin[2] + k * spacing[2]};
  }
};

}  // namespace boxgen::runtime
