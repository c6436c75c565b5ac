// The voxel-to-world map of a grid: world = A index + t, the 4x4 affine of NIfTI's sform and of
// NRRD's space directions and origin (columns of A = the space directions). A diagonal A is an
// axis-aligned grid with a spacing per axis; anything else is oblique (scanners tilt their slices).
#pragma once
#include <array>
#include <cmath>
#include <cstddef>
#include <optional>
#include <span>
#include <stdexcept>
#include <string>

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

// An oblique (or axis-permuting) voxel-to-world affine `a` as the runtime holds it: the voxel
// grid in its own frame (steps = the lengths of a's columns, origin 0) and `frame`, that frame's
// map to world (a's columns over their lengths, a's translation), so that
// frame.after(Affine::diagonal(steps, {0, 0, 0})) is `a` up to rounding. The one split of the
// NIfTI reader and of Python's Volume(affine=). Returns "" or why `a` cannot be split: "has a zero
// or non-finite column C" or "is singular (its voxel axes are not independent)".
inline std::string split_oblique(const Affine& a, Vec3& steps, Affine& frame) {
  for (int c = 0; c < 3; ++c) {
    const auto cu = static_cast<std::size_t>(c);
    steps[cu] = a.step_length(c);
    if (!(std::isfinite(steps[cu]) && steps[cu] > 0))
      return "has a zero or non-finite column " + std::to_string(c);
    for (std::size_t r = 0; r < 3; ++r) frame.linear[r][cu] = a.linear[r][cu] / steps[cu];
  }
  frame.translation = a.translation;
  try {
    (void)frame.inverse();
  } catch (const std::invalid_argument&) {
    return "is singular (its voxel axes are not independent)";
  }
  return {};
}

// The map from a grid's frame to a volume's, both given by their maps to world (nothing: the
// world itself). Nothing when the frames are one, so that a grid on the volume's own frame is
// evaluated at exactly its points.
inline std::optional<Affine> grid_to_volume(const std::optional<Affine>& volume_frame,
                                            const std::optional<Affine>& grid_frame) {
  if (volume_frame == grid_frame) return std::nullopt;
  const Affine from = grid_frame.value_or(Affine::diagonal({1, 1, 1}, {0, 0, 0}));
  return volume_frame ? volume_frame->inverse().after(from) : from;
}

// Derivatives a volume's evaluator took in its own frame, as derivatives in world, where
// `to_volume` maps world to that frame (v = L w + t): by the chain rule the gradient is L^T g and
// the Hessian L^T H L (Hessians as xx xy xz yy yz zz). Either span may be empty.
inline void derivatives_to_world(const Affine& to_volume, std::span<Vec3> gradients,
                                 std::span<Hessian> hessians) {
  const auto& l = to_volume.linear;
  for (Vec3& g : gradients) {
    Vec3 w{};
    for (std::size_t c = 0; c < 3; ++c)
      for (std::size_t r = 0; r < 3; ++r) w[c] += l[r][c] * g[r];
    g = w;
  }
  constexpr std::size_t kAt[3][3] = {{0, 1, 2}, {1, 3, 4}, {2, 4, 5}};  // (i, j) -> xx xy ...
  for (Hessian& h : hessians) {
    double hl[3][3] = {};  // H L
    for (std::size_t i = 0; i < 3; ++i)
      for (std::size_t j = 0; j < 3; ++j)
        for (std::size_t k = 0; k < 3; ++k) hl[i][j] += h[kAt[i][k]] * l[k][j];
    Hessian w{};
    for (std::size_t i = 0; i < 3; ++i)
      for (std::size_t j = i; j < 3; ++j)
        for (std::size_t k = 0; k < 3; ++k) w[kAt[i][j]] += l[k][i] * hl[k][j];
    h = w;
  }
}

}  // namespace boxgen::runtime
