// Properties of a box spline that follow from its direction matrix alone (docs/design.md §3,
// paper section 3.2): degree, continuity, approximation order, support volume, stencil size and
// linear independence of the lattice shifts.
#pragma once
#include "generator/spec.h"

namespace boxgen::generator {

struct BoxSplineProperties {
  int degree = 0;                     // m - n
  int approximation_order = 0;        // rho
  int continuity = 0;                 // rho - 2 (C^k)
  Integer support_volume;             // sum over n-subsets of |det|
  Integer stencil_size;               // volume / |det G|
  bool linearly_independent = false;  // every n-subset has |det| in {0, |det G|}
};

BoxSplineProperties box_spline_properties(const BoxSplineSpec& spec);

}  // namespace boxgen::generator
