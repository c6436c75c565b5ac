// rho(Xi): the least number of columns whose removal leaves a set that does not span R^n.
// Expected values are counted by hand for each matrix.
#include "generator/approximation_order.h"

#include <gtest/gtest.h>

namespace boxgen::generator {
namespace {

TEST(ApproximationOrder, PlanarSetsCountedByHand) {
  // Three pairwise independent directions: dropping two leaves one line.
  EXPECT_EQ(approximation_order({{1, 0}, {0, 1}, {1, 1}}, 2), 2);
  // Four pairwise independent directions (Zwart-Powell): dropping three leaves one line.
  EXPECT_EQ(approximation_order({{1, 0}, {0, 1}, {1, 1}, {-1, 1}}, 2), 3);
  // Tensor product of two cubic B-splines: dropping the four copies of e1 leaves e2 alone.
  EXPECT_EQ(
      approximation_order({{1, 0}, {1, 0}, {1, 0}, {1, 0}, {0, 1}, {0, 1}, {0, 1}, {0, 1}}, 2), 4);
  // Parallel columns (and a negated copy) count as one line.
  EXPECT_EQ(approximation_order({{1, 0}, {-2, 0}, {0, 1}}, 2), 1);
}

TEST(ApproximationOrder, SpatialSets) {
  EXPECT_EQ(approximation_order({{1, 0, 0}, {0, 1, 0}, {0, 0, 1}}, 3), 1);
  // M7 = Xi1 + Xi2 on BCC: order 4 (the paper's Table 1). Removing the three axes leaves Xi1,
  // which spans; removing any four columns leaves three that are dependent or not.
  const IntColumns m7{{1, 1, 1}, {1, -1, -1}, {-1, 1, -1}, {-1, -1, 1},
                      {2, 0, 0}, {0, 2, 0},   {0, 0, 2}};
  EXPECT_EQ(approximation_order(m7, 3), 4);
}

TEST(ApproximationOrder, NonSpanningColumnsHaveOrderZero) {
  EXPECT_EQ(approximation_order({{1, 0}, {2, 0}}, 2), 0);
  EXPECT_EQ(approximation_order({{1, 0, 0}, {0, 1, 0}, {1, 1, 0}}, 3), 0);
}

}  // namespace
}  // namespace boxgen::generator
