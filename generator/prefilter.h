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

#include "generator/interpolation_symbol.h"
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
  //   "per_orbit": one weight per orbit of the symmetry group within each shell;
  //   "fir":       qfir (derive_fir_prefilter), one weight per orbit, by least squares.
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

// qfir:K, the FIR interpolation prefilter on the shells 0..last_shell (docs/design.md §18,
// support/fir_prefilter.hpp): of the prefilters there that keep the approximation order, the one
// whose spline comes closest to the samples (least squares of the residual at the samples of a
// unit impulse, smoothed twice by M: the |A|^4-weighted error), exactly. `samples`:
// lattice_samples(spec). One weight per orbit of the symmetry group (the minimiser is unique, hence
// symmetric). Throws InputError (one line) for a shell out of range or when no prefilter of full
// order exists on those shells, naming the least K that has one.
Prefilter derive_fir_prefilter(const BoxSplineSpec& spec, int last_shell,
                               const std::vector<LatticeSample>& samples);

// Every prefilter of full order on the given shells with one weight per orbit of the symmetry
// group: the orbit weights are particular + sum_i t_i basis[i] for any parameters t (the free
// parameters derive_prefilter sets to zero, here kept free for optimisation: the optimised q1opt
// and q2opt, frontend/optimised_prefilter.h). Exact; throws like derive_prefilter.
struct PrefilterFamily {
  int order = 0;
  std::vector<int> shells;
  std::vector<std::vector<IntVec>> orbits;  // the points sharing each weight
  std::vector<std::string> orbit_labels;    // "shell 1 orbit of (-1,-1,-1)"
  RatVec particular;                        // one weight per orbit; the parameters zero
  std::vector<RatVec> basis;                // one per free parameter: solutions of the
                                            // homogeneous conditions
  std::vector<int> free_orbits;             // the orbit each parameter is the weight of
  std::vector<IntVec> points;               // every point of the shells, by shell then offset
  std::vector<int> orbit_of_point;          // parallel to points
};
PrefilterFamily prefilter_family(const BoxSplineSpec& spec, const std::vector<int>& shells);

// The member with parameters t (t.size() == basis.size()), exactly, as a Prefilter on every
// point of the shells (parametrisation "per_orbit", the note empty).
Prefilter family_member(const PrefilterFamily& family, const RatVec& t);

// A prefilter by the name the programs take: q1, q2 (quasi_interpolation_shells with
// derive_prefilter) or qfir:K. Throws InputError (one line) for another name.
Prefilter named_prefilter(const BoxSplineSpec& spec, std::string_view name);
// The names the programs take, for messages and help texts: named_prefilter's, and q1opt, q2opt
// (frontend/optimised_prefilter.h, which needs the numerical analysis).
inline constexpr const char* kPrefilterNames = "q1, q2, q1opt, q2opt or qfir:K";

}  // namespace boxgen::generator
