// Scaled pairs (k Xi on k G) derived on (Xi, G) and stretched back (generator/common_scale.h):
// the reduced pieces equal an independent derivation of (Xi, G), and every basis polynomial of the
// stretched structure equals the piece of the scaled pair's own derivation, exactly.
#include "generator/common_scale.h"

#include <gtest/gtest.h>

#include "generator/piece_checks.h"

namespace boxgen::generator {
namespace {

TEST(CommonScale, IsTheGcdOfEveryEntryOfXiAndG) {
  EXPECT_EQ(common_scale(parse_spec("m7")), 1);
  EXPECT_EQ(common_scale(parse_spec("64,0; 0,64; 64,64", "64,0; 0,64")), 64);
  EXPECT_EQ(common_scale(parse_spec("4,0; 0,6; 4,6", "4,0; 0,6")), 2);
  // Directions divisible by 2 on Z^2: the lattice is not, so nothing is reduced.
  EXPECT_EQ(common_scale(parse_spec("2,0; 0,2; 2,2")), 1);
  // m12's directions are 2 e_i, but its lattice is BCC (entries 1).
  EXPECT_EQ(common_scale(parse_spec("m12")), 1);
}

TEST(CommonScale, ReducedPiecesEqualTheReducedPairsOwnDerivation) {
  for (const auto& [spec, lattice] :
       {std::pair<const char*, const char*>{"3,0; 0,3; 3,3; -3,3", "3,0; 0,3"},
        {"2,2,2; 2,-2,-2; -2,2,-2; -2,-2,2; 4,0,0; 0,4,0; 0,0,4", "-2,2,2; 2,-2,2; 2,2,-2"}}) {
    SCOPED_TRACE(spec);
    const BoxSplineSpec scaled = parse_spec(spec, lattice);
    const std::int64_t k = common_scale(scaled);
    const PiecewiseForm reduced =
        scaled_down(derive_piecewise(scaled, DerivationMethod::TruncatedPower), k);
    const PiecewiseForm direct =
        derive_piecewise(reduced_spec(scaled, k), DerivationMethod::DirectionalIntegration);
    ASSERT_EQ(reduced.knots.cells().size(), direct.knots.cells().size());
    for (size_t i = 0; i < direct.knots.cells().size(); ++i) {
      EXPECT_EQ(reduced.knots.cells()[i].key, direct.knots.cells()[i].key);
      EXPECT_EQ(reduced.knots.cells()[i].vertices, direct.knots.cells()[i].vertices);
      EXPECT_EQ(reduced.polys[i], direct.polys[i]) << "knot cell " << i;
    }
  }
}

TEST(CommonScale, StretchedBasisIsTheScaledPairsOwnPieceOnEveryReferenceRegion) {
  const BoxSplineSpec scaled =
      parse_spec("2,2,2; 2,-2,-2; -2,2,-2; -2,-2,2; 4,0,0; 0,4,0; 0,0,4", "-2,2,2; 2,-2,2; 2,2,-2");
  const PiecewiseForm form = derive_piecewise(scaled, DerivationMethod::TruncatedPower);
  const SplineStructure s = spline_structure(form);
  EXPECT_EQ(s.scale, 2);
  const SplineStructure m7 =
      spline_structure(derive_piecewise(parse_spec("m7"), DerivationMethod::TruncatedPower));
  ASSERT_EQ(s.regions.size(), m7.regions.size());
  ASSERT_EQ(s.references.size(), m7.references.size());
  const RatVec c = spline_centre(scaled);
  EXPECT_EQ(s.centre, c);
  const Rational det = Rational(scaled.lattice.det_abs());
  for (size_t o = 0; o < s.references.size(); ++o) {
    const ReferenceRegion& ref = s.references[o];
    ASSERT_EQ(ref.vertices.size(), m7.references[o].vertices.size());
    for (size_t v = 0; v < ref.vertices.size(); ++v)
      for (size_t i = 0; i < 3; ++i)
        EXPECT_EQ(ref.vertices[v][i], Rational(2) * m7.references[o].vertices[v][i]);
    ASSERT_EQ(ref.stencil.size(), ref.basis.size());
    for (size_t k = 0; k < ref.stencil.size(); ++k) {
      EXPECT_TRUE(scaled.lattice.contains(ref.stencil[k]));
      // M(x - j) = |det G| P(x + c - j), P the piece of the scaled pair's knot cell there.
      RatVec u(3), shift(3);
      for (int i = 0; i < 3; ++i) {
        u[i] = ref.interior[i] + c[i] - Rational(ref.stencil[k][i]);
        shift[i] = Rational(ref.stencil[k][i]) - c[i];
      }
      const int cell = form.knots.locate(u);
      ASSERT_GE(cell, 0);
      EXPECT_EQ(ref.basis[k], form.polys[cell].translated(shift) * det) << "stencil point " << k;
    }
  }
  EXPECT_NO_THROW(check_partition_of_unity(form, s, true));
}

}  // namespace
}  // namespace boxgen::generator
