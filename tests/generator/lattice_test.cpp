#include "generator/lattice.h"

#include <gtest/gtest.h>

#include <set>

#include "generator/error.h"
#include "generator/symmetry.h"

namespace boxgen::generator {
namespace {

TEST(Lattice, BccMembershipIsAllEvenOrAllOdd) {
  const Lattice bcc = Lattice::bcc();
  EXPECT_EQ(bcc.det_abs(), 4);
  for (int x = -3; x <= 3; ++x)
    for (int y = -3; y <= 3; ++y)
      for (int z = -3; z <= 3; ++z) {
        const bool expected =
            (x % 2 == 0 && y % 2 == 0 && z % 2 == 0) || (x % 2 != 0 && y % 2 != 0 && z % 2 != 0);
        EXPECT_EQ(bcc.contains({x, y, z}), expected) << x << ' ' << y << ' ' << z;
      }
}

TEST(Lattice, FccMembershipIsEvenCoordinateSum) {
  const Lattice fcc = Lattice::fcc();
  EXPECT_EQ(fcc.det_abs(), 2);
  for (int x = -2; x <= 2; ++x)
    for (int y = -2; y <= 2; ++y)
      for (int z = -2; z <= 2; ++z)
        EXPECT_EQ(fcc.contains({x, y, z}), ((x + y + z) % 2 + 2) % 2 == 0);
}

TEST(Lattice, CosetRepresentativesAreDistinctAndComplete) {
  for (const Lattice& l :
       {Lattice::bcc(), Lattice::fcc(), Lattice::cartesian(3), Lattice::cartesian(2)}) {
    auto reps = l.coset_representatives();
    EXPECT_EQ(static_cast<std::int64_t>(reps.size()), l.det_abs());
    std::set<IntVec> seen;
    for (const auto& r : reps) {
      EXPECT_EQ(l.reduce(r), r);
      seen.insert(r);
    }
    EXPECT_EQ(seen.size(), reps.size());
    // Every integer point reduces to one of them, by a lattice vector.
    const int n = l.dimension();
    for (int a = -3; a <= 3; ++a)
      for (int b = -3; b <= 3; ++b) {
        IntVec x(n, 0);
        x[0] = a;
        x[1] = b;
        if (n == 3) x[2] = a - b;
        IntVec r = l.reduce(x);
        EXPECT_TRUE(seen.count(r));
        IntVec diff(n);
        for (int i = 0; i < n; ++i) diff[i] = x[i] - r[i];
        EXPECT_TRUE(l.contains(diff));
      }
  }
}

TEST(Lattice, BccShellsMatchThePaper) {
  auto shells = Lattice::bcc().shells(3);
  ASSERT_EQ(shells.size(), 3u);
  EXPECT_EQ(shells[0].size(), 1u);
  EXPECT_EQ(shells[1].size(), 8u);  // (+-1, +-1, +-1), squared norm 3
  EXPECT_EQ(shells[2].size(), 6u);  // (+-2, 0, 0) and permutations, squared norm 4
  for (const auto& p : shells[1]) EXPECT_EQ(dot(p, p), 3);
  for (const auto& p : shells[2]) EXPECT_EQ(dot(p, p), 4);
}

TEST(Lattice, PointsInABoxAreExactlyTheMembersInScanOrder) {
  // Against a scan of the whole box with contains(), x_0 fastest: skewed, scaled and 2-D lattices.
  for (const Lattice& l :
       {Lattice::bcc(), Lattice::fcc(), Lattice("skew", {{3, 1, 0}, {0, 2, 1}, {1, 0, 5}}),
        Lattice("scaled bcc", {{-4, 4, 4}, {4, -4, 4}, {4, 4, -4}}),
        Lattice("2-D", {{2, 1}, {-1, 3}})}) {
    SCOPED_TRACE(l.name());
    const int n = l.dimension();
    IntVec lo(n), hi(n);
    for (int i = 0; i < n; ++i) lo[i] = -7 + i, hi[i] = 6 + 2 * i;
    std::vector<IntVec> scanned;
    IntVec x = lo;
    for (;;) {
      if (l.contains(x)) scanned.push_back(x);
      int i = 0;
      while (i < n && x[i] == hi[i]) x[i] = lo[i], ++i;
      if (i == n) break;
      ++x[i];
    }
    EXPECT_FALSE(scanned.empty());
    EXPECT_EQ(l.points_in_box(lo, hi), scanned);
  }
}

TEST(Lattice, SingularGeneratorIsRejected) {
  EXPECT_THROW(Lattice("bad", IntColumns{{1, 0, 0}, {0, 1, 0}, {1, 1, 0}}), InputError);
}

TEST(Symmetry, SignedPermutationGroupLaws) {
  auto all = all_signed_permutations(3);
  EXPECT_EQ(all.size(), 48u);
  EXPECT_TRUE(all.front().is_identity());
  for (const auto& g : all) {
    EXPECT_TRUE(g.compose(g.inverse()).is_identity());
    IntVec x{1, 2, 3};
    EXPECT_EQ(g.inverse().apply(g.apply(x)), x);
  }
}

}  // namespace
}  // namespace boxgen::generator
