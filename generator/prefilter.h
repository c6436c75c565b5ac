// Exact quasi-interpolation prefilters (docs/design.md §8, the paper's Table 1).
// For the filter M = |det G| M^c on its lattice L, a discrete filter q on L gives the
// reconstruction s(x) = sum_j (V*q)(j) M(x - j) approximation order rho when
//   hat(q)(w) hat(M^c)(w) = 1 + O(|w|^rho),   hat(M^c)(w) = prod_xi sinc(xi.w/2),
// rho = approximation_order(Xi). q is sought on the requested shells of L (shell k = the lattice
// points of the k-th smallest norm, shell 0 = the origin), by matching every Taylor coefficient
// of degree < rho exactly.
#pragma once
#include <string>
#include <string_view>
#include <vector>

#include "generator/spec.h"

namespace boxgen::generator {

inline constexpr int kMaxPrefilterShell = 8;

struct PrefilterWeight {
  IntVec offset;    // lattice point j
  Rational weight;  // q(j)
};

struct Prefilter {
  int order = 0;            // rho: hat(q) hat(M^c) = 1 + O(|w|^order)
  std::vector<int> shells;  // ascending, always contains 0
  // Which parametrisation was solvable, tried in this order:
  //   "common":    one weight at the origin, one shared by every point of the nonzero shells
  //                (the paper's Q^I and Q^II);
  //   "per_shell": one weight per shell;
  //   "per_orbit": one weight per orbit of the symmetry group within each shell.
  std::string parametrisation;
  std::string note;  // empty, or which free parameters were set to zero when q is not unique
  std::vector<PrefilterWeight> weights;  // every point of the shells, by shell then offset
};

// Parses a shell list such as "0,1,2". Throws InputError unless it is a non-empty list of
// distinct shell indices 0..kMaxPrefilterShell that contains 0. Returns them ascending.
std::vector<int> parse_shells(std::string_view text);

// Derives q exactly. Throws InputError for an invalid shell set, or (one line) when no prefilter
// of order rho is supported on those shells, naming the order they reach and a shell set that
// would suffice.
Prefilter derive_prefilter(const BoxSplineSpec& spec, const std::vector<int>& shells);

// The shells of the prefilters q1 and q2 of a filter (`boxgen emit`, `kernel --prefilter`, the
// run-time filters of loader/): q1 on the leading shells 0..k for the smallest k on which a
// prefilter of the full approximation order exists, q2 (which = 2) on 0..k+1, the next larger.
// Throws InputError (one line, naming no option) when no k <= kMaxPrefilterShell (k + 1 for q2)
// has one.
std::vector<int> quasi_interpolation_shells(const BoxSplineSpec& spec, int which);

}  // namespace boxgen::generator
