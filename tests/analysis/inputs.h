// The exact generator's outputs as the analysis takes them (the same conversion the boxgen
// commands make in frontend/analysis_inputs.cpp).
#pragma once
#include <string>
#include <vector>

#include "analysis/error_kernel.h"
#include "generator/autocorr.h"
#include "generator/prefilter.h"
#include "generator/spec.h"

namespace boxgen::test {

using namespace ::boxgen::generator;  // NOLINT(google-build-using-namespace): the generator's
                                      // outputs

inline std::vector<analysis::LatticeTap> autocorrelation_taps(const BoxSplineSpec& spec) {
  std::vector<analysis::LatticeTap> out;
  for (const auto& s : autocorrelation_refinement(spec).samples)
    out.push_back({s.point, to_double(s.value)});
  return out;
}

inline std::vector<analysis::LatticeTap> prefilter_taps(const BoxSplineSpec& spec,
                                                        std::vector<int> shells) {
  std::vector<analysis::LatticeTap> out;
  for (const auto& w : derive_prefilter(spec, shells).weights)
    out.push_back({w.offset, to_double(w.weight)});
  return out;
}

}  // namespace boxgen::test
