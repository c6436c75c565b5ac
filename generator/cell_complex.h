// The fine cell complex of docs/design.md §4: integer levels of every knot normal plus the coordinate
// axes. Each cell is a convex polytope inside one unit cube, kept with its exact vertices and
// the slab constraints level <= nu.x <= level + 1 that define it.
#pragma once
#include <unordered_map>
#include <vector>

#include "generator/cell_key.h"
#include "generator/poly.h"

namespace boxgen {

struct FineCell {
  CellKey key;                   // floor(nu . x) for every arrangement normal
  std::vector<RatVec> vertices;  // exact, distinct
  RatVec interior;               // vertex mean: strictly inside
};

class CellComplex {
 public:
  // Cells of all unit cubes with lower corners in [lo, hi) (componentwise).
  CellComplex(std::vector<IntVec> normals, IntVec lo, IntVec hi);

  int dimension() const { return n_; }
  const std::vector<IntVec>& normals() const { return normals_; }
  const std::vector<FineCell>& cells() const { return cells_; }
  const IntVec& lo() const { return lo_; }
  const IntVec& hi() const { return hi_; }
  // Index of the cell with this key, or -1 if it is not in the box.
  int find(const CellKey& key) const;
  // Cells of one unit cube (exposed for point location of arbitrary points).
  static std::vector<FineCell> split_cube(const std::vector<IntVec>& normals, const IntVec& corner);

 private:
  int n_;
  std::vector<IntVec> normals_;
  IntVec lo_, hi_;
  std::vector<FineCell> cells_;
  std::unordered_map<CellKey, int, CellKeyHash> index_;
};

// Facets of a cell: for each normal index and side (level or level + 1) holding an (n-1)-face.
struct Facet {
  int normal;
  std::int32_t level;   // the plane nu . x = level
  bool upper;           // true if the plane is the cell's upper side (key + 1)
  std::vector<RatVec> vertices;
};
std::vector<Facet> facets_of(const FineCell& cell, const std::vector<IntVec>& normals);
// Affine rank of a point set (0 for one point).
int affine_rank(const std::vector<RatVec>& points);
// Pulling triangulation of a convex cell into simplices (each n+1 vertices).
std::vector<std::vector<RatVec>> triangulate(const FineCell& cell, const std::vector<IntVec>& normals);
// A plane nu . x = level.
struct Plane {
  IntVec nu;
  Rational level;
};
// Pulling triangulation of the convex polytope with these vertices, whose faces lie on `planes`.
std::vector<std::vector<RatVec>> triangulate_polytope(const std::vector<RatVec>& vertices,
                                                      const std::vector<Plane>& planes);

}  // namespace boxgen
