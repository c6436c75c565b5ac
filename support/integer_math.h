// Integer helpers shared by the generator, the evaluator glue (C++ and CUDA, host and device) and
// the runtime: one definition each, so that every part rounds the same way.
#pragma once
#include <cstdint>

#include "support/host_device.h"

namespace boxgen::support {

// floor(a / b) for b != 0 (C++ division truncates towards zero). For a divisor known to be
// positive at compile time the sign test folds away, so the evaluators' power-of-two divisions
// stay a shift and a compare.
BOXGEN_HOST_DEVICE constexpr std::int64_t floor_div(std::int64_t a, std::int64_t b) noexcept {
  if (b < 0) {
    a = -a;
    b = -b;
  }
  const std::int64_t q = a / b;
  return q * b > a ? q - 1 : q;
}

}  // namespace boxgen::support
