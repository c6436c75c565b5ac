// The support's bounding box, against boxes summed by hand: each axis runs from the sum of the
// directions' negative entries to the sum of their positive ones.
#include "generator/zonotope.h"

#include <gtest/gtest.h>

namespace boxgen::generator {
namespace {

TEST(Zonotope, BoxOfM7OnBcc) {
  // (1,1,1), (1,-1,-1), (-1,1,-1), (-1,-1,1), (2,0,0), (0,2,0), (0,0,2): per axis two -1s and
  // 1 + 1 + 2.
  const IntColumns m7{{1, 1, 1}, {1, -1, -1}, {-1, 1, -1}, {-1, -1, 1},
                      {2, 0, 0}, {0, 2, 0},   {0, 0, 2}};
  const Zonotope box(m7, 3);
  EXPECT_EQ(box.box_lo(), (IntVec{-2, -2, -2}));
  EXPECT_EQ(box.box_hi(), (IntVec{4, 4, 4}));
}

TEST(Zonotope, BoxOfTheZwartPowellElement) {
  // (1,0), (0,1), (1,1), (-1,1): x from -1 to 2, y from 0 to 3.
  const Zonotope box(IntColumns{{1, 0}, {0, 1}, {1, 1}, {-1, 1}}, 2);
  EXPECT_EQ(box.box_lo(), (IntVec{-1, 0}));
  EXPECT_EQ(box.box_hi(), (IntVec{2, 3}));
}

}  // namespace
}  // namespace boxgen::generator
