#include "apps/boxrecon/prefilter_options.h"

#include <fmt/format.h>

#include <cmath>
#include <iostream>
#include <utility>

#include "apps/boxrecon/progress.h"
#include "frontend/filter_choice.h"

namespace boxgen::app {

using namespace boxgen::runtime;

void add_prefilter_options(CLI::App* command, PrefilterOptions& options,
                           const std::string& default_note) {
  command->add_option("--prefilter", options.prefilter,
                      fmt::format("{} ({}); interp: the spline through every sample, LAMBDA its "
                                  "Tikhonov weight where the filter's symbol vanishes",
                                  kPrefilterChoices, default_note));
  command->add_option("--boundary", options.boundary,
                      fmt::format("{}: what lies beyond the volume's faces (default {})",
                                  kBoundaryChoices, boundary_name(kDefaultBoundary)));
}

PrefilterSetting parse_prefilter_options(const PrefilterOptions& options) {
  return {parse_prefilter(options.prefilter), parse_boundary(options.boundary)};
}

std::string interpolation_line(const SplineFilter& f, const InterpolationReport& r) {
  std::string line = fmt::format(
      "interp: {} lambda {:g}",
      r.lambda > 0 ? f.name() + "'s symbol vanishes (regularised)," : f.name(), r.lambda);
  if (std::isfinite(r.residual_max))
    line += fmt::format("; residual at the samples max {:.3g}, rms {:.3g} (of max |sample|)",
                        r.residual_max, r.residual_rms);
  return line;
}

template <class T>
LatticeVolume<T> coefficients_for(LatticeVolume<T> samples, const SplineFilter& f,
                                  const PrefilterSetting& setting, InterpolationReport* report) {
  InterpolationReport r;
  LatticeVolume<T> out = [&] {
    // A solve or a large volume's prefilter takes a while, and counts no steps: a stage line.
    const Stage stage(fmt::format("prefilter {} ({} boundary)", setting.choice.text(),
                                  boundary_name(setting.boundary)));
    return spline_coefficients(std::move(samples), f, setting.choice, setting.boundary, &r);
  }();
  if (!setting.choice.is_fir() && r.lambda > 0 && !frontend::quiet())
    std::cerr << interpolation_line(f, r) << '\n';
  if (report) *report = r;
  return out;
}

template LatticeVolume<float> coefficients_for<float>(LatticeVolume<float>, const SplineFilter&,
                                                      const PrefilterSetting&,
                                                      InterpolationReport*);
template LatticeVolume<double> coefficients_for<double>(LatticeVolume<double>, const SplineFilter&,
                                                        const PrefilterSetting&,
                                                        InterpolationReport*);

}  // namespace boxgen::app
