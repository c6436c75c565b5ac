// Tensor-product structure of a reference polynomial (README.md, `boxgen emit`): when every
// stencil polynomial p_k is a product of univariate factors and the stencil splits into full
// grids X_0 x ... x X_{n-1} with each factor depending only on its own coordinate of j_k, the
// spline sum_k v[k] p_k(x) is a contraction of the grid's values with 1-D weights per axis.
// That is the case for axis-aligned direction matrices (M12 on BCC, the tricubic B-spline).
#pragma once
#include <optional>
#include <vector>

#include "generator/spline_regions.h"

namespace boxgen::generator {

// A univariate polynomial, coefficients from degree 0 up.
using UnivariatePoly = std::vector<Rational>;

struct TensorGrid {
  // weights[i][a]: the factor of axis i for the a-th value of the grid on that axis.
  std::vector<std::vector<UnivariatePoly>> weights;
  // stencil[flat]: index k into the reference stencil of grid point (a_0, ..., a_{n-1}),
  // flat = a_0 + |X_0| (a_1 + |X_1| a_2).
  std::vector<int> stencil;
  std::vector<int> sizes;  // |X_i|
};

// nullopt unless the exact identity sum over grids of v[stencil] prod_i weights[i][a_i](x_i)
// == sum_k v[k] p_k(x) holds term by term (checked exactly before returning).
std::optional<std::vector<TensorGrid>> separable_form(const ReferenceRegion& ref, int n);

}  // namespace boxgen::generator
