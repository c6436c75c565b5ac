// The regulariser of interpolation (support/lattice_regulariser.h): a rule of the lattice, not of
// the basis that describes it; its symbol vanishes on the dual lattice and nowhere else that is
// tested; the choice of lambda and its refusals.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <numbers>
#include <stdexcept>
#include <vector>

#include "support/lattice_regulariser.h"

namespace boxgen::support {
namespace {

using Basis = std::vector<std::vector<std::int64_t>>;

double symbol(const LatticeTaps& taps, double w0, double w1, double w2) {
  double s = 0;
  for (const auto& [t, v] : taps) s += v * std::cos(w0 * t[0] + w1 * t[1] + w2 * t[2]);
  return s;
}

// BCC by the generator's symmetric basis and by the runtime's Hermite form: the same D, the
// Laplacian over the eight shortest vectors (+-1, +-1, +-1), whose weights are written by hand.
TEST(LatticeRegulariser, IsTheLaplacianOverTheShortestVectorsWhateverTheBasis) {
  const LatticeTaps symmetric = regulariser_taps({{-1, 1, 1}, {1, -1, 1}, {1, 1, -1}}, 4);
  const LatticeTaps hermite = regulariser_taps({{1, -1, -1}, {0, 2, 0}, {0, 0, 2}}, 4);
  EXPECT_EQ(symmetric, hermite);
  LatticeTaps by_hand{{{0, 0, 0}, 8.0}};
  for (int z : {-1, 1})
    for (int y : {-1, 1})
      for (int x : {-1, 1}) by_hand.push_back({{x, y, z}, -1.0});
  EXPECT_EQ(convolve(symmetric, {{{0, 0, 0}, 1.0}}), convolve(by_hand, {{{0, 0, 0}, 1.0}}));
  // Order 5 to 8: the square of the Laplacian.
  EXPECT_EQ(regulariser_taps({{1, 0, 0}, {0, 1, 0}, {0, 0, 1}}, 6),
            convolve(regulariser_taps({{1, 0, 0}, {0, 1, 0}, {0, 0, 1}}, 4),
                     regulariser_taps({{1, 0, 0}, {0, 1, 0}, {0, 0, 1}}, 4)));
}

// Where the shortest vectors do not generate L (Z x Z x 5Z: only +-e1, +-e2), longer shells join
// until they do: the symbol vanishes at 2 pi (0, 0, 1/5), on the dual lattice, but not at half of
// it, which a Laplacian over the plane alone would miss.
TEST(LatticeRegulariser, TakesLongerVectorsUntilTheyGenerateTheLattice) {
  const LatticeTaps d = regulariser_taps({{1, 0, 0}, {0, 1, 0}, {0, 0, 5}}, 4);
  const double pi = std::numbers::pi;
  EXPECT_NEAR(symbol(d, 0, 0, 2 * pi / 5), 0, 1e-9);
  EXPECT_NEAR(symbol(d, 2 * pi, 0, 0), 0, 1e-9);
  EXPECT_GT(symbol(d, 0, 0, pi / 5), 1);
  // A 2-D lattice, the checkerboard D2 = {x + y even}: its points have z = 0, and (1/2, 1/2) is in
  // its dual.
  const LatticeTaps d2 = regulariser_taps({{1, 1}, {1, -1}}, 4);
  for (const auto& [t, v] : d2) EXPECT_EQ(t[2], 0);
  EXPECT_NEAR(symbol(d2, 2 * pi, 0, 0), 0, 1e-9);
  EXPECT_NEAR(symbol(d2, pi, pi, 0), 0, 1e-9);
  EXPECT_GT(symbol(d2, pi, 0, 0), 1);
}

TEST(LatticeRegulariser, ChoosesLambdaAndRefusesBadOnes) {
  const Basis z3{{1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
  // A symbol that vanishes at pi (1, 0, 0): (delta_0 + delta_e1) / 2.
  const LatticeTaps vanishing{{{0, 0, 0}, 0.5}, {{1, 0, 0}, 0.5}};
  const LatticeTaps positive{{{0, 0, 0}, 1.0}};
  EXPECT_EQ(regularisation(vanishing, z3, 4, std::nullopt, "f").lambda, kDefaultLambda);
  EXPECT_EQ(regularisation(positive, z3, 4, std::nullopt, "f").lambda, 0);
  EXPECT_TRUE(regularisation(positive, z3, 4, std::nullopt, "f").regulariser.empty());
  const Regularisation r = regularisation(vanishing, z3, 4, 0.5, "f");
  EXPECT_DOUBLE_EQ(r.mu, 0.5 * 1.0 / (12.0 * 12.0));  // max |A| = 1, max |D| = 12 at pi (1,1,1)
  EXPECT_THROW((void)regularisation(vanishing, z3, 4, 0.0, "f"), std::invalid_argument);
  for (const double bad : {-1e-3, 2.0, std::nan(""), HUGE_VAL})
    EXPECT_THROW((void)regularisation(positive, z3, 4, bad, "f"), std::invalid_argument) << bad;
}

}  // namespace
}  // namespace boxgen::support
