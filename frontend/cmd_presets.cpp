#include <fmt/core.h>

#include "frontend/commands.h"
#include "generator/spec.h"

namespace boxgen::frontend {

int run_presets(bool json) {
  if (json) {
    nlohmann::json out = nlohmann::json::array();
    for (const auto& p : presets())
      out.push_back({{"name", p.name},
                     {"directions", p.directions},
                     {"lattice", p.lattice},
                     {"description", p.description}});
    print_json(out);
    return 0;
  }
  for (const auto& p : presets())
    fmt::print("{:<9} {:<10} {}\n{:<20} {}\n", p.name, p.lattice, p.description, "", p.directions);
  return 0;
}

}  // namespace boxgen::frontend
