#include "generator/approximation_order.h"

#include <algorithm>

#include "generator/error.h"

namespace boxgen::generator {

int approximation_order(const IntColumns& xi, int n) {
  if (n != 2 && n != 3) fail_internal("approximation_order: only dimensions 2 and 3 are supported");
  for (const auto& c : xi)
    if (static_cast<int>(c.size()) != n)
      fail_internal("approximation_order: column of the wrong length");
  if (rank(xi, n) < n) return 0;

  // A largest subset that fails to span lies in a hyperplane spanned by columns (a smaller span
  // could be enlarged by another column without reaching R^n), so it suffices to count the
  // columns on every hyperplane spanned by n-1 of them; rho = m - the largest such count.
  auto columns_on = [&](const IntVec& normal) {
    return static_cast<int>(
        std::count_if(xi.begin(), xi.end(), [&](const IntVec& c) { return dot(normal, c) == 0; }));
  };
  int most_on_a_hyperplane = 0;
  const size_t m = xi.size();
  for (size_t i = 0; i < m; ++i) {
    if (n == 2) {
      if (auto normal = hyperplane_normal({xi[i]}, 2))
        most_on_a_hyperplane = std::max(most_on_a_hyperplane, columns_on(*normal));
      continue;
    }
    for (size_t j = i + 1; j < m; ++j)
      if (auto normal = hyperplane_normal({xi[i], xi[j]}, 3))
        most_on_a_hyperplane = std::max(most_on_a_hyperplane, columns_on(*normal));
  }
  return static_cast<int>(m) - most_on_a_hyperplane;
}

}  // namespace boxgen::generator
