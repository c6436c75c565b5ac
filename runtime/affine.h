// The voxel-to-world map of a grid: world = A index + t, the 4x4 affine of NIfTI's sform and of
// NRRD's space directions and origin (columns of A = the space directions). A diagonal A is an
// axis-aligned grid with a spacing per axis; anything else is oblique (scanners tilt their slices).
#pragma once
#include <array>
#include <cmath>
#include <stdexcept>

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
  // This map after `first`: x -> this(first(x)).
  Affine after(const Affine& first) const noexcept {
    Affine out;
    out.translation = apply(first.translation);
    for (int r = 0; r < 3; ++r)
      for (int c = 0; c < 3; ++c)
        for (int k = 0; k < 3; ++k) out.linear[r][c] += linear[r][k] * first.linear[k][c];
    return out;
  }
  // The inverse map (cofactors over the determinant). Throws std::invalid_argument (one line)
  // for a singular or non-finite linear part.
  Affine inverse() const {
    const auto& m = linear;
    const double det = m[0][0] * (m[1][1] * m[2][2] - m[1][2] * m[2][1]) -
                       m[0][1] * (m[1][0] * m[2][2] - m[1][2] * m[2][0]) +
                       m[0][2] * (m[1][0] * m[2][1] - m[1][1] * m[2][0]);
    if (!std::isfinite(det) || det == 0)
      throw std::invalid_argument("the affine's linear part is singular or not finite");
    Affine inv;
    for (int r = 0; r < 3; ++r)
      for (int c = 0; c < 3; ++c) {
        // Cofactor of m[c][r] (the adjugate is the transposed cofactor matrix).
        const int r1 = (c + 1) % 3, r2 = (c + 2) % 3, c1 = (r + 1) % 3, c2 = (r + 2) % 3;
        inv.linear[r][c] = (m[r1][c1] * m[r2][c2] - m[r1][c2] * m[r2][c1]) / det;
      }
    for (int r = 0; r < 3; ++r)
      for (int c = 0; c < 3; ++c) inv.translation[r] -= inv.linear[r][c] * translation[c];
    return inv;
  }
  bool operator==(const Affine&) const = default;
};

}  // namespace boxgen::runtime
