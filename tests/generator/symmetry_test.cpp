// Signed permutations and the symmetry groups of small direction sets, counted by hand.
#include "generator/symmetry.h"

#include <gtest/gtest.h>

namespace boxgen::generator {
namespace {

TEST(Symmetry, AllSignedPermutations) {
  const auto all = all_signed_permutations(3);
  EXPECT_EQ(all.size(), 48u);  // 3! 2^3
  EXPECT_TRUE(all.front().is_identity());
  EXPECT_EQ(all_signed_permutations(2).size(), 8u);
  for (const auto& g : all) {
    EXPECT_TRUE(g.compose(g.inverse()).is_identity());
    EXPECT_EQ(g.inverse().apply(g.apply(IntVec{1, 2, 3})), (IntVec{1, 2, 3}));
  }
}

TEST(Symmetry, ApplyFollowsTheDefinition) {
  const SignedPermutation g{{2, 0, 1}, {1, -1, 1}};  // (g x)_i = sign_i x_perm_i
  EXPECT_EQ(g.apply(IntVec{1, 2, 3}), (IntVec{3, -1, 2}));
}

TEST(Symmetry, GroupsOfPresets) {
  // (1,0), (0,1), (1,1) on Z^2: the identity, the swap, -I and the swap composed with -I keep
  // the set up to signs; a single sign flip sends (1,1) to (-1,1), which is not in it.
  EXPECT_EQ(symmetry_group(parse_spec("1,0; 0,1; 1,1")).size(), 4u);
  // The Zwart-Powell set has the square's whole symmetry group.
  EXPECT_EQ(symmetry_group(parse_spec("zp")).size(), 8u);
  // M7 on BCC: every signed permutation keeps BCC, Xi1 and Xi2 up to signs.
  EXPECT_EQ(symmetry_group(parse_spec("m7")).size(), 48u);
}

}  // namespace
}  // namespace boxgen::generator
