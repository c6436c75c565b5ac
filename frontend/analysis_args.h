// Parsing the analysis commands' arguments: a direction or normal "a,b,c" and the abscissae
// (--w LIST or --from A --to B --steps K). Bad input throws InputError with one line.
#pragma once
#include <string>
#include <vector>

#include "analysis/spectrum.h"
#include "frontend/commands.h"

namespace boxgen::frontend {

// A non-zero vector of `dimension` finite numbers; `what` names the option in the message.
analysis::Vec parse_direction(const std::string& text, int dimension, const std::string& what);
// The abscissae from --w or from --from/--to/--steps (linear, or logarithmic when `log`); when
// none is given, `fallback_from`..`fallback_to` with `fallback_steps` points.
std::vector<double> abscissae(const FrequencyOptions& o, bool log, double fallback_from,
                              double fallback_to, int fallback_steps, bool required);

}  // namespace boxgen::frontend
