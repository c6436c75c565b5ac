#include "frontend/analysis_inputs.h"

#include <cmath>

#include "frontend/optimised_prefilter.h"
#include "generator/error.h"
#include "generator/prefilter.h"

namespace boxgen::frontend {

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
  // q1, q2 (the leading shells of full order and the next), q1opt, q2opt or qfir:K; InputError
  // otherwise.
  const Prefilter q = is_optimised_prefilter(name) ? optimised_prefilter(spec, name).prefilter
                                                   : named_prefilter(spec, name);
  std::vector<analysis::LatticeTap> out;
  for (const auto& w : q.weights) out.push_back({w.offset, to_double(w.weight)});
  return out;
}

double density_scale(const BoxSplineSpec& spec, bool equal) {
  if (!equal) return 1.0;
  return std::pow(static_cast<double>(spec.lattice.det_abs()), -1.0 / spec.dimension());
}

}  // namespace boxgen::frontend
