#include <fmt/core.h>

#include "apps/boxgen/commands.h"
#include "generator/emitter.h"

namespace boxgen::cli {

int run_emit(const Common& c, const std::string& name, const std::string& out, const std::string& strategy) {
  const EmissionStrategy chosen = parse_strategy(strategy);  // before the derivation: fail fast
  const BoxSplineSpec spec = parse_spec(c.spec, c.lattice);
  const Analysis a = analyze(spec);  // the exact checks run before anything is emitted
  EmissionRequest request{name,
                          fmt::format("boxgen emit {} {}--name {} --strategy {} --out <dir>",
                                      spec.name == "custom" ? "\"" + spec.text + "\"" : spec.name,
                                      c.lattice.empty() ? "" : "--lattice \"" + c.lattice + "\" ", name, strategy),
                          chosen};
  const auto files = emit(a, request);
  write_files(files, out);
  if (c.json) {
    nlohmann::json j = nlohmann::json::array();
    for (const auto& f : files) j.push_back(out + "/" + f.filename);
    print_json({{"files", j}});
  } else {
    for (const auto& f : files) fmt::print("{}/{}\n", out, f.filename);
  }
  return 0;
}

}  // namespace boxgen::cli
