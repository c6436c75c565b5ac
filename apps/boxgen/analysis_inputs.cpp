#include "apps/boxgen/analysis_inputs.h"

#include "generator/error.h"
#include "generator/prefilter.h"

namespace boxgen::cli {

analysis::BoxSplineSpectrum spectrum_of(const BoxSplineSpec& spec) {
  return analysis::BoxSplineSpectrum(spec.directions);
}

analysis::DualLattice dual_of(const BoxSplineSpec& spec) {
  return analysis::DualLattice(spec.lattice.generator());
}

std::vector<analysis::LatticeTap> taps_of(const Autocorrelation& a) {
  std::vector<analysis::LatticeTap> out;
  for (const auto& s : a.samples) out.push_back({s.point, to_double(s.value)});
  return out;
}

std::vector<analysis::LatticeTap> prefilter_taps_of(const BoxSplineSpec& spec,
                                                    const std::string& name) {
  if (name == "none") return {};
  if (name != "q1" && name != "q2")
    fail_input("unknown prefilter '" + name.substr(0, 40) + "': expected none, q1, q2 or min");
  // q1 on the smallest shells with a prefilter of full order, q2 on the next larger.
  const std::vector<int> shells = quasi_interpolation_shells(spec, name == "q1" ? 1 : 2);
  std::vector<analysis::LatticeTap> out;
  for (const auto& w : derive_prefilter(spec, shells).weights)
    out.push_back({w.offset, to_double(w.weight)});
  return out;
}

}  // namespace boxgen::cli
