#include "generator/symmetry.h"

#include <algorithm>
#include <numeric>

namespace boxgen::generator {

IntVec SignedPermutation::apply(const IntVec& x) const {
  IntVec y(x.size());
  for (size_t i = 0; i < x.size(); ++i) y[i] = sign[i] * x[perm[i]];
  return y;
}

RatVec SignedPermutation::apply(const RatVec& x) const {
  RatVec y(x.size());
  for (size_t i = 0; i < x.size(); ++i) y[i] = sign[i] < 0 ? Rational(-x[perm[i]]) : x[perm[i]];
  return y;
}

SignedPermutation SignedPermutation::inverse() const {
  SignedPermutation inv{perm, sign};
  for (size_t i = 0; i < perm.size(); ++i) {
    inv.perm[perm[i]] = static_cast<int>(i);
    inv.sign[perm[i]] = sign[i];
  }
  return inv;
}

SignedPermutation SignedPermutation::compose(const SignedPermutation& inner) const {
  // (this o inner)(x)_i = sign[i] * inner(x)[perm[i]] = sign[i] * inner.sign[perm[i]] *
  // x[inner.perm[perm[i]]]
  SignedPermutation out{perm, sign};
  for (size_t i = 0; i < perm.size(); ++i) {
    out.perm[i] = inner.perm[perm[i]];
    out.sign[i] = sign[i] * inner.sign[perm[i]];
  }
  return out;
}

IntColumns SignedPermutation::matrix() const {
  const size_t n = perm.size();
  IntColumns cols(n, IntVec(n, 0));
  for (size_t i = 0; i < n; ++i) cols[perm[i]][i] = sign[i];
  return cols;
}

bool SignedPermutation::is_identity() const {
  for (size_t i = 0; i < perm.size(); ++i)
    if (perm[i] != static_cast<int>(i) || sign[i] != 1) return false;
  return true;
}

std::vector<SignedPermutation> all_signed_permutations(int n) {
  std::vector<SignedPermutation> out;
  std::vector<int> perm(n);
  std::iota(perm.begin(), perm.end(), 0);
  do {
    for (int mask = 0; mask < (1 << n); ++mask) {
      std::vector<int> sign(n);
      for (int i = 0; i < n; ++i) sign[i] = (mask >> i) & 1 ? -1 : 1;
      out.push_back({perm, sign});
    }
  } while (std::next_permutation(perm.begin(), perm.end()));
  return out;
}

namespace {

std::vector<IntVec> canonical_multiset(const IntColumns& cols) {
  std::vector<IntVec> out;
  for (const auto& c : cols) out.push_back(sign_canonical(c));
  std::sort(out.begin(), out.end());
  return out;
}

}  // namespace

std::vector<SignedPermutation> symmetry_group(const BoxSplineSpec& spec) {
  const auto reference = canonical_multiset(spec.directions);
  std::vector<SignedPermutation> group;
  for (const auto& g : all_signed_permutations(spec.dimension())) {
    bool keeps_lattice =
        std::all_of(spec.lattice.generator().begin(), spec.lattice.generator().end(),
                    [&](const IntVec& c) { return spec.lattice.contains(g.apply(c)); });
    if (!keeps_lattice) continue;
    IntColumns image;
    for (const auto& c : spec.directions) image.push_back(g.apply(c));
    if (canonical_multiset(image) == reference) group.push_back(g);
  }
  return group;
}

}  // namespace boxgen::generator
