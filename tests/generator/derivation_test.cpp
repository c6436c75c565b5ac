// `analyze` against the paper's Table 1 (M12, M8, M7) and textbook values for the other presets.
// Every expected number comes from the paper or from a hand count written beside it; none is
// copied from the generator's output.
#include <gtest/gtest.h>

#include "tests/generator/derivation_fixture.h"

namespace boxgen::generator {
namespace {

using fixture::derivation_of;

struct Expected {
  const char* preset;
  int degree, order;
  long volume, stencil;
  bool independent;
  int regions, orbits, group;
};

// M12, M8, M7: Table 1 of Kim 2013 and its section 4 (24 congruent tetrahedra for M7, 6 for M8;
// M12's pieces are unit cubes: 4 per fundamental region of volume 4, one type up to symmetry).
// cart7: volume = sum of |det| over triples = 1 (e1 e2 e3) + 12 (two axes, a diagonal) +
//   24 (one axis, two diagonals: 2 per pair with nonzero minor, 4 such pairs per axis) + 16 (4
//   triples of diagonals, |det| 4); order 4 (the plane x = 0 misses e1 and all 4 diagonals: 5; y =
//   z misses e2, e3 and two diagonals: 4); det 2 subsets -> dependent; 48 signed permutations keep
//   it.
// fcc6: Kim, Entezari, Peters 2008 (paper ref [15]): cubic, C^1, order 3, 16-sample stencil; every
//   triple of face diagonals has |det| 0 or 2 = |det G_fcc| -> independent; volume 16 * 2 = 32.
//   Its pieces are the FCC Delaunay tetrahedra and octahedra; the octahedra split into tetrahedra
//   of two types along the knot planes, so 2 orbits.
// tricubic: tensor-product cubic B-spline: degree 9, order 4, 4^3 = 64 samples, one unit cube.
// hex3: the Courant element: linear, order 2, 3 samples, two triangles per unit square.
// zp: the Zwart-Powell element: quadratic, order 3, support area 7, four triangles per unit square,
//   det((1,1),(-1,1)) = 2 -> dependent.
const Expected kExpected[] = {
    {"m12", 9, 4, 512, 128, false, 4, 1, 48}, {"m8", 5, 4, 128, 32, true, 6, 1, 48},
    {"m7", 4, 4, 120, 30, false, 24, 1, 48},  {"cart7", 4, 4, 53, 53, false, 24, 1, 48},
    {"fcc6", 3, 3, 32, 16, true, 10, 2, 48},  {"tricubic", 9, 4, 64, 64, true, 1, 1, 48},
    {"hex3", 1, 2, 3, 3, true, 2, 1, 4},      {"zp", 2, 3, 7, 7, false, 4, 1, 8},
};

class AnalyzePreset : public ::testing::TestWithParam<Expected> {};

TEST_P(AnalyzePreset, MatchesTheLiterature) {
  const Expected& e = GetParam();
  const Derivation& a = fixture::verified_derivation_of(e.preset);
  EXPECT_EQ(a.properties.degree, e.degree);
  EXPECT_EQ(a.properties.approximation_order, e.order);
  EXPECT_EQ(a.properties.continuity, e.order - 2);
  EXPECT_EQ(a.properties.support_volume, Integer(e.volume));
  EXPECT_EQ(a.properties.stencil_size, Integer(e.stencil));
  EXPECT_EQ(a.properties.linearly_independent, e.independent);
  EXPECT_EQ(static_cast<int>(a.structure.regions.size()), e.regions);
  EXPECT_EQ(static_cast<int>(a.structure.references.size()), e.orbits);
  EXPECT_EQ(static_cast<int>(a.structure.group.size()), e.group);
  // Every region's actual stencil has the size the volume formula predicts.
  EXPECT_EQ(a.structure.stencil_min, e.stencil);
  EXPECT_EQ(a.structure.stencil_max, e.stencil);
  // The default exact checks ran and passed.
  EXPECT_TRUE(a.checks.methods_agree);
  EXPECT_TRUE(a.checks.integral_is_one);
  EXPECT_TRUE(a.checks.symmetric);
  EXPECT_TRUE(a.checks.partition_of_unity);
  EXPECT_TRUE(a.checks.continuity.sharp);
  EXPECT_GT(a.checks.continuity.faces_checked, 0);
}

INSTANTIATE_TEST_SUITE_P(Presets, AnalyzePreset, ::testing::ValuesIn(kExpected),
                         [](const auto& p) { return std::string(p.param.preset); });

TEST(Analyze, M7ReferenceTetrahedronIsThePapers) {
  const auto& ref = derivation_of("m7").structure.references.at(0);
  // Paper section 4.2: v1 = (0,0,0), v2 = (1,1,1), v3 = (1,0,0), v4 = (1,1,0) (sorted here).
  std::vector<RatVec> expected{{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {1, 1, 1}};
  EXPECT_EQ(ref.vertices, expected);
  EXPECT_EQ(ref.stencil.size(), 30u);
  EXPECT_EQ(ref.regions_in_orbit, 24);
}

TEST(Analyze, PiecesOfTensorProductSplinesAreCubes) {
  // A tensor-product cubic B-spline has 4 pieces per axis: 64 polynomial pieces, and M12 is one
  // with knot spacing 2. The Courant element has 6 triangles.
  EXPECT_EQ(derivation_of("tricubic").pieces, 64);
  EXPECT_EQ(derivation_of("m12").pieces, 64);
  EXPECT_EQ(derivation_of("hex3").pieces, 6);
}

TEST(Analyze, EveryRegionMapsOntoItsReference) {
  for (const char* p : fixture::kAllPresets) {
    const auto& s = derivation_of(p).structure;
    for (const auto& r : s.regions) {
      std::vector<RatVec> image;
      for (const auto& v : r.vertices) image.push_back(r.to_reference.apply(v));
      std::sort(image.begin(), image.end());
      EXPECT_EQ(image, s.references[r.orbit].vertices) << p;
    }
  }
}

TEST(Analyze, JsonHasTheDocumentedKeys) {
  const auto j = to_json(derivation_of("m7"));
  for (const char* key :
       {"dimension", "directions", "lattice", "degree", "continuity", "approximation_order",
        "support_volume", "stencil_size", "stencil_size_min", "stencil_size_max",
        "linearly_independent", "pieces", "regions_per_fundamental_region", "symmetry_group_order",
        "regions_up_to_symmetry", "derivation_seconds"})
    EXPECT_TRUE(j.contains(key)) << key;
  EXPECT_EQ(j["support_volume"], "120");
}

}  // namespace
}  // namespace boxgen::generator
