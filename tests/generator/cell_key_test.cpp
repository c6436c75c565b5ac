// Cell keys of hyperplane arrangements, at points placed by hand.
#include "generator/cell_key.h"

#include <gtest/gtest.h>

namespace boxgen::generator {
namespace {

const std::vector<IntVec> kNormals{{1, 0}, {1, 1}};

TEST(CellKey, FloorKeyCountsIntegerLevels) {
  EXPECT_EQ(floor_key(kNormals, {Rational(1) / 2, Rational(3) / 2}), (CellKey{0, 2}));
  EXPECT_EQ(floor_key(kNormals, {Rational(-1) / 2, Rational(1) / 4}), (CellKey{-1, -1}));
  // On a plane the key is the upper side's (floor of an integer is itself).
  EXPECT_EQ(floor_key(kNormals, {Rational(1), Rational(0)}), (CellKey{1, 1}));
}

TEST(CellKey, SignKeyOfTheCentralArrangement) {
  EXPECT_EQ(sign_key(kNormals, {Rational(1) / 2, Rational(3) / 2}), (CellKey{0, 0}));
  EXPECT_EQ(sign_key(kNormals, {Rational(-1) / 2, Rational(1) / 4}), (CellKey{-1, -1}));
  EXPECT_EQ(sign_key(kNormals, {Rational(-1) / 2, Rational(1)}), (CellKey{-1, 0}));
}

TEST(CellKey, OffIntegerPlanes) {
  EXPECT_TRUE(off_integer_planes(kNormals, {Rational(1) / 2, Rational(1) / 3}));   // 1/2, 5/6
  EXPECT_FALSE(off_integer_planes(kNormals, {Rational(1) / 2, Rational(1) / 2}));  // x + y = 1
  EXPECT_FALSE(off_integer_planes(kNormals, {Rational(2), Rational(1) / 3}));      // x = 2
  EXPECT_NE(CellKeyHash{}(CellKey{0, 1}), CellKeyHash{}(CellKey{1, 0}));
}

}  // namespace
}  // namespace boxgen::generator
