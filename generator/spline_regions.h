// The polynomial structure of the spline s(x) = sum_j V(j) M(x - j) (docs/design.md §7, paper 4.2).
//
// Frames: fine cells are kept in the UNCENTRED frame u of M_Xi; the user's (centred) frame is
// x = u - c, c = sum(Xi)/2. A stencil point j is the same lattice point in both frames because
// M(x - j) = |det G| M_Xi(u - j).
//
// The fundamental region F is the union of the unit cubes at the coset representatives of
// Z^n / L. Its fine cells are merged into regions (maximal sets with one spline polynomial,
// modulo lattice translations); regions fall into orbits of the space group x -> g x + l
// (g in the symmetry group, l in L); each orbit has one reference region, to which every region
// maps by such an x -> g x + l (the generalisation of the paper's Algorithm 1).
#pragma once
#include "generator/cell_complex.h"
#include "generator/piecewise_form.h"
#include "generator/symmetry.h"

namespace boxgen::generator {

struct FundamentalCell {
  FineCell cell;  // uncentred frame, inside F
  int region = -1;
  IntVec placement;  // cell + placement is where the cell sits in its region's geometry
};

struct SpaceGroupElement {
  SignedPermutation g;
  IntVec l;  // x -> g x + l in the centred frame
  RatVec apply(const RatVec& x) const;
};

struct SplineRegion {
  std::vector<int> cells;        // fundamental cells (with their placements)
  std::vector<RatVec> vertices;  // centred frame, vertices of the (convex) region
  std::vector<Plane> planes;     // centred frame, the planes of its boundary facets
  RatVec centroid;               // centred, mean of the vertices
  int orbit = -1;
  SpaceGroupElement to_reference;  // maps this region onto its orbit's reference region
};

struct ReferenceRegion {
  std::vector<RatVec> vertices;  // centred frame
  std::vector<Plane> planes;
  RatVec interior;                      // a point strictly inside (centred)
  std::vector<IntVec> stencil;          // lattice points j, sorted
  std::vector<int> stencil_knot_cells;  // per stencil point: the knot cell of M_Xi it takes
  std::vector<Poly> basis;              // M(x - j) on the region, x centred, M = |det G| M^c
  int regions_in_orbit = 0;             // per fundamental region
};

struct SplineStructure {
  RatVec centre;  // c
  std::vector<SignedPermutation> group;
  std::vector<FundamentalCell> cells;
  std::vector<SplineRegion> regions;
  std::vector<ReferenceRegion> references;  // one per orbit
  int stencil_min = 0, stencil_max = 0;
  // 1, or the common factor k of a scaled pair (k Xi, k G) (generator/common_scale.h): then the
  // structure was derived on (Xi, G) and stretched back, and the fine cells' keys (with the unit
  // cubes of F they name) are those of the reduced frame x / k. Every other member, the cells'
  // vertices and placements included, is in the user's frame.
  std::int64_t scale = 1;
};

// For a scaled pair (k Xi, k G), derived on (Xi, G) and stretched back (scale = k).
SplineStructure spline_structure(const PiecewiseForm& form);

// Throws InternalError unless sum_j M(x - j) = 1 identically on every fundamental cell (full), or
// on every reference region (the default: each fine cell lies in a region, where the stencil's
// pieces are those of its reference region mapped by a symmetry and a lattice translation,
// both of which keep the sum). Exact: each distinct term (knot cell, j) is converted once to
// integer numerators over one common denominator, and the sums are integer sums (poly_sum.h).
void check_partition_of_unity(const PiecewiseForm& form, const SplineStructure& s,
                              bool full = true);

}  // namespace boxgen::generator
