// The piecewise form (generator/piecewise_form.h) against the independent de Boor-Hoellig
// recurrence, and exact point values on knot planes. The two derivations are compared in
// box_spline_derivation_test.cpp, the exact checks in piece_checks_test.cpp.
#include <gtest/gtest.h>

#include "generator/error.h"
#include "generator/piece_checks.h"
#include "generator/recurrence.h"
#include "tests/generator/derivation_fixture.h"

namespace boxgen::generator {
namespace {

using fixture::derivation_of;

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
      const auto& cell =
          form.knots.cells()[support_cells[static_cast<size_t>(next()) % support_cells.size()]];
      for (int i = 0; i < n; ++i)
        x[i] = cell.interior[i] + Rational(1) / Rational(50 * primes[(k + i) % 6]);
      out.push_back(x);
      continue;
    }
    for (int i = 0; i < n; ++i) {  // anywhere in the bounding box, one unit beyond
      const long span =
          form.complex.hi()[i] - form.complex.lo()[i] + 2;  // one unit beyond each side
      const Rational t = Rational(next()) / Rational(20000);
      x[i] = Rational(form.complex.lo()[i] - 1) + t * Rational(span) +
             Rational(1) / Rational(primes[(k + i) % 6]);
    }
    out.push_back(x);
  }
  return out;
}

class PiecewisePreset : public ::testing::TestWithParam<const char*> {};

TEST_P(PiecewisePreset, AgreesWithTheRecurrenceAtGenericPoints) {
  const Derivation& a = derivation_of(GetParam());
  BoxSplineRecurrence recurrence(a.spec.directions);
  int inside = 0;
  for (const auto& x : generic_points(a.form, 240)) {
    const Rational expected = recurrence.value(x);
    EXPECT_EQ(a.form.value_at(x), expected) << GetParam();
    inside += !cln::zerop(expected);
  }
  EXPECT_GT(inside, 100) << "too few points inside the support to be a test";
}

INSTANTIATE_TEST_SUITE_P(Presets, PiecewisePreset, ::testing::ValuesIn(fixture::kAllPresets),
                         [](const auto& p) { return std::string(p.param); });

TEST(Eval, ValueOnAKnotPlaneIsTheContinuousLimit) {
  // M7 is continuous: at a point on knot planes the adjacent pieces agree.
  const auto& form = derivation_of("m7").form;
  EXPECT_NO_THROW(form.value_at({1, 1, 1}));
  // The first derivative of the C^0 Courant element jumps across its knot lines.
  const auto& hat = derivation_of("hex3").form;
  EXPECT_EQ(hat.value_at({1, 1}), 1);  // the apex, uncentred frame
  EXPECT_THROW(hat.value_at({1, 1}, {1, 0, 0}), InputError);
}

}  // namespace
}  // namespace boxgen::generator
