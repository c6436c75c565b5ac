// `boxgen metrics SPEC...`: the Marschner-Lobb smoothing and postaliasing of each filter
// (docs/design.md §10, the paper's Table 3), with the quadrature's convergence shown.
#include <fmt/core.h>

#include <chrono>
#include <cmath>
#include <map>
#include <optional>

#include "analysis/filter_metrics.h"
#include "frontend/analysis_inputs.h"
#include "frontend/analysis_specs.h"
#include "frontend/commands.h"
#include "generator/autocorr.h"

namespace boxgen::frontend {

namespace {

struct PaperRow {
  double smoothing, postaliasing;
};

// The digits printed in Kim 2013, Table 3 (for comparison only; nothing is computed from them).
std::optional<PaperRow> paper_table3(const std::string& preset) {
  static const std::map<std::string, PaperRow> rows = {
      {"m12", {0.94495, 0.00004}}, {"m8", {0.85287, 0.00399}}, {"m7", {0.85488, 0.00355}}};
  const auto it = rows.find(preset);
  if (it == rows.end()) return std::nullopt;
  return it->second;
}

struct MetricsRow {
  NamedSpec s;
  Rational a0;
  analysis::FilterMetrics m;
  double seconds;
};

std::vector<MetricsRow> metrics_rows(const FrequencyOptions& o) {
  std::vector<MetricsRow> rows;
  for (auto& s : parse_named_specs(o.specs, o.lattice, o.labels))  // all parsed before any work
    rows.push_back({std::move(s), Rational(0), {}, 0});
  for (auto& r : rows) {
    const auto start = std::chrono::steady_clock::now();
    r.a0 =
        about_spec(r.s.text, [&] { return autocorrelation_refinement(r.s.spec).integral_squared; });
    r.m = analysis::filter_metrics(spectrum_of(r.s.spec), dual_of(r.s.spec), to_double(r.a0));
    if (o.equal_density) {
      // S and P are ratios of integrals over frequencies, unchanged when the lattice and the
      // filter are scaled together; the volumes and integrals are those at unit density.
      const double volume = std::pow(density_scale(r.s.spec, true), -r.s.spec.dimension());
      r.m.nyquist_volume *= volume;
      r.m.inside *= volume;
      r.m.total *= volume;
      for (auto& s : r.m.steps) {
        s.iterated *= volume;
        s.simplex_fan *= volume;
      }
    }
    r.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  }
  return rows;
}

}  // namespace

nlohmann::json metrics_json(const FrequencyOptions& o) {
  nlohmann::json out = nlohmann::json::object();
  for (const auto& r : metrics_rows(o)) {
    nlohmann::json steps = nlohmann::json::array();
    for (const auto& s : r.m.steps)
      steps.push_back(
          {{"order", s.order}, {"iterated", s.iterated}, {"simplex_fan", s.simplex_fan}});
    out[r.s.key] = {{"smoothing", r.m.smoothing},
                    {"postaliasing", r.m.postaliasing},
                    {"integral_squared", to_string(r.a0)},
                    {"lattice", r.s.spec.lattice.name()},
                    {"nyquist_volume", r.m.nyquist_volume},
                    {"integral_inside", r.m.inside},
                    {"integral_total", r.m.total},
                    {"estimated_error", r.m.estimated_error},
                    {"quadrature", steps}};
  }
  return out;
}

int run_metrics(const FrequencyOptions& o) {
  if (o.json) {
    print_json(metrics_json(o));
    return 0;
  }
  const std::vector<MetricsRow> rows = metrics_rows(o);
  fmt::print(
      "Marschner-Lobb filter metrics of psi = M^c (S = 1 - (1/|N|) int_N |psi_hat|^2, "
      "P = (1/|N|) int_outside N |psi_hat|^2)\n");
  fmt::print("{:<10} {:<10} {:>12} {:>12} {:>9} {:>10} {:>10}  {}\n", "filter", "lattice",
             "smoothing", "postaliasing", "error<=", "paper S", "paper P", "int (M^c)^2 = a(0)");
  for (const auto& r : rows) {
    // The paper's row only for the preset on its own lattice.
    const auto& spec = r.s.spec;
    const auto paper = spec.lattice.name() == "bcc" ? paper_table3(spec.name) : std::nullopt;
    fmt::print("{:<10} {:<10} {:>12.7g} {:>12.7g} {:>9.1e} {:>10} {:>10}  {}\n", r.s.key,
               spec.lattice.name(), r.m.smoothing, r.m.postaliasing, r.m.estimated_error,
               paper ? fmt::format("{:.5f}", paper->smoothing) : "-",
               paper ? fmt::format("{:.5f}", paper->postaliasing) : "-", to_string(r.a0));
  }
  fmt::print(
      "\nquadrature of int_N |psi_hat|^2 (Gauss-Legendre of the given order per variable; two "
      "independent "
      "rules)\n");
  for (const auto& r : rows) {
    fmt::print("{} (|N| = {:.12g}, (2 pi)^n a(0) = {:.15g}, {:.2f} s)\n", r.s.key,
               r.m.nyquist_volume, r.m.total, r.seconds);
    fmt::print("  {:>5} {:>22} {:>22} {:>10}\n", "order", "iterated (breakpoints)",
               "simplex fan (Duffy)", "difference");
    for (const auto& s : r.m.steps)
      fmt::print("  {:>5} {:>22.15f} {:>22.15f} {:>10.1e}\n", s.order, s.iterated, s.simplex_fan,
                 std::abs(s.iterated - s.simplex_fan));
  }
  return 0;
}

}  // namespace boxgen::frontend
