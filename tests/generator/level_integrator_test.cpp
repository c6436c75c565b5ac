// Directional integration on a matrix whose box spline and truncated power are known by hand:
// columns e1, e2, e1 give M(x, y) = B(x) on 0 < y < 1 with the hat B of [0, 2] (B = x, then
// 2 - x), and the truncated power T(x, y) = x on the quadrant x, y > 0.
#include "generator/level_integrator.h"

#include <gtest/gtest.h>

namespace boxgen::generator {
namespace {

const IntColumns kColumns{{1, 0}, {0, 1}, {1, 0}};

TEST(LevelIntegrator, UnitSegmentsGiveTheHat) {
  LevelIntegrator integrator(kColumns, 2, IntegrationPath::UnitSegment);
  EXPECT_EQ(integrator.top({Rational(1) / 2, Rational(1) / 3}), Poly::affine({0, 1, 0}));
  EXPECT_EQ(integrator.top({Rational(3) / 2, Rational(1) / 3}), Poly::affine({2, -1, 0}));
  EXPECT_TRUE(integrator.top({Rational(5) / 2, Rational(1) / 3}).is_zero());
  EXPECT_TRUE(integrator.top({Rational(1) / 2, Rational(4) / 3}).is_zero());
}

TEST(LevelIntegrator, RaysGiveTheTruncatedPower) {
  LevelIntegrator integrator(kColumns, 2, IntegrationPath::Ray);
  EXPECT_EQ(integrator.top({Rational(1) / 2, Rational(1) / 3}), Poly::affine({0, 1, 0}));
  EXPECT_EQ(integrator.top({Rational(7) / 2, Rational(5) / 3}), Poly::affine({0, 1, 0}));
  EXPECT_TRUE(integrator.top({Rational(-1) / 2, Rational(1) / 3}).is_zero());
}

}  // namespace
}  // namespace boxgen::generator
