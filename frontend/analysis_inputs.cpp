#include "frontend/analysis_inputs.h"

#include <fmt/format.h>

#include <array>
#include <cmath>
#include <cstdint>
#include <exception>
#include <optional>
#include <stdexcept>
#include <utility>

#include "frontend/optimised_prefilter.h"
#include "generator/approximation_order.h"
#include "generator/error.h"
#include "generator/interpolation_symbol.h"
#include "generator/prefilter.h"
#include "support/lattice_regulariser.h"

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

bool is_interpolation(const std::string& prefilter) {
  return prefilter == "interp" || prefilter.starts_with("interp:");
}

namespace {

// The LAMBDA of "interp:LAMBDA" (none for "interp": the runtime's choice), read as the runtime
// reads it; support::regularisation checks the range.
std::optional<double> interpolation_lambda(const std::string& prefilter) {
  if (prefilter == "interp") return std::nullopt;
  const std::string number = prefilter.substr(7, 40);
  std::size_t used = 0;
  double lambda = 0;
  try {
    lambda = std::stod(number, &used);
  } catch (const std::exception&) {
    used = 0;
  }
  if (number.empty() || used != number.size())
    fail_input(
        fmt::format("prefilter '{}': the regularisation after interp: must be a number in [0, 1]",
                    prefilter.substr(0, 40)));
  return lambda;
}

}  // namespace

analysis::ErrorKernel interpolation_kernel(const BoxSplineSpec& spec, const std::string& name,
                                           const std::vector<analysis::LatticeTap>& autocorrelation,
                                           const std::string& prefilter) {
  const std::optional<double> lambda = interpolation_lambda(prefilter);
  const int n = spec.dimension();
  std::vector<analysis::LatticeTap> samples;
  support::LatticeTaps values;
  for (const auto& s : lattice_samples(spec)) {
    samples.push_back({s.point, to_double(s.value)});
    std::array<int, 3> at{0, 0, 0};
    for (std::size_t i = 0; i < s.point.size(); ++i) at[i] = static_cast<int>(s.point[i]);
    values.push_back({at, samples.back().value});
  }
  const std::vector<std::vector<std::int64_t>> basis(spec.lattice.generator().begin(),
                                                     spec.lattice.generator().end());
  support::Regularisation r;
  try {
    r = support::regularisation(values, basis, approximation_order(spec.directions, n), lambda,
                                name);
  } catch (const std::invalid_argument& e) {
    fail_input(fmt::format("prefilter {}: {}", prefilter.substr(0, 40), e.what()));
  }
  std::vector<analysis::LatticeTap> d;
  for (const auto& [at, w] : r.regulariser)
    d.push_back({std::vector<std::int64_t>(at.begin(), at.begin() + n), w});
  return analysis::ErrorKernel::regularised_interpolation(
      spectrum_of(spec), static_cast<double>(spec.lattice.det_abs()), autocorrelation,
      std::move(samples), std::move(d), r.mu);
}

}  // namespace boxgen::frontend
