// Lattice samples of the doubled box spline, a(j) = M^c_{Xi ∪ Xi}(j) (docs/design.md §9,
// paper 3.5): the autocorrelation of M^c at lattice points, which the error kernel and the filter
// metrics need; a(0) = ∫ (M^c)^2 for the normalisation ∫ M = 1. The doubled spline has degree 2m -
// n (21 for M12), so deriving its piecewise form is avoided; two cheap exact methods, independent
// of each other, compute the samples and are required to agree in the tests.
#pragma once
#include <vector>

#include "generator/spec.h"

namespace boxgen::generator {

struct AutocorrSample {
  IntVec point;
  Rational value;
};

struct Autocorrelation {
  Rational integral_squared;            // a(0)
  std::vector<AutocorrSample> samples;  // every lattice point with a != 0, sorted by point
};

// Xi ∪ Xi on the same lattice.
BoxSplineSpec doubled_spec(const BoxSplineSpec& spec);

struct RefinementOptions {
  // Solve exactly on orbits of the symmetry group (fast). Off: every lattice point is an unknown
  // of the exact solve (slow beyond a few hundred points; for tests of small cases).
  bool reduce_by_symmetry = true;
  // After an orbit solve, confirm on all points without symmetry: exactly that the samples are
  // an eigenvector, and by ranks modulo primes that eigenvalue 1 is simple on the whole space
  // (a lower bound on the rank over Q, so a proof, not a heuristic).
  bool verify_on_all_points = true;
};

// Both methods throw InputError if a direction is not a lattice vector (parse_spec rejects that
// already; hand-built specs are checked again because the methods depend on it).
//
// The eigenvector of eigenvalue 1 of the subdivision operator restricted to the lattice points
// in the open support, normalised so the samples sum to 1/|det G|. Throws InternalError if the
// eigenvalue is not simple or a sample is not positive.
Autocorrelation autocorrelation_refinement(const BoxSplineSpec& spec,
                                           const RefinementOptions& options = {});

// The limit of M^c_{Xi ∪ Xi}(x0 + eps v) as eps -> 0 along a generic direction v, from exact
// recurrence values at deg+1 small eps (one polynomial cell) interpolated in eps, confirmed by
// two more samples. Scans every lattice point of the support's bounding box, so it also checks
// where the samples vanish. Its cost grows with the number of sub-multisets of the doubled
// columns, prod over distinct columns of (multiplicity + 1): M7 and cart7 2187 (seconds), M8 625,
// M12 15625 (many minutes). Above kContinuityMaxSubMultisets it throws InputError rather than
// appear to hang.
inline constexpr unsigned kContinuityMaxSubMultisets = 4096;
Autocorrelation autocorrelation_continuity(const BoxSplineSpec& spec);

}  // namespace boxgen::generator
