#include "generator/codegen/targets/emission_report.h"

#include <fmt/format.h>

#include "generator/codegen/code_text.h"

namespace boxgen::generator {

std::string strategy_description(EmissionStrategy strategy, const std::string& form) {
  return form.empty() ? strategy_name(strategy)
                      : fmt::format("{} {}", strategy_name(strategy), form);
}

std::string considered_text(const std::vector<StrategyCost>& considered) {
  std::vector<std::string> parts;
  for (const auto& c : considered)
    parts.push_back(fmt::format("{} {} / {} / {}", strategy_name(c.strategy), c.value.total(),
                                c.gradient.total(), c.hessian.total()));
  return code::join(parts);
}

}  // namespace boxgen::generator
