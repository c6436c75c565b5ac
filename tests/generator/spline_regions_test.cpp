// The spline's regions on the fundamental region, counted by hand for small cases and for the
// paper's M7 (24 congruent tetrahedra, one orbit).
#include "generator/spline_regions.h"

#include <gtest/gtest.h>

#include <map>
#include <optional>

#include "generator/error.h"
#include "generator/spec.h"
#include "tests/generator/derivation_fixture.h"

namespace boxgen::generator {
namespace {

using fixture::derivation_of;

TEST(SplineRegions, CourantElementHasTwoTrianglesInOneOrbit) {
  // Z^2: the fundamental region is the unit square, cut by its diagonal; x -> -x plus a lattice
  // translation maps one triangle onto the other. Each triangle sees three hats.
  const SplineStructure& s = derivation_of("hex3").structure;
  EXPECT_EQ(s.regions.size(), 2u);
  ASSERT_EQ(s.references.size(), 1u);
  EXPECT_EQ(s.references[0].regions_in_orbit, 2);
  EXPECT_EQ(s.stencil_min, 3);
  EXPECT_EQ(s.stencil_max, 3);
  EXPECT_EQ(s.references[0].vertices.size(), 3u);
}

TEST(SplineRegions, M7HasTwentyFourTetrahedraInOneOrbit) {
  const SplineStructure& s = derivation_of("m7").structure;
  EXPECT_EQ(s.regions.size(), 24u);
  ASSERT_EQ(s.references.size(), 1u);
  EXPECT_EQ(s.references[0].stencil.size(), 30u);
  EXPECT_EQ(s.references[0].basis.size(), 30u);
  EXPECT_EQ(s.group.size(), 48u);
}

TEST(SplineRegions, PartitionOfUnityHoldsAndItsCheckCanFail) {
  const Derivation& a = derivation_of("zp");
  EXPECT_NO_THROW(check_partition_of_unity(a.form, a.structure));
  PiecewiseForm broken = a.form;
  for (auto& p : broken.polys)
    if (!p.is_zero()) {
      p += Poly::constant(2, Rational(1) / 1000);
      break;
    }
  EXPECT_THROW(check_partition_of_unity(broken, a.structure), InternalError);
}

// The whole stencil at a point u, found by locating u - j for every lattice point j of the
// support's box, as the map j + placement -> polynomial.
using Terms = std::map<IntVec, const Poly*>;
Terms terms_at(const PiecewiseForm& form, const RatVec& u, const IntVec& placement) {
  const int n = form.dimension();
  IntVec lo(n), hi(n);
  for (int i = 0; i < n; ++i) {
    const std::int64_t corner = floor_to_int64(u[i]);
    lo[i] = corner - form.complex.hi()[i];
    hi[i] = corner - form.complex.lo()[i] + 1;
  }
  Terms out;
  for (const auto& j : form.spec.lattice.points_in_box(lo, hi)) {
    RatVec q = u;
    for (int i = 0; i < n; ++i) q[i] = q[i] - Rational(j[i]);
    const int k = form.knots.locate(q);
    if (k < 0 || form.polys[k].is_zero()) continue;
    IntVec placed = j;
    for (int i = 0; i < n; ++i) placed[i] += placement[i];
    out.emplace(placed, &form.polys[k]);
  }
  return out;
}

bool same_terms(const Terms& x, const Terms& y) {
  if (x.size() != y.size()) return false;
  for (auto p = x.begin(), q = y.begin(); p != x.end(); ++p, ++q)
    if (p->first != q->first || *p->second != *q->second) return false;
  return true;
}

// Strictly inside a region's convex polytope (centred frame): on its centroid's side of every
// boundary plane.
bool inside(const SplineRegion& region, const RatVec& x) {
  for (const auto& pl : region.planes) {
    const Rational at = dot(pl.nu, x) - pl.level;
    const Rational centre = dot(pl.nu, region.centroid) - pl.level;
    if (cln::zerop(at) || cln::minusp(at) != cln::minusp(centre)) return false;
  }
  return true;
}

// A point of the neighbour across facet f of a fine cell: beyond the facet's centre, as near as
// it takes for its floor key to be the cell's with the facet's entry moved by one.
std::optional<RatVec> point_across(const FineCell& cell, const Facet& f,
                                   const std::vector<IntVec>& normals) {
  const int n = static_cast<int>(cell.interior.size());
  RatVec mid(n, Rational(0));
  for (const auto& v : f.vertices)
    for (int i = 0; i < n; ++i) mid[i] = mid[i] + v[i] / Rational(long(f.vertices.size()));
  CellKey expected = cell.key;
  expected[static_cast<size_t>(f.normal)] += f.upper ? 1 : -1;
  for (Rational step = Rational(1) / 8; step > Rational(1) / 1048576; step = step / 2) {
    RatVec across = mid;
    for (int i = 0; i < n; ++i) across[i] = across[i] + (mid[i] - cell.interior[i]) * step;
    bool on_a_plane = false;
    for (const auto& nu : normals) on_a_plane = on_a_plane || is_integer(dot(nu, across));
    if (!on_a_plane && floor_key(normals, across) == expected) return across;
  }
  return std::nullopt;
}

// The regions are merged by comparing only the terms on a facet's knot planes. Checked here
// against every term: every fine cell of a region must have its region's map; and across every
// facet of every fine cell, the neighbour has the same map exactly when it lies in the same region
// (else the merge joined too much or stopped early). 2-D with long directions, a 3-D skewed
// matrix, and M7 on BCC.
TEST(SplineRegions, RegionsAreTheMaximalSetsOfCellsWithTheSameTerms) {
  for (const char* text : {"9,1; 1,9; 4,3; -5,2", "2,1,0; 0,2,1; 1,0,2; 1,1,1", "m7"}) {
    DerivationOptions options;
    options.verify = false;
    const Derivation a = derive(parse_spec(text), options);
    const SplineStructure& s = a.structure;
    const int n = a.form.dimension();
    std::vector<std::optional<Terms>> region_terms(s.regions.size());
    size_t facets = 0;
    for (const auto& fc : s.cells) {
      const auto r = static_cast<size_t>(fc.region);
      const Terms here = terms_at(a.form, fc.cell.interior, fc.placement);
      if (!region_terms[r]) region_terms[r] = here;
      EXPECT_TRUE(same_terms(*region_terms[r], here)) << text << ": a cell of region " << r;
      for (const auto& f : facets_of(fc.cell, a.form.complex.normals())) {
        const auto across = point_across(fc.cell, f, a.form.complex.normals());
        ASSERT_TRUE(across.has_value()) << text;
        RatVec centred(n);
        for (int i = 0; i < n; ++i)
          centred[i] = (*across)[i] + Rational(fc.placement[i]) - s.centre[i];
        EXPECT_EQ(same_terms(terms_at(a.form, *across, fc.placement), here),
                  inside(s.regions[r], centred))
            << text << ": a facet of region " << r;
        ++facets;
      }
    }
    EXPECT_GT(facets, s.cells.size()) << text;
  }
}

}  // namespace
}  // namespace boxgen::generator
