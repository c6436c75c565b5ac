// Knot-plane normals of a direction matrix (docs/design.md §4): every n-1 columns that span a
// hyperplane give a primitive integer normal. All knot planes of M_Xi and of its integer
// shifts are nu . x = c with integer c.
#pragma once
#include <vector>

#include "generator/int_linalg.h"

namespace boxgen {

// Distinct primitive normals of the hyperplanes spanned by columns, sorted.
std::vector<IntVec> knot_normals(const IntColumns& columns, int n);
// knot_normals plus the coordinate axes (so every cell lies in one unit cube), axes first.
std::vector<IntVec> arrangement_normals(const IntColumns& columns, int n);
// Reorders columns so that the first n form a basis (stable otherwise).
IntColumns basis_first(const IntColumns& columns, int n);

}  // namespace boxgen
