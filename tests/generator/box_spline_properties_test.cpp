// Properties read from the direction matrix alone, for small matrices whose determinants are
// summed by hand (support volume = sum over n-subsets Z of |det Z|).
#include "generator/box_spline_properties.h"

#include <gtest/gtest.h>

namespace boxgen::generator {
namespace {

TEST(BoxSplineProperties, ThreeDirectionPlanarSpline) {
  // (1,0), (0,1), (1,1): the three 2-subsets have |det| 1, 1, 1.
  const BoxSplineProperties p = box_spline_properties(parse_spec("1,0; 0,1; 1,1"));
  EXPECT_EQ(p.degree, 1);
  EXPECT_EQ(p.approximation_order, 2);
  EXPECT_EQ(p.continuity, 0);
  EXPECT_EQ(p.support_volume, 3);
  EXPECT_EQ(p.stencil_size, 3);
  EXPECT_TRUE(p.linearly_independent);
}

TEST(BoxSplineProperties, ZwartPowellElement) {
  // (1,0), (0,1), (1,1), (-1,1): |det| of the six pairs is 1, 1, 1, 1, 1 and 2 for
  // (1,1),(-1,1); the 2 breaks linear independence on Z^2.
  const BoxSplineProperties p = box_spline_properties(parse_spec("1,0; 0,1; 1,1; -1,1"));
  EXPECT_EQ(p.degree, 2);
  EXPECT_EQ(p.approximation_order, 3);
  EXPECT_EQ(p.continuity, 1);
  EXPECT_EQ(p.support_volume, 7);
  EXPECT_EQ(p.stencil_size, 7);
  EXPECT_FALSE(p.linearly_independent);
}

TEST(BoxSplineProperties, StencilSizeDividesByTheLatticeDeterminant) {
  // The same planar matrix on the lattice 2Z x Z (|det G| = 2) with even first coordinates:
  // (2,0), (0,1), (2,1): pairs |det| 2, 2, 2; volume 6, stencil 3, and every |det| is |det G|.
  const BoxSplineProperties p = box_spline_properties(parse_spec("2,0; 0,1; 2,1", "2,0; 0,1"));
  EXPECT_EQ(p.support_volume, 6);
  EXPECT_EQ(p.stencil_size, 3);
  EXPECT_TRUE(p.linearly_independent);
}

}  // namespace
}  // namespace boxgen::generator
