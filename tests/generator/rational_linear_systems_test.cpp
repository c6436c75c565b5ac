// Exact row reduction on systems solved by hand.
#include "generator/rational_linear_systems.h"

#include <gtest/gtest.h>

namespace boxgen::generator {
namespace {

TEST(RationalLinearSystems, UniqueSolution) {
  // x + y = 3, x - y = 1.
  const auto s = solve_exactly({{1, 1, 3}, {1, -1, 1}}, 2);
  ASSERT_TRUE(s);
  EXPECT_EQ(s->values, (RatVec{2, 1}));
  EXPECT_TRUE(s->free_columns.empty());
  // 3x = 1: a fraction, exactly.
  EXPECT_EQ(solve_exactly({{3, 1}}, 1)->values, (RatVec{Rational(1) / 3}));
}

TEST(RationalLinearSystems, InconsistentSystemHasNoSolution) {
  EXPECT_FALSE(solve_exactly({{1, 1, 1}, {2, 2, 3}}, 2));
}

TEST(RationalLinearSystems, FreeUnknownsAreTheLastAndSetToZero) {
  // x + y + z = 1: pivot on x, y and z free.
  const auto s = solve_exactly({{1, 1, 1, 1}}, 3);
  ASSERT_TRUE(s);
  EXPECT_EQ(s->values, (RatVec{1, 0, 0}));
  EXPECT_EQ(s->free_columns, (std::vector<int>{1, 2}));
}

TEST(RationalLinearSystems, NullSpaceVectorsSolveTheHomogeneousSystem) {
  const std::vector<RatVec> rows{{1, 1, 1}, {1, -1, 0}};
  const auto basis = null_space(rows, 3);
  ASSERT_EQ(basis.size(), 1u);  // rank 2 in 3 unknowns
  for (const auto& row : rows) {
    Rational s = 0;
    for (int k = 0; k < 3; ++k) s = s + row[k] * basis[0][k];
    EXPECT_EQ(s, 0);
  }
  EXPECT_FALSE(cln::zerop(basis[0][2]));
  EXPECT_EQ(null_space({{1, 0}, {0, 1}}, 2).size(), 0u);
}

}  // namespace
}  // namespace boxgen::generator
