// The Horner form shared by the value and its derivatives (exactness: polynomial_code_test).
#include "generator/codegen/strategies/horner_strategy.h"

#include <gtest/gtest.h>

#include <array>
#include <utility>

#include "tests/generator/derivation_fixture.h"

namespace boxgen::generator::strategies {
namespace {

// Sharing between the value, the gradient and the Hessian (the derivatives differentiate the
// Horner form) makes M7's and M8's value + gradient + Hessian at least 15% cheaper than the 536
// and 895 operations of the unshared code they replace; the value path is never dearer.
TEST(HornerStrategy, DerivativesShareTheValuesHornerForm) {
  const std::pair<const char*, std::array<long, 3>> before[] = {{"m7", {278, 404, 536}},
                                                                {"m8", {415, 628, 895}}};
  for (const auto& [preset, counts] : before) {
    const Derivation& a = fixture::derivation_of(preset);
    const OrbitCode c = choose_orbit_code(a.structure.references[0], 0, 3, a.properties.degree,
                                          EmissionStrategy::Auto);
    EXPECT_LE(c.value.total(), counts[0]) << preset;
    EXPECT_LE(c.gradient.total(), counts[1]) << preset;
    EXPECT_LE(c.hessian.total() * 100, counts[2] * 85) << preset;
  }
}

}  // namespace
}  // namespace boxgen::generator::strategies
