// The two quadratures over the Voronoi cell against exact integrals: polynomials on the cube and
// the rhombic dodecahedron (the Gauss rules are exact for them at a low order), and a smooth
// non-polynomial integrand with a closed form on the cube.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "analysis/dual_lattice.h"
#include "analysis/quadrature.h"
#include "generator/lattice.h"

namespace boxgen::analysis {
namespace {

using namespace ::boxgen::generator;  // NOLINT(google-build-using-namespace): the generator's
                                      // lattices and SPECs

TEST(GaussLegendre, IntegratesPolynomialsOfDegreeBelowTwiceTheOrderExactly) {
  for (int order : {1, 2, 5, 16, 40}) {
    const GaussRule g = gauss_legendre(order);
    for (int degree = 0; degree < 2 * order; degree += 3) {
      double s = 0;
      for (int i = 0; i < order; ++i) s += g.weights[i] * std::pow(g.nodes[i], degree);
      EXPECT_NEAR(s, 1.0 / (degree + 1), 1e-14) << "order " << order << " degree " << degree;
    }
  }
}

TEST(CellQuadrature, VolumeAndSecondMomentOfTheRhombicDodecahedron) {
  const DualLattice d(Lattice::bcc().generator());
  const Integrand one = [](const Vec&) { return 1.0; };
  const Integrand x2 = [](const Vec& w) { return w[0] * w[0]; };
  // ∫ w_x^2 over |w_i| + |w_j| <= pi, by hand: in the positive octant the slice at x has area
  // (pi - x)^2 - (pi - 2x)^2 / 2 = pi^2/2 - x^2 for x <= pi/2 and (pi - x)^2 beyond, so the octant
  // gives pi^5 (7/480 + 1/60) = pi^5 / 32 and the cell pi^5 / 4 (the same slices give the
  // volume 2 pi^3).
  const double exact_moment = std::pow(std::numbers::pi, 5) / 4;
  for (int order : {4, 8}) {
    EXPECT_NEAR(integrate_iterated(d.cell(), one, order), 2 * std::pow(std::numbers::pi, 3), 1e-10);
    EXPECT_NEAR(integrate_simplex_fan(d.cell(), one, order), 2 * std::pow(std::numbers::pi, 3),
                1e-10);
    EXPECT_NEAR(integrate_iterated(d.cell(), x2, order), exact_moment, 1e-9);
    EXPECT_NEAR(integrate_simplex_fan(d.cell(), x2, order), exact_moment, 1e-9);
  }
}

TEST(CellQuadrature, SmoothIntegrandOnTheCubeConvergesToTheClosedForm) {
  const DualLattice d(Lattice::cartesian(3).generator());
  // ∫_{[-pi,pi]^3} cos(x/2) cos(y/3) e^{z/4} = (4)(6 sin(pi/3))(4 (e^{pi/4} - e^{-pi/4})).
  const Integrand f = [](const Vec& w) {
    return std::cos(w[0] / 2) * std::cos(w[1] / 3) * std::exp(w[2] / 4);
  };
  const double exact = 4 * (6 * std::sin(std::numbers::pi / 3)) *
                       (4 * (std::exp(std::numbers::pi / 4) - std::exp(-std::numbers::pi / 4)));
  EXPECT_NEAR(integrate_iterated(d.cell(), f, 12), exact, 1e-11 * exact);
  EXPECT_NEAR(integrate_simplex_fan(d.cell(), f, 16), exact, 1e-11 * exact);
}

TEST(CellQuadrature, PlanarCells) {
  const DualLattice d(IntDirections{{2, 0}, {1, 2}});  // hexagonal cell, area pi^2
  const Integrand one = [](const Vec&) { return 1.0; };
  EXPECT_NEAR(integrate_iterated(d.cell(), one, 3), std::numbers::pi * std::numbers::pi, 1e-11);
  EXPECT_NEAR(integrate_simplex_fan(d.cell(), one, 3), std::numbers::pi * std::numbers::pi, 1e-11);
}

}  // namespace
}  // namespace boxgen::analysis
