// The world's view of a box that lies in a volume's own frame (an oblique volume's region, an
// oblique reference's grid): the axis-aligned box around it, which slice and render frame.
#pragma once
#include <algorithm>
#include <cmath>
#include <optional>

#include "runtime/affine.h"
#include "runtime/resample.h"

namespace boxgen::runtime {

// The world's axis-aligned box around `box` of a frame (`frame`: its map to world; nothing: the
// box itself, the frame being the world).
inline Box world_box(const Box& box, const std::optional<Affine>& frame) {
  if (!frame) return box;
  Box out{};
  for (int a = 0; a < 3; ++a) {
    out.min[a] = HUGE_VAL;
    out.max[a] = -HUGE_VAL;
  }
  for (int corner = 0; corner < 8; ++corner) {
    Vec3 p{};
    for (int a = 0; a < 3; ++a) p[a] = (corner >> a & 1) != 0 ? box.max[a] : box.min[a];
    const Vec3 w = frame->apply(p);
    for (int a = 0; a < 3; ++a) {
      out.min[a] = std::min(out.min[a], w[a]);
      out.max[a] = std::max(out.max[a], w[a]);
    }
  }
  return out;
}

}  // namespace boxgen::runtime
