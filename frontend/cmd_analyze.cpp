#include <fmt/format.h>

#include <iostream>

#include "frontend/analysis_symbol.h"
#include "frontend/commands.h"
#include "frontend/progress.h"
#include "generator/cost_estimate.h"
#include "generator/derivation.h"
#include "generator/error.h"

namespace boxgen::frontend {

Derivation analyze_derivation(const Common& c, const AnalyzeOptions& o,
                              const ProgressFn& progress) {
  const BoxSplineSpec spec = parse_spec(c.spec, c.lattice);
  if (o.checks != "default" && o.checks != "full")
    fail_input(fmt::format("--checks must be default or full, got '{}'", o.checks));
  // The derivation refuses up front, on the same estimate, what it predicts beyond the limit.
  DerivationOptions options;
  options.verify = o.verify;
  options.full_checks = o.checks == "full";
  options.progress = progress;
  options.max_seconds = c.max_seconds;
  options.max_bytes = c.max_memory_mb * 1e6;
  return derive(spec, options);
}

int run_analyze(const Common& c, const AnalyzeOptions& o) {
  const BoxSplineSpec spec = parse_spec(c.spec, c.lattice);
  if (o.checks != "default" && o.checks != "full")
    fail_input(fmt::format("--checks must be default or full, got '{}'", o.checks));
  const bool full = o.checks == "full";
  if (o.estimate_only) {
    const CostEstimate estimate = estimate_cost(spec, o.verify, full);
    if (c.json) {
      print_json({{"spec", spec.name},
                  {"estimated_seconds", estimate.seconds},
                  {"estimated_bytes", estimate.bytes},
                  {"knot_cells", estimate.knot_cells},
                  {"fundamental_cells", estimate.fundamental_cells},
                  {"cells_exact", estimate.cells_exact},
                  {"integration_level_cells", estimate.level_cells},
                  {"work",
                   {{"plane_checks", estimate.work.plane_checks},
                    {"integration", estimate.work.integration},
                    {"integration_deg", estimate.work.integration_deg},
                    {"stored", estimate.work.stored},
                    {"stencil", estimate.work.stencil},
                    {"fine", estimate.work.fine}}}});
    } else {
      fmt::print("estimated time    {:.3g} s (this machine's calibration)\n", estimate.seconds);
      fmt::print("estimated memory  {:.3g} MB\n", estimate.bytes / 1e6);
      fmt::print("knot cells        {}{}\n", estimate.knot_cells,
                 estimate.cells_exact ? "" : " (upper bound)");
    }
    return 0;
  }
  ProgressPrinter progress(o.progress);
  const Derivation a = analyze_derivation(c, o, progress.callback());
  progress.finish();
  if (c.json)
    print_json(analyze_json(a));
  else
    std::cout << to_table(a) << symbol_text(a);
  return 0;
}

nlohmann::json analyze_json(const Derivation& a) {
  nlohmann::json j = to_json(a);
  j["interpolation_symbol"] = symbol_json(a);
  return j;
}

}  // namespace boxgen::frontend
