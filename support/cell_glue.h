// The cell-locating glue that the C++ evaluators (support/evaluator_support.hpp) and the CUDA
// headers (templates/evaluator.cuh.fmt, which include this file) share: one definition, compiled
// for the host and the device. It needs no CUDA header, and of the standard library only
// <cstdint> (through integer_math.h). The GLSL evaluators print their own port
// (generator/codegen/targets/glsl_evaluator.cpp); tests/gpu/glue_test.cpp runs all three on the
// same cases.
#pragma once

#include "support/host_device.h"
#include "support/integer_math.h"

namespace boxgen::support {

// Rounding put r on an empty key combination (it lies on a knot plane): the cell of this cube
// whose slabs [key, key + 1] the normals' products nu . r violate least, the first of several;
// the spline is continuous there, so either side is right. The products are summed in T, the
// precision r and the lookup key were computed in (a float evaluator on a GPU has no double to
// spare), in the order the key's sums take, so the violation is measured on the numbers that
// found no cell. `cells` holds the cells of every cube (members cube and keys[]), `normals` the
// knot-plane normals and one unused row (K1 = K + 1).
template <class T, class Cell, int C, int K1, int N>
BOXGEN_HOST_DEVICE int nearest_cell(int cube, const T* r, const Cell (&cells)[C],
                                    const int (&normals)[K1][N]) {
  int best = -1;
  T best_violation = T(0);
  for (int c = 0; c < C; ++c) {
    if (cells[c].cube != cube) continue;
    T violation = T(0);
    for (int k = 0; k + 1 < K1; ++k) {
      T s = T(0);
      for (int i = 0; i < N; ++i) s += static_cast<T>(normals[k][i]) * r[i];
      const T lo = static_cast<T>(cells[c].keys[k]);
      violation += (s < lo ? lo - s : T(0)) + (s > lo + T(1) ? s - (lo + T(1)) : T(0));
    }
    if (best < 0 || violation < best_violation) {
      best = c;
      best_violation = violation;
    }
  }
  return best;
}

}  // namespace boxgen::support
