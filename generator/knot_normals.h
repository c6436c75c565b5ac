// Knot-plane normals of a direction matrix (docs/design.md §4): every n-1 columns that span a
// hyperplane give a primitive integer normal. All knot planes of M_Xi and of its integer
// shifts are nu . x = c with integer c.
#pragma once
#include <vector>

#include "generator/int_linalg.h"

namespace boxgen::generator {

// The true knot planes of M_Xi (docs/design.md §4): for each normal nu, the planes nu . x = nu .
// sum(S) over the sub-multisets S of the columns. Only these carry breaks of the polynomial pieces,
// so an arrangement of them grows with the pieces M_Xi really has, not with the length of the
// columns (the integer levels of a normal (1,-20) would give 400 planes where 8 are knots).
struct KnotPlanes {
  std::vector<IntVec> normals;
  std::vector<std::vector<std::int64_t>> levels;  // per normal: sorted, distinct
};
// Knot planes of `columns`: normals of the hyperplanes they span, levels their sub-sums.
KnotPlanes knot_planes(const IntColumns& columns, int n);
// Sorted distinct values nu . sum(S) over the sub-multisets S of `columns`.
std::vector<std::int64_t> subset_sum_levels(const IntVec& nu, const IntColumns& columns);

// Distinct primitive normals of the hyperplanes spanned by columns, sorted.
std::vector<IntVec> knot_normals(const IntColumns& columns, int n);
// knot_normals plus the coordinate axes (so every cell lies in one unit cube), axes first.
std::vector<IntVec> arrangement_normals(const IntColumns& columns, int n);
// Reorders columns so that the first n form a basis (stable otherwise).
IntColumns basis_first(const IntColumns& columns, int n);

}  // namespace boxgen::generator
