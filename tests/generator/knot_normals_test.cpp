// Knot-plane normals, derived by hand for small matrices.
#include "generator/knot_normals.h"

#include <gtest/gtest.h>

#include <set>

namespace boxgen::generator {
namespace {

std::set<IntVec> as_set(const std::vector<IntVec>& v) { return {v.begin(), v.end()}; }

TEST(KnotNormals, PlanarLinesGiveTheirPrimitiveNormals) {
  // The lines spanned by (1,0), (0,1), (2,2) have normals (0,1), (1,0), (1,-1); (2,2) and a
  // repeated column add nothing new.
  const auto normals = knot_normals({{1, 0}, {0, 1}, {2, 2}, {1, 1}}, 2);
  EXPECT_EQ(as_set(normals), (std::set<IntVec>{{0, 1}, {1, 0}, {1, -1}}));
  EXPECT_EQ(normals.size(), 3u);
  EXPECT_TRUE(std::is_sorted(normals.begin(), normals.end()));
}

TEST(KnotNormals, ArrangementPutsTheAxesFirst) {
  const auto normals = arrangement_normals({{1, 0}, {0, 1}, {1, 1}}, 2);
  EXPECT_EQ(as_set(normals), (std::set<IntVec>{{0, 1}, {1, 0}, {1, -1}}));
  ASSERT_GE(normals.size(), 2u);
  EXPECT_EQ(as_set({normals[0], normals[1]}), (std::set<IntVec>{{0, 1}, {1, 0}}));
}

TEST(KnotNormals, SpatialPlanesOfThreeAxes) {
  // e1, e2, e3 and (1,1,1): planes spanned by pairs.
  const auto normals = knot_normals({{1, 0, 0}, {0, 1, 0}, {0, 0, 1}, {1, 1, 1}}, 3);
  EXPECT_EQ(
      as_set(normals),
      (std::set<IntVec>{{1, 0, 0}, {0, 1, 0}, {0, 0, 1}, {0, 1, -1}, {1, 0, -1}, {1, -1, 0}}));
}

TEST(KnotNormals, BasisFirstMovesAnIndependentSetToTheFront) {
  const IntColumns reordered = basis_first({{1, 1}, {2, 2}, {0, 1}}, 2);
  EXPECT_EQ(reordered, (IntColumns{{1, 1}, {0, 1}, {2, 2}}));
}

}  // namespace
}  // namespace boxgen::generator
