#include "frontend/optimised_prefilter.h"

#include <string>
#include <utility>

#include "frontend/analysis_inputs.h"
#include "generator/autocorr.h"
#include "generator/error.h"

namespace boxgen::frontend {

bool is_optimised_prefilter(std::string_view name) { return name == "q1opt" || name == "q2opt"; }

OptimisedPrefilter optimised_prefilter(const BoxSplineSpec& spec, std::string_view name,
                                       const std::vector<int>& q1_shells) {
  if (!is_optimised_prefilter(name))
    fail_input("unknown prefilter '" + std::string(name.substr(0, 40)) + "': expected " +
               kPrefilterNames);
  const int which = name == "q1opt" ? 1 : 2;
  std::vector<int> shells = q1_shells;
  if (shells.empty())
    shells = quasi_interpolation_shells(spec, which);
  else if (which == 2)
    shells.push_back(shells.back() + 1);
  OptimisedPrefilter out;
  out.family = prefilter_family(spec, shells);
  analysis::PrefilterFamilyValues values;
  for (const auto& orbit : out.family.orbits) {
    auto& points = values.orbits.emplace_back();
    for (const auto& p : orbit) points.emplace_back(p.begin(), p.end());
  }
  for (const auto& w : out.family.particular) values.particular.push_back(to_double(w));
  for (const auto& v : out.family.basis) {
    auto& row = values.basis.emplace_back();
    for (const auto& w : v) row.push_back(to_double(w));
  }
  out.optimisation = analysis::minimise_integrated_error(
      spectrum_of(spec), dual_of(spec), taps_of(autocorrelation_refinement(spec)), values);
  RatVec t;
  for (double x : out.optimisation.parameters) t.push_back(exact_rational(x));
  out.prefilter = family_member(out.family, t);
  out.prefilter.parametrisation = "optimised";
  return out;
}

std::optional<OptimisedPrefilterTable> optimised_table(const BoxSplineSpec& spec,
                                                       std::string_view name,
                                                       const std::vector<int>& q1_shells) {
  try {
    OptimisedPrefilter o = optimised_prefilter(spec, name, q1_shells);
    return OptimisedPrefilterTable{std::move(o.prefilter), o.family.basis.empty()};
  } catch (const InputError&) {
    return std::nullopt;
  }
}

}  // namespace boxgen::frontend
