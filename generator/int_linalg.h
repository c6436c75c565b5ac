// Small exact linear algebra on integer vectors and matrices (dimension 2 or 3).
// Matrices are stored as a list of columns, matching how direction matrices are read.
#pragma once
#include <cstdint>
#include <optional>
#include <vector>

#include "generator/rational.h"

namespace boxgen::generator {

using IntColumns = std::vector<IntVec>;  // n x m matrix as m columns of length n
using RatMatrix = std::vector<RatVec>;   // row-major square matrix

std::int64_t det(const IntColumns& square);  // n x n, n <= 3
int rank(const IntColumns& columns, int n);  // rank of an n x m integer matrix
std::int64_t gcd_of(const IntVec& v);
IntVec sign_canonical(IntVec v);  // negated if needed so the first nonzero entry is positive
IntVec primitive(IntVec v);       // divided by gcd, then sign_canonical
// Normal of the hyperplane spanned by n-1 columns (n = 2: rotate; n = 3: cross product).
// Returns nullopt if they do not span a hyperplane.
std::optional<IntVec> hyperplane_normal(const IntColumns& columns, int n);
// Solves A x = b exactly for square A given by columns; nullopt if singular.
std::optional<RatVec> solve(const IntColumns& square, const RatVec& b);
// Inverse of a square integer matrix (columns) as a row-major rational matrix.
RatMatrix inverse(const IntColumns& square);

}  // namespace boxgen::generator
