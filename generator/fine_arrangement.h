// The integer-level refinement of a box spline's knot planes that the emitter's lookup table uses
// (piecewise_form.h holds it beside the knot cells).
#pragma once
#include <cstdint>
#include <utility>
#include <vector>

#include "generator/cell_complex.h"
#include "generator/rational.h"

namespace boxgen::generator {

// The fine arrangement: every integer level of the knot normals plus the axes (axes first), on
// the bounding box [lo, hi) of the support. It is invariant under integer shifts, so it holds the
// cells of the unit cube at the origin, split once (the cost estimate counts them, the spline
// structure translates them); every other cube's cells are their translates.
class FineArrangement {
 public:
  FineArrangement(std::vector<IntVec> normals, IntVec lo, IntVec hi)
      : normals_(std::move(normals)),
        lo_(std::move(lo)),
        hi_(std::move(hi)),
        unit_cells_(split_cube(normals_, IntVec(lo_.size(), 0))) {}
  const std::vector<IntVec>& normals() const { return normals_; }
  const IntVec& lo() const { return lo_; }
  const IntVec& hi() const { return hi_; }
  const std::vector<FineCell>& unit_cells() const { return unit_cells_; }
  // The arrangement of the directions divided by k (generator/common_scale.h): the same normals
  // and unit cube, on the box divided by k.
  FineArrangement scaled_down(std::int64_t k) const {
    FineArrangement out = *this;
    for (auto& v : out.lo_) v /= k;  // the support's box: sums of entries, multiples of k
    for (auto& v : out.hi_) v /= k;
    return out;
  }

 private:
  std::vector<IntVec> normals_;
  IntVec lo_, hi_;
  std::vector<FineCell> unit_cells_;
};

}  // namespace boxgen::generator
