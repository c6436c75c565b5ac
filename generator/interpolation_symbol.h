// The interpolation symbol of a filter M = |det G| M^c on its lattice L (docs/design.md §18):
//   A(w) = sum_{k in L} M(k) e^(-i w.k),
// the transfer function of "coefficients -> the spline's values at the samples". Exact
// interpolation (the spline through every sample) solves A C = V frequency by frequency, so it is
// well posed exactly when A has no zero; M7's shifts are linearly dependent and its A vanishes.
// M is symmetric, so A is real: A(w) = sum_k M(k) cos(w.k), and A(0) = 1 (partition of unity).
//
// The samples M(k) are exact rationals from the derived pieces. A is evaluated exactly at every
// frequency w = pi r where each cos(pi r.k) is rational: by Niven's theorem that needs r.k in
// Z/2 or Z/3, so the candidates are r in (Z/2)^n and (Z/3)^n (A has period 2 pi along each axis,
// since L lies in Z^n). The minimum of |A| over all frequencies is numerical (analysis/); where it
// is attained at a candidate, the value there is exact.
#pragma once
#include <optional>
#include <vector>

#include "generator/piecewise_form.h"
#include "generator/spec.h"

namespace boxgen::generator {

struct LatticeSample {
  IntVec point;    // k in L (the centred frame)
  Rational value;  // M(k) != 0
};

// M(k) at every lattice point where it is not zero, sorted by point, from the pieces of `form`.
// Throws InputError when the filter is discontinuous (approximation order < 2): its values on
// the knot planes through lattice points are not defined.
std::vector<LatticeSample> lattice_samples(const PiecewiseForm& form);
// The same, deriving the pieces first (by the truncated power).
std::vector<LatticeSample> lattice_samples(const BoxSplineSpec& spec);

// A(pi r) exactly, or nullopt where some cos(pi r.k) is irrational.
std::optional<Rational> symbol_at(const std::vector<LatticeSample>& samples, const RatVec& r);

// A frequency w = pi r modulo the dual lattice 2 pi G^-T Z^n, given by its representatives
// nearest the origin (in the Brillouin zone; several where they tie on its boundary), the
// lexicographically largest first.
struct FrequencyClass {
  std::vector<RatVec> representatives;  // r of each w = pi r
};

struct ExactSymbolValues {
  // The smallest |A| over the candidate frequencies, and where (its classes).
  Rational min_abs;
  std::vector<FrequencyClass> min_at;
  // Classes of the candidates where A = 0 exactly (empty: no zero at a candidate).
  std::vector<FrequencyClass> zeros;
  int candidates = 0;  // classes of candidate frequencies evaluated
};

// A at every candidate frequency (see above), exactly.
ExactSymbolValues exact_symbol_values(const std::vector<LatticeSample>& samples,
                                      const Lattice& lattice);

}  // namespace boxgen::generator
