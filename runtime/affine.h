// The voxel-to-world map of a grid: world = A index + t, the 4x4 affine of NIfTI's sform and of
// NRRD's space directions and origin (columns of A = the space directions). A diagonal A is an
// axis-aligned grid with a spacing per axis; anything else is oblique (scanners tilt their slices).
#pragma once
#include <array>
#include <cmath>

#include "runtime/lattice_volume.h"

namespace boxgen::runtime {

struct Affine {
  std::array<Vec3, 3> linear{};  // linear[r][c]: row r, column c (column c = axis c's step)
  Vec3 translation{};            // the world point of index (0, 0, 0)

  static Affine diagonal(const Vec3& spacing, const Vec3& origin) {
    Affine a;
    for (int r = 0; r < 3; ++r) a.linear[r][r] = spacing[r];
    a.translation = origin;
    return a;
  }
  Vec3 apply(const Vec3& index) const noexcept {
    Vec3 w = translation;
    for (int r = 0; r < 3; ++r)
      for (int c = 0; c < 3; ++c) w[r] += linear[r][c] * index[c];
    return w;
  }
  // The length of axis c's step (its voxel size).
  double step_length(int c) const noexcept {
    return std::hypot(linear[0][c], linear[1][c], linear[2][c]);
  }
};

}  // namespace boxgen::runtime
