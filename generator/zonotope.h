// The bounding box of a box spline's support, the zonotope Xi [0,1]^m: where its pieces
// (piecewise_form.h), its cost estimate and its symbol's sums look.
#pragma once
#include "generator/int_linalg.h"
#include "generator/rational.h"

namespace boxgen::generator {

// The bounding box [lo, hi] of the support Xi [0,1]^m.
class Zonotope {
 public:
  explicit Zonotope(const IntColumns& directions, int n);
  const IntVec& box_lo() const { return lo_; }
  const IntVec& box_hi() const { return hi_; }

 private:
  IntVec lo_, hi_;
};

}  // namespace boxgen::generator
