// Small exact integer linear algebra, checked on matrices worked out by hand.
#include "generator/int_linalg.h"

#include <gtest/gtest.h>

namespace boxgen::generator {
namespace {

TEST(IntLinalg, DeterminantAndRank) {
  EXPECT_EQ(det({{1, 3}, {2, 4}}), -2);                     // columns (1,3), (2,4)
  EXPECT_EQ(det({{-1, 1, 1}, {1, -1, 1}, {1, 1, -1}}), 4);  // the BCC generator
  EXPECT_EQ(rank({{1, 2, 3}, {2, 4, 6}}, 3), 1);
  EXPECT_EQ(rank({{1, 0, 0}, {0, 1, 0}, {1, 1, 0}}, 3), 2);
  EXPECT_EQ(rank({{1, 0, 0}, {0, 1, 0}, {1, 1, 1}}, 3), 3);
}

TEST(IntLinalg, PrimitiveAndCanonicalVectors) {
  EXPECT_EQ(gcd_of({4, -6, 8}), 2);
  EXPECT_EQ(sign_canonical({0, -2, 3}), (IntVec{0, 2, -3}));
  EXPECT_EQ(sign_canonical({0, 2, -3}), (IntVec{0, 2, -3}));
  EXPECT_EQ(primitive({0, -4, 6}), (IntVec{0, 2, -3}));
}

TEST(IntLinalg, HyperplaneNormals) {
  EXPECT_EQ(hyperplane_normal({{1, 0, 0}, {0, 1, 0}}, 3), (IntVec{0, 0, 1}));
  const auto n = hyperplane_normal({{1, 1, 1}, {1, -1, -1}}, 3);
  ASSERT_TRUE(n);
  EXPECT_EQ(dot(*n, IntVec{1, 1, 1}), 0);
  EXPECT_EQ(dot(*n, IntVec{1, -1, -1}), 0);
  EXPECT_FALSE(hyperplane_normal({{1, 1, 1}, {2, 2, 2}}, 3));
  const auto line = hyperplane_normal({{1, 1}}, 2);
  ASSERT_TRUE(line);
  EXPECT_EQ(dot(*line, IntVec{1, 1}), 0);
}

TEST(IntLinalg, SolveAndInverse) {
  // [[2, 1], [1, 3]] x = (3, 4) has x = (1, 1).
  EXPECT_EQ(solve({{2, 1}, {1, 3}}, {3, 4}), (RatVec{1, 1}));
  EXPECT_FALSE(solve({{1, 2}, {2, 4}}, {1, 1}));
  // G^-1 G = I for the BCC generator, entry by entry.
  const IntColumns g{{-1, 1, 1}, {1, -1, 1}, {1, 1, -1}};
  const RatMatrix inv = inverse(g);
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) {
      Rational s = 0;
      for (int k = 0; k < 3; ++k) s = s + inv[i][k] * Rational(g[j][k]);
      EXPECT_EQ(s, i == j ? 1 : 0) << i << "," << j;
    }
}

}  // namespace
}  // namespace boxgen::generator
