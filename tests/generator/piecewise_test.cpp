// The piecewise form against the independent de Boor-Hoellig recurrence, the two derivations
// against each other, and the exact checks against deliberately broken forms (so they can fail).
#include <gtest/gtest.h>

#include "generator/error.h"
#include "generator/piece_checks.h"
#include "generator/recurrence.h"
#include "tests/generator/analysis_fixture.h"

namespace boxgen {
namespace {

using testing::analysis_of;

// Generic points: coordinates with large prime denominators, spread over and beyond the support.
std::vector<RatVec> generic_points(const PiecewiseForm& form, int count) {
  const int n = form.dimension();
  static const long primes[] = {10007, 10009, 10037, 10039, 10061, 10067};
  std::vector<RatVec> out;
  std::uint64_t state = 12345;
  auto next = [&] {
    state = state * 6364136223846793005ull + 1442695040888963407ull;
    return static_cast<long>((state >> 33) % 20000);
  };
  std::vector<size_t> support_cells;
  for (size_t i = 0; i < form.polys.size(); ++i)
    if (!form.polys[i].is_zero()) support_cells.push_back(i);
  for (int k = 0; k < count; ++k) {
    RatVec x(n);
    if (k % 2 == 0) {  // near the interior point of a cell of the support
      const auto& cell = form.knots.cells()[support_cells[static_cast<size_t>(next()) % support_cells.size()]];
      for (int i = 0; i < n; ++i) x[i] = cell.interior[i] + Rational(1) / Rational(50 * primes[(k + i) % 6]);
      out.push_back(x);
      continue;
    }
    for (int i = 0; i < n; ++i) {  // anywhere in the bounding box, one unit beyond
      const long span = form.complex.hi()[i] - form.complex.lo()[i] + 2;  // one unit beyond each side
      const Rational t = Rational(next()) / Rational(20000);
      x[i] = Rational(form.complex.lo()[i] - 1) + t * Rational(span) + Rational(1) / Rational(primes[(k + i) % 6]);
    }
    out.push_back(x);
  }
  return out;
}

class PiecewisePreset : public ::testing::TestWithParam<const char*> {};

TEST_P(PiecewisePreset, AgreesWithTheRecurrenceAtGenericPoints) {
  const Analysis& a = analysis_of(GetParam());
  BoxSplineRecurrence recurrence(a.spec.directions);
  int inside = 0;
  for (const auto& x : generic_points(a.form, 240)) {
    const Rational expected = recurrence.value(x);
    EXPECT_EQ(a.form.value_at(x), expected) << GetParam();
    inside += !cln::zerop(expected);
  }
  EXPECT_GT(inside, 100) << "too few points inside the support to be a test";
}

TEST_P(PiecewisePreset, TwoDerivationsAgreeCellByCell) {
  const Analysis& a = analysis_of(GetParam());
  const PiecewiseForm other = derive_piecewise(a.spec, DerivationMethod::DirectionalIntegration);
  ASSERT_EQ(other.polys.size(), a.form.polys.size());
  int nonzero = 0;
  for (size_t i = 0; i < other.polys.size(); ++i) {
    EXPECT_EQ(other.polys[i], a.form.polys[i]) << GetParam() << " cell " << i;
    nonzero += !other.polys[i].is_zero();
  }
  EXPECT_GT(nonzero, 0);
}

INSTANTIATE_TEST_SUITE_P(Presets, PiecewisePreset, ::testing::ValuesIn(testing::kAllPresets),
                         [](const auto& p) { return std::string(p.param); });

// A copy of M7's form with one nonzero piece changed by a tiny amount.
PiecewiseForm broken_m7(const Poly& change) {
  PiecewiseForm f = analysis_of("m7").form;
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
  EXPECT_EQ(total_integral(analysis_of("m7").form), 1);
}

TEST(ExactChecks, IntegralOfCellsCutBySlopeOneHalf) {
  // The knot line x - 2y = k cuts unit squares into triangles and quadrilaterals; a quadrilateral
  // is not a unit square although it has 2^2 vertices, and must be triangulated (the unit-cube
  // shortcut once took it for one, and these splines failed their integral check).
  for (const char* spec : {"1,0;2,1", "1,0;1,2", "1,0;0,1;1,1;1,-1;2,1"}) {
    const PiecewiseForm f = derive_piecewise(parse_spec(spec), DerivationMethod::DirectionalIntegration);
    EXPECT_EQ(total_integral(f), 1) << spec;
  }
}

TEST(ExactChecks, DetectABrokenSymmetry) {
  const auto f = broken_m7(Poly::constant(3, Rational(1) / 1000));
  EXPECT_THROW(check_symmetry(f, analysis_of("m7").structure.group), InternalError);
}

TEST(ExactChecks, DetectBrokenContinuity) {
  // Adding (x - c)^3 inside one cell keeps C^2 only if the cell is bounded by x = c on both
  // sides, which it is not: a jump of order < 3 appears on some face.
  const auto f = broken_m7(Poly::affine({Rational(0), Rational(1) / 1000, 0, 0}));
  EXPECT_THROW(check_continuity(f, 3), InternalError);
}

TEST(ExactChecks, ContinuityOrderIsSharp) {
  // M7 is C^2 and not C^3: asking for order 4 (C^3) must fail somewhere.
  EXPECT_THROW(check_continuity(analysis_of("m7").form, 4), InternalError);
}

TEST(Eval, ValueOnAKnotPlaneIsTheContinuousLimit) {
  // M7 is continuous: at a point on knot planes the adjacent pieces agree.
  const auto& form = analysis_of("m7").form;
  EXPECT_NO_THROW(form.value_at({1, 1, 1}));
  // The first derivative of the C^0 Courant element jumps across its knot lines.
  const auto& hat = analysis_of("hex3").form;
  EXPECT_EQ(hat.value_at({1, 1}), 1);  // the apex, uncentred frame
  EXPECT_THROW(hat.value_at({1, 1}, {1, 0, 0}), InputError);
}

}  // namespace
}  // namespace boxgen
