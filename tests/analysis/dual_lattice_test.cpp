// The Nyquist region as the Voronoi cell of the dual lattice, against the known polytopes:
// BCC's dual is pi * FCC and its cell the rhombic dodecahedron |w_i| + |w_j| <= pi (volume
// 2 pi^3, 12 faces, 14 vertices); FCC's cell the truncated octahedron (volume 4 pi^3, 14 faces,
// 24 vertices); the Cartesian cell the cube [-pi, pi]^n.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "analysis/dual_lattice.h"
#include "generator/spec.h"

namespace boxgen::analysis {
namespace {

using namespace ::boxgen::generator;  // NOLINT(google-build-using-namespace): the generator's
                                      // lattices and SPECs

DualLattice dual_of(const Lattice& l) { return DualLattice(l.generator()); }

TEST(DualLattice, BasisIsTwoPiTimesInverseTranspose) {
  const Lattice bcc = Lattice::bcc();
  const DualLattice d = dual_of(bcc);
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) {
      double dot = 0;
      for (int r = 0; r < 3; ++r)
        dot += d.basis()[i][r] * static_cast<double>(bcc.generator()[j][r]);
      EXPECT_NEAR(dot, i == j ? 2 * std::numbers::pi : 0, 1e-12);
    }
}

TEST(DualLattice, BccCellIsTheRhombicDodecahedron) {
  const DualLattice d = dual_of(Lattice::bcc());
  const VoronoiCell& c = d.cell();
  EXPECT_EQ(c.faces.size(), 12u);
  EXPECT_EQ(c.vertices.size(), 14u);
  EXPECT_NEAR(c.volume, 2 * std::numbers::pi * std::numbers::pi * std::numbers::pi, 1e-9);
  for (const auto& v : c.vertices) {  // every vertex on |w_i| + |w_j| <= pi with equality somewhere
    double worst = 0;
    for (int i = 0; i < 3; ++i)
      for (int j = i + 1; j < 3; ++j) worst = std::max(worst, std::abs(v[i]) + std::abs(v[j]));
    EXPECT_NEAR(worst, std::numbers::pi, 1e-9);
  }
  EXPECT_TRUE(c.contains({std::numbers::pi / 2 - 1e-6, std::numbers::pi / 2 - 1e-6, 0}));
  EXPECT_FALSE(c.contains({std::numbers::pi / 2 + 1e-6, std::numbers::pi / 2 + 1e-6, 0}));
}

TEST(DualLattice, FccCellIsTheTruncatedOctahedron) {
  const DualLattice d = dual_of(Lattice::fcc());
  const VoronoiCell& c = d.cell();
  EXPECT_EQ(c.faces.size(), 14u);
  EXPECT_EQ(c.vertices.size(), 24u);
  EXPECT_NEAR(c.volume, 4 * std::numbers::pi * std::numbers::pi * std::numbers::pi, 1e-9);
}

TEST(DualLattice, CartesianCellsAreCubesAndSquares) {
  const DualLattice d3 = dual_of(Lattice::cartesian(3));
  const VoronoiCell& c3 = d3.cell();
  EXPECT_EQ(c3.faces.size(), 6u);
  EXPECT_EQ(c3.vertices.size(), 8u);
  EXPECT_NEAR(c3.volume, 8 * std::numbers::pi * std::numbers::pi * std::numbers::pi, 1e-9);
  const DualLattice d2 = dual_of(Lattice::cartesian(2));
  const VoronoiCell& c2 = d2.cell();
  EXPECT_EQ(c2.faces.size(), 4u);
  EXPECT_NEAR(c2.volume, 4 * std::numbers::pi * std::numbers::pi, 1e-9);
}

TEST(DualLattice, HexagonalCellOfASkewPlanarLattice) {
  // Columns (1,1), (1,-1): the checkerboard lattice {x + y even}, whose dual is again a square
  // lattice rotated by 45 degrees: the cell is a square of area (2 pi)^2 / 2.
  const DualLattice d(IntDirections{{1, 1}, {1, -1}});
  EXPECT_EQ(d.cell().faces.size(), 4u);
  EXPECT_NEAR(d.cell().volume, 2 * std::numbers::pi * std::numbers::pi, 1e-9);
  // Columns (2,0), (1,2) (det 4): an oblique lattice, whose dual's cell is a hexagon of area
  // (2 pi)^2 / 4.
  const DualLattice h(IntDirections{{2, 0}, {1, 2}});
  EXPECT_EQ(h.cell().faces.size(), 6u);
  EXPECT_NEAR(h.cell().volume, 4 * std::numbers::pi * std::numbers::pi / 4, 1e-9);
}

TEST(DualLattice, NearestPointAndBoundaryGap) {
  const DualLattice d = dual_of(Lattice::bcc());
  double gap = -1;
  const Vec k =
      d.nearest({2 * std::numbers::pi - 0.1, 0.05, 0}, &gap);  // (2 pi, 0, 0) is a dual point
  EXPECT_NEAR(k[0], 2 * std::numbers::pi, 1e-12);
  EXPECT_NEAR(k[1], 0, 1e-12);
  EXPECT_GT(gap, 0.05);
  d.nearest({std::numbers::pi / 2, std::numbers::pi / 2, 0},
            &gap);  // on a face: two points equally near
  EXPECT_NEAR(gap, 0, 1e-12);
}

TEST(DualLattice, SingularGeneratorIsRefused) {
  EXPECT_THROW(DualLattice(IntDirections{{1, 1, 0}, {2, 2, 0}, {0, 0, 1}}), std::invalid_argument);
}

}  // namespace
}  // namespace boxgen::analysis
