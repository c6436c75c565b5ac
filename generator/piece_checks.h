// Exact checks and counts on the piecewise form of M_Xi (docs/design.md §5): distinct pieces, the
// integral, continuity across every internal face, and symmetry of the centred spline.
#pragma once
#include "generator/piecewise_form.h"
#include "generator/symmetry.h"

namespace boxgen::generator {

// Orbits of the knot cells under the symmetry group of the centred spline, x -> g(x - c) + c
// (the complex is symmetric, so each image of a cell is a cell): representatives and sizes.
struct CellOrbits {
  std::vector<int> representatives;  // one cell per orbit
  std::vector<int> sizes;            // cells in that orbit
};
CellOrbits cell_orbits(const PiecewiseForm& form, const std::vector<SignedPermutation>& group);

// Maximal connected unions of cells with one polynomial (nonzero cells only).
int count_pieces(const PiecewiseForm& form);
// Sum of the integrals of the pieces (1 for a box spline).
Rational total_integral(const PiecewiseForm& form);
// The same from one cell per orbit, weighted by the orbit's size (valid once the spline's
// symmetry is checked: the maps preserve volume and carry pieces onto pieces).
Rational total_integral(const PiecewiseForm& form, const CellOrbits& orbits);

struct ContinuityReport {
  int faces_checked = 0;
  int smoothness = 0;  // every face: the jump vanishes to this order (C^(smoothness-1))
  bool sharp = false;  // some face has a nonzero jump of order `smoothness`
};
// Checks that across every face nu.x = c the jump is divisible by (nu.x - c)^order;
// throws InternalError naming the face if not. Reports whether order is sharp.
ContinuityReport check_continuity(const PiecewiseForm& form, int order);
// The same on the faces of the given cells only (one per orbit suffices once symmetry is checked).
ContinuityReport check_continuity(const PiecewiseForm& form, int order,
                                  const std::vector<int>& cells);

// Throws InternalError unless M^c(g x) = M^c(x) on every cell for g in `group` (checked on a
// generating set, which implies the whole group) and for x -> -x.
void check_symmetry(const PiecewiseForm& form, const std::vector<SignedPermutation>& group);
// A small generating set of the group.
std::vector<SignedPermutation> generators(const std::vector<SignedPermutation>& group);

// Uncentred-frame affine image of a point under the centred symmetry g: g(y - c) + c.
RatVec symmetry_image(const SignedPermutation& g, const RatVec& y, const RatVec& centre);
RatVec spline_centre(const BoxSplineSpec& spec);  // sum(Xi)/2

}  // namespace boxgen::generator
