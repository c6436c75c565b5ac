// The dual lattice 2 pi G^-T Z^n of a lattice L = G Z^n and its Voronoi cell around 0, the
// Nyquist region of sampling on L (docs/design.md §10). For BCC it is the rhombic dodecahedron
// |w_i| + |w_j| <= pi, volume 2 pi^3.
#pragma once
#include <cstdint>
#include <vector>

#include "analysis/spectrum.h"

namespace boxgen::analysis {

struct HalfSpace {
  Vec normal;     // a dual lattice point k
  double offset;  // |k|^2 / 2: the cell is {w : k.w <= |k|^2/2}
};

// A convex polytope (the Voronoi cell) in R^n, n = 2 or 3.
struct VoronoiCell {
  int n = 3;
  std::vector<HalfSpace> faces;  // only the facet-defining ones
  std::vector<Vec> vertices;
  // n = 3: per face, its vertices (indices) in cyclic order; n = 2: per face, its two vertices.
  std::vector<std::vector<int>> face_vertices;
  double volume = 0;  // from the simplex fan around 0
  bool contains(const Vec& w, double tolerance = 1e-12) const;
};

class DualLattice {
 public:
  // `generator`: the columns of G (n columns of length n, n = 2 or 3). Throws
  // std::invalid_argument if G is singular.
  explicit DualLattice(const IntDirections& generator);
  int dimension() const { return n_; }
  const std::vector<Vec>& basis() const { return basis_; }  // columns of 2 pi G^-T
  double det_g() const { return det_g_; }                   // |det G|
  Vec point(const std::vector<std::int64_t>& c) const;      // sum c_i basis_i
  // Every dual lattice point with |k| <= radius.
  std::vector<Vec> points_within(double radius) const;
  // The Voronoi cell of 0 (its volume is (2 pi)^n / |det G|).
  const VoronoiCell& cell() const { return cell_; }
  // The dual lattice point nearest to w and the distance gap to the second nearest (0 on a
  // Voronoi boundary).
  Vec nearest(const Vec& w, double* gap = nullptr) const;

 private:
  // Every nonzero dual point with coefficients in [-range, range], shortest first.
  std::vector<Vec> short_points(int range) const;
  void build_voronoi_cell();

  int n_;
  std::vector<Vec> basis_;
  double det_g_;
  VoronoiCell cell_;
  double covering_radius_ = 0;
};

// Vertices of the polytope {a_i . w <= b_i} in R^n (n = 1, 2, 3) by intersecting every n of
// its constraints; duplicates merged. Exposed for the quadrature's slices.
std::vector<Vec> polytope_vertices(const std::vector<HalfSpace>& constraints, int n,
                                   double tolerance = 1e-10);

}  // namespace boxgen::analysis
