// The exact checks of generator/piece_checks.h, on M7's derived form and on deliberately broken
// copies of it, so that each check is shown to fail when it should.
#include "generator/piece_checks.h"

#include <gtest/gtest.h>

#include "generator/error.h"
#include "tests/generator/derivation_fixture.h"

namespace boxgen::generator {
namespace {

using fixture::derivation_of;

// A copy of M7's form with one nonzero piece changed by a tiny amount.
PiecewiseForm broken_m7(const Poly& change) {
  PiecewiseForm f = derivation_of("m7").form;
  for (auto& p : f.polys)
    if (!p.is_zero()) {
      p += change;
      break;
    }
  return f;
}

TEST(ExactChecks, DetectABrokenIntegral) {
  const auto f = broken_m7(Poly::constant(3, Rational(1) / 1000));
  EXPECT_NE(total_integral(f), 1);
  EXPECT_EQ(total_integral(derivation_of("m7").form), 1);
}

TEST(ExactChecks, IntegralOfCellsCutBySlopeOneHalf) {
  // The knot line x - 2y = k cuts unit squares into triangles and quadrilaterals; a quadrilateral
  // is not a unit square although it has 2^2 vertices, and must be triangulated (the unit-cube
  // shortcut once took it for one, and these splines failed their integral check).
  for (const char* spec : {"1,0;2,1", "1,0;1,2", "1,0;0,1;1,1;1,-1;2,1"}) {
    const PiecewiseForm f =
        derive_piecewise(parse_spec(spec), DerivationMethod::DirectionalIntegration);
    EXPECT_EQ(total_integral(f), 1) << spec;
  }
}

TEST(ExactChecks, DetectABrokenSymmetry) {
  const auto f = broken_m7(Poly::constant(3, Rational(1) / 1000));
  EXPECT_THROW(check_symmetry(f, derivation_of("m7").structure.group), InternalError);
}

TEST(ExactChecks, DetectBrokenContinuity) {
  // Adding (x - c)^3 inside one cell keeps C^2 only if the cell is bounded by x = c on both
  // sides, which it is not: a jump of order < 3 appears on some face.
  const auto f = broken_m7(Poly::affine({Rational(0), Rational(1) / 1000, 0, 0}));
  EXPECT_THROW(check_continuity(f, 3), InternalError);
}

TEST(ExactChecks, ContinuityOrderIsSharp) {
  // M7 is C^2 and not C^3: asking for order 4 (C^3) must fail somewhere.
  EXPECT_THROW(check_continuity(derivation_of("m7").form, 4), InternalError);
}

}  // namespace
}  // namespace boxgen::generator
