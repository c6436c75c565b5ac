// The two independent derivations (generator/box_spline_derivation.h): directional integration
// and finite differences of the truncated power agree cell by cell for every preset.
#include "generator/box_spline_derivation.h"

#include <gtest/gtest.h>

#include "tests/generator/derivation_fixture.h"

namespace boxgen::generator {
namespace {

using fixture::derivation_of;

class DerivationPreset : public ::testing::TestWithParam<const char*> {};

TEST_P(DerivationPreset, TwoDerivationsAgreeCellByCell) {
  const Derivation& a = derivation_of(GetParam());
  const PiecewiseForm other = derive_piecewise(a.spec, DerivationMethod::DirectionalIntegration);
  ASSERT_EQ(other.polys.size(), a.form.polys.size());
  int nonzero = 0;
  for (size_t i = 0; i < other.polys.size(); ++i) {
    EXPECT_EQ(other.polys[i], a.form.polys[i]) << GetParam() << " cell " << i;
    nonzero += !other.polys[i].is_zero();
  }
  EXPECT_GT(nonzero, 0);
}

INSTANTIATE_TEST_SUITE_P(Presets, DerivationPreset, ::testing::ValuesIn(fixture::kAllPresets),
                         [](const auto& p) { return std::string(p.param); });

}  // namespace
}  // namespace boxgen::generator
