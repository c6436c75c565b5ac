// The symmetry group of a box spline on its lattice (docs/design.md §7): the signed
// permutation matrices g with g L = L and g Xi = Xi up to column signs. M^c(g x) = M^c(x).
#pragma once
#include <vector>

#include "generator/spec.h"

namespace boxgen::generator {

struct SignedPermutation {
  std::vector<int> perm;  // (g x)_i = sign[i] * x[perm[i]]
  std::vector<int> sign;

  IntVec apply(const IntVec& x) const;
  RatVec apply(const RatVec& x) const;
  SignedPermutation inverse() const;
  SignedPermutation compose(const SignedPermutation& inner) const;  // this o inner
  IntColumns matrix() const;                                        // as columns
  bool is_identity() const;
};

// All signed permutations of dimension n (n! 2^n of them), identity first.
std::vector<SignedPermutation> all_signed_permutations(int n);
// The subgroup that preserves the lattice and the direction multiset up to signs.
std::vector<SignedPermutation> symmetry_group(const BoxSplineSpec& spec);

}  // namespace boxgen::generator
