#include "generator/codegen/strategies/polynomial_code.h"

#include <fmt/format.h>

#include <utility>

#include "generator/codegen/strategies/bernstein_strategy.h"
#include "generator/codegen/strategies/horner_strategy.h"
#include "generator/codegen/strategies/monomial_strategy.h"
#include "generator/codegen/strategies/separable_strategy.h"
#include "generator/codegen/strategies/shifted_strategy.h"
#include "generator/error.h"

namespace boxgen::generator {

EmissionStrategy parse_strategy(std::string_view name) {
  if (name == "auto") return EmissionStrategy::Auto;
  if (name == "monomial") return EmissionStrategy::Monomial;
  if (name == "horner") return EmissionStrategy::Horner;
  if (name == "separable") return EmissionStrategy::Separable;
  if (name == "shifted") return EmissionStrategy::Shifted;
  if (name == "bernstein") return EmissionStrategy::Bernstein;
  fail_input("--strategy must be auto, horner, shifted, bernstein, separable or monomial, got '" +
             std::string(name.substr(0, 40)) + "'");
}

const char* strategy_name(EmissionStrategy s) {
  switch (s) {
    case EmissionStrategy::Auto:
      return "auto";
    case EmissionStrategy::Monomial:
      return "monomial";
    case EmissionStrategy::Horner:
      return "horner";
    case EmissionStrategy::Separable:
      return "separable";
    case EmissionStrategy::Shifted:
      return "shifted";
    case EmissionStrategy::Bernstein:
      return "bernstein";
  }
  return "?";
}

std::optional<OrbitCode> orbit_code(const ReferenceRegion& ref, int orbit, int n, int degree,
                                    EmissionStrategy strategy) {
  switch (strategy) {
    case EmissionStrategy::Monomial:
      return strategies::monomial_code(ref, orbit, n, degree);
    case EmissionStrategy::Horner:
      return strategies::horner_code(ref, orbit, n, degree);
    case EmissionStrategy::Separable:
      return strategies::separable_code(ref, orbit, n, degree);
    case EmissionStrategy::Shifted:
      return strategies::shifted_code(ref, orbit, n, degree);
    case EmissionStrategy::Bernstein:
      return strategies::bernstein_code(ref, orbit, n, degree);
    case EmissionStrategy::Auto:
      break;
  }
  return std::nullopt;
}

namespace {

// Why a strategy does not apply to an orbit, as one line for the user.
std::string not_applicable(EmissionStrategy strategy, const ReferenceRegion& ref, int orbit,
                           int n) {
  switch (strategy) {
    case EmissionStrategy::Bernstein:
      return fmt::format(
          "--strategy bernstein: the reference region of orbit {} is not a simplex ({} vertices "
          "in {}-D)",
          orbit, ref.vertices.size(), n);
    case EmissionStrategy::Separable:
      return fmt::format(
          "--strategy separable: orbit {} is not a tensor product of univariate "
          "factors",
          orbit);
    default:
      return fmt::format("--strategy {}: no candidate origin for orbit {}", strategy_name(strategy),
                         orbit);
  }
}

}  // namespace

OrbitCode choose_orbit_code(const ReferenceRegion& ref, int orbit, int n, int degree,
                            EmissionStrategy strategy) {
  if (strategy != EmissionStrategy::Auto) {
    auto code = orbit_code(ref, orbit, n, degree, strategy);
    if (!code) fail_input(not_applicable(strategy, ref, orbit, n));
    return std::move(*code);
  }
  std::optional<OrbitCode> best;
  std::vector<StrategyCost> considered;
  // Ties keep the earlier strategy: the newer forms replace a chosen one only when cheaper.
  for (auto s : {EmissionStrategy::Horner, EmissionStrategy::Separable, EmissionStrategy::Monomial,
                 EmissionStrategy::Shifted, EmissionStrategy::Bernstein}) {
    auto code = orbit_code(ref, orbit, n, degree, s);
    if (!code) continue;
    considered.push_back({s, code->value, code->gradient, code->hessian});
    if (!best || code->gradient.total() < best->gradient.total()) best = std::move(code);
  }
  best->considered = std::move(considered);
  return std::move(*best);
}

}  // namespace boxgen::generator
