// An exact point evaluator of the uncentred box spline M_Xi by the de Boor-Hoellig recurrence
// (docs/design.md §2). It shares nothing with the piecewise derivation, which is why it exists: it
// is the independent reference that the piecewise form and the autocorrelation are checked against.
//
// Validity: the recurrence drops the terms whose remaining columns no longer span R^n (they are
// measures on hyperplanes, zero off them) and uses the half-open base case. Both are right only
// at GENERIC points: points with nu.x not an integer for every primitive normal nu of a
// hyperplane spanned by n-1 columns (every knot plane of M_Xi and of all its sub-splines lies on
// such an integer level). Every point the recursion visits differs from x by an integer vector,
// so checking x once is enough: the evaluators below check it and throw InputError otherwise.
// Coordinates with distinct large prime denominators are generic.
#pragma once
#include <cstddef>
#include <memory>

#include "generator/int_linalg.h"

namespace boxgen::generator {

// Primitive normals (first nonzero entry positive) of the hyperplanes spanned by n-1 columns;
// for n = 1 the single normal (1). Sorted, without duplicates.
std::vector<IntVec> knot_plane_normals(const IntColumns& xi);
// True if nu.x is not an integer for every normal of knot_plane_normals(xi).
bool is_generic_point(const IntColumns& xi, const RatVec& x);

// The recursion over one direction matrix. What depends only on Xi (the sub-multisets reached,
// their bases and slabs) is kept across points; the memo of values is per base point. One memo
// serves all integer shifts of a base, because the recursion only ever moves by integer vectors:
// sampling a spline at many lattice points (sums of shifts, autocorrelation) then costs little
// more than one point.
class BoxSplineRecurrence {
 public:
  // Throws InputError if xi has a zero column, mixed lengths, rank < n, n outside 1..3, or so
  // many distinct columns that the multiset code overflows.
  explicit BoxSplineRecurrence(const IntColumns& xi);
  ~BoxSplineRecurrence();
  BoxSplineRecurrence(BoxSplineRecurrence&&) noexcept;
  BoxSplineRecurrence& operator=(BoxSplineRecurrence&&) noexcept;

  Rational value(const RatVec& x);         // M_Xi(x), with a fresh memo
  void set_base(const RatVec& base);       // clears the memo; throws InputError if not generic
  Rational at_shift(const IntVec& shift);  // M_Xi(base + shift), sharing the memo

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

// M_Xi(x), uncentred (support Xi[0,1]^m, integral 1), memoised within the call.
Rational box_spline_recurrence(const IntColumns& xi, const RatVec& x);
// M^c_Xi(x) = M_Xi(x + sum(Xi)/2).
Rational box_spline_centred_recurrence(const IntColumns& xi, const RatVec& x);

}  // namespace boxgen::generator
