#include "generator/zonotope.h"

namespace boxgen::generator {

Zonotope::Zonotope(const IntColumns& directions, int n) : lo_(n, 0), hi_(n, 0) {
  for (const auto& xi : directions)
    for (int i = 0; i < n; ++i) (xi[i] < 0 ? lo_[i] : hi_[i]) += xi[i];
}

}  // namespace boxgen::generator
