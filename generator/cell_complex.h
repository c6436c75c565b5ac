// Cell complexes of docs/design.md §4, each cell a convex polytope kept with its exact vertices:
//  - KnotComplex: the arrangement of the true knot planes of M_Xi (KnotPlanes) inside its
//    support, where each cell carries one polynomial piece; the derivation works on it;
//  - split_cube: the fine cells of one unit cube cut by every integer level of the normals plus
//    the axes, the refinement the emitter's lookup table uses (each fine cell lies in one
//    knot cell, whose polynomial it takes).
#pragma once
#include <unordered_map>
#include <vector>

#include "generator/cell_key.h"
#include "generator/knot_normals.h"
#include "generator/poly.h"

namespace boxgen::generator {

struct FineCell {
  CellKey key;                   // per normal: floor(nu . x) (fine) or the interval index (knot)
  std::vector<RatVec> vertices;  // exact, distinct
  RatVec interior;               // vertex mean: strictly inside
};

// Cells of one unit cube in the arrangement of integer levels of `normals` (axes first).
std::vector<FineCell> split_cube(const std::vector<IntVec>& normals, const IntVec& corner);
// The same for several cubes, in order. The arrangement is invariant under integer shifts, so
// one cube is split and the others are its translates (keys move by nu . shift): the same cells.
std::vector<FineCell> split_cubes(const std::vector<IntVec>& normals,
                                  const std::vector<IntVec>& corners);
// The same from the cells `unit` of the cube at the origin (split_cube(normals, 0)), split once.
std::vector<FineCell> translate_cells(const std::vector<FineCell>& unit,
                                      const std::vector<IntVec>& normals,
                                      const std::vector<IntVec>& corners);

class KnotComplex {
 public:
  // Cells of the knot-plane arrangement inside the box [lo, hi] and between the first and last
  // level of every normal (the support zonotope).
  KnotComplex(KnotPlanes planes, IntVec lo, IntVec hi);
  // The same complex shrunk by k (every level and box bound divisible by k): the cells keep their
  // order and keys, so an index names the same cell in both (generator/common_scale.h).
  KnotComplex scaled_down(std::int64_t k) const;

  int dimension() const { return static_cast<int>(lo_.size()); }
  const KnotPlanes& planes() const { return planes_; }
  const std::vector<FineCell>& cells() const { return cells_; }
  const IntVec& lo() const { return lo_; }
  const IntVec& hi() const { return hi_; }
  // Index of the cell with this key, or -1 (an empty cell or one outside the support).
  int find(const CellKey& key) const;
  // Index of the cell holding a point that lies on no knot plane, or -1 outside the support.
  int locate(const RatVec& x) const { return find(interval_key(planes_, x)); }

 private:
  KnotPlanes planes_;
  IntVec lo_, hi_;
  std::vector<FineCell> cells_;
  std::unordered_map<CellKey, int, CellKeyHash> index_;
};

// Exact point location of p - j in a knot complex for many integer shifts j (the stencil of a
// cell): the knot levels L are integers, so L < nu.(p - j) compares L + nu.j with floor(nu.p)
// (and with nu.p itself when that is an integer), all in machine integers whatever the
// denominators of p (falls back to rational arithmetic only if floor(nu.p) could overflow).
class ShiftLocator {
 public:
  ShiftLocator(const KnotComplex& knots, const RatVec& p);
  // Index of the knot cell holding p - j, or -1 outside the support. p - j must lie on no knot
  // plane.
  int cell_at(const IntVec& j) const;
  // The locator of p + l (integer l): the floors move by nu.l, no rational arithmetic.
  ShiftLocator translated(const IntVec& l) const;

 private:
  const KnotComplex* knots_;
  RatVec p_;
  bool small_ = false;
  std::vector<std::int64_t> floor_nu_p_;  // per normal: floor(nu.p)
  std::vector<bool> nu_p_integral_;       // per normal: nu.p is an integer
  mutable CellKey key_;  // reused: cell_at runs for every stencil candidate of every fine cell
};

// Facets of a cell: for each normal index and side (level or level + 1) holding an (n-1)-face.
struct Facet {
  int normal;
  std::int64_t level;  // the plane nu . x = level
  bool upper;          // true if the plane is the cell's upper side (key + 1)
  std::vector<RatVec> vertices;
};
std::vector<Facet> facets_of(const FineCell& cell, const std::vector<IntVec>& normals);
// The same for a cell of the knot complex (level = the knot level of the facet's plane).
std::vector<Facet> facets_of(const FineCell& cell, const KnotPlanes& planes);
// Affine rank of a point set (0 for one point), or cap if that is smaller (cap < 0: no cap). A
// caller that knows the points lie on a plane asks only whether they span it.
int affine_rank(const std::vector<RatVec>& points, int cap = -1);
// Pulling triangulation of a convex cell into simplices (each n+1 vertices).
std::vector<std::vector<RatVec>> triangulate(const FineCell& cell, const KnotComplex& complex);
// A plane nu . x = level.
struct Plane {
  IntVec nu;
  Rational level;
};
// Pulling triangulation of the convex polytope with these vertices, whose faces lie on `planes`.
std::vector<std::vector<RatVec>> triangulate_polytope(const std::vector<RatVec>& vertices,
                                                      const std::vector<Plane>& planes);

}  // namespace boxgen::generator
