// The interpolation symbol section of `boxgen analyze` (docs/design.md §18): the generator's
// exact lattice samples and values at rational-cosine frequencies with the analysis module's
// numerical extremes, as text and as JSON (also the Python dict).
#pragma once
#include <string>

#include <nlohmann/json.hpp>

#include "generator/derivation.h"

namespace boxgen::frontend {

// The "interpolation_symbol" object of `analyze --json`.
nlohmann::json symbol_json(const generator::Derivation& a);
// Its lines for the text of `analyze`.
std::string symbol_text(const generator::Derivation& a);

}  // namespace boxgen::frontend
