// The report text of an emission: how each orbit's code was chosen, as the emitted headers' cost
// comments and `boxgen emit --report` print it. The strategies and their choice
// (generator/codegen/strategies/polynomial_code.h) produce the data; this module words it.
#pragma once
#include <string>
#include <vector>

#include "generator/codegen/strategies/polynomial_code.h"

namespace boxgen::generator {

// "shifted about (1,1,1)", or the strategy's name when it has no further choice.
std::string strategy_description(EmissionStrategy strategy, const std::string& form);
// "horner 282 / 408 / 540, shifted 278 / 404 / 536, ...": value / + gradient / + Hessian.
std::string considered_text(const std::vector<StrategyCost>& considered);

}  // namespace boxgen::generator
