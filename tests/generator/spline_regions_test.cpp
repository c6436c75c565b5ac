// The spline's regions on the fundamental region, counted by hand for small cases and for the
// paper's M7 (24 congruent tetrahedra, one orbit).
#include "generator/spline_regions.h"

#include <gtest/gtest.h>

#include "generator/error.h"
#include "tests/generator/analysis_fixture.h"

namespace boxgen {
namespace {

using testing::analysis_of;

TEST(SplineRegions, CourantElementHasTwoTrianglesInOneOrbit) {
  // Z^2: the fundamental region is the unit square, cut by its diagonal; x -> -x plus a lattice
  // translation maps one triangle onto the other. Each triangle sees three hats.
  const SplineStructure& s = analysis_of("hex3").structure;
  EXPECT_EQ(s.regions.size(), 2u);
  ASSERT_EQ(s.references.size(), 1u);
  EXPECT_EQ(s.references[0].regions_in_orbit, 2);
  EXPECT_EQ(s.stencil_min, 3);
  EXPECT_EQ(s.stencil_max, 3);
  EXPECT_EQ(s.references[0].vertices.size(), 3u);
}

TEST(SplineRegions, M7HasTwentyFourTetrahedraInOneOrbit) {
  const SplineStructure& s = analysis_of("m7").structure;
  EXPECT_EQ(s.regions.size(), 24u);
  ASSERT_EQ(s.references.size(), 1u);
  EXPECT_EQ(s.references[0].stencil.size(), 30u);
  EXPECT_EQ(s.references[0].basis.size(), 30u);
  EXPECT_EQ(s.group.size(), 48u);
}

TEST(SplineRegions, PartitionOfUnityHoldsAndItsCheckCanFail) {
  const Analysis& a = analysis_of("zp");
  EXPECT_NO_THROW(check_partition_of_unity(a.form, a.structure));
  PiecewiseForm broken = a.form;
  for (auto& p : broken.polys)
    if (!p.is_zero()) {
      p += Poly::constant(2, Rational(1) / 1000);
      break;
    }
  EXPECT_THROW(check_partition_of_unity(broken, a.structure), InternalError);
}

}  // namespace
}  // namespace boxgen
