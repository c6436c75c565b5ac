// The paper's direction sets (docs/design.md §1), written out so tests of the recurrence and the
// autocorrelation do not depend on the SPEC parser.
#pragma once
#include <initializer_list>

#include "generator/int_linalg.h"

namespace boxgen::generator::fixture {

inline const IntColumns kXi1 = {{1, 1, 1}, {1, -1, -1}, {-1, 1, -1}, {-1, -1, 1}};
inline const IntColumns kXi2 = {{2, 0, 0}, {0, 2, 0}, {0, 0, 2}};

inline IntColumns concat(std::initializer_list<IntColumns> parts) {
  IntColumns out;
  for (const auto& p : parts) out.insert(out.end(), p.begin(), p.end());
  return out;
}

inline IntColumns negated(IntColumns c) {
  for (auto& v : c)
    for (auto& x : v) x = -x;
  return c;
}

}  // namespace boxgen::generator::fixture
