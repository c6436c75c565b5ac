#include "generator/box_spline_properties.h"

#include <cstdlib>

#include "generator/approximation_order.h"

namespace boxgen::generator {

BoxSplineProperties box_spline_properties(const BoxSplineSpec& spec) {
  const int n = spec.dimension();
  const auto& xi = spec.directions;
  const int m = static_cast<int>(xi.size());
  BoxSplineProperties p;
  p.degree = m - n;
  p.approximation_order = approximation_order(xi, n);
  p.continuity = p.approximation_order - 2;
  p.support_volume = 0;
  p.linearly_independent = true;
  auto visit = [&](const IntColumns& z) {
    const std::int64_t d = std::llabs(det(z));
    p.support_volume = p.support_volume + Integer(static_cast<long long>(d));
    if (d != 0 && d != spec.lattice.det_abs()) p.linearly_independent = false;
  };
  for (int a = 0; a < m; ++a)
    for (int b = a + 1; b < m; ++b) {
      if (n == 2) {
        visit({xi[a], xi[b]});
        continue;
      }
      for (int c = b + 1; c < m; ++c) visit({xi[a], xi[b], xi[c]});
    }
  p.stencil_size =
      cln::exquo(p.support_volume, Integer(static_cast<long long>(spec.lattice.det_abs())));
  return p;
}

}  // namespace boxgen::generator
