// `boxgen kernel SPEC...`: the Blu-Unser error kernel E(w d) of each filter with a prefilter
// (docs/design.md §9-§10; the paper's Fig. 13), from the exact autocorrelation samples.
#include <fmt/core.h>

#include <cmath>
#include <map>
#include <numbers>
#include <string>

#include "analysis/error_kernel.h"
#include "analysis/gnuplot.h"
#include "frontend/analysis_args.h"
#include "frontend/analysis_inputs.h"
#include "frontend/analysis_specs.h"
#include "frontend/commands.h"
#include "frontend/optimised_prefilter.h"
#include "generator/autocorr.h"
#include "generator/error.h"
#include "support/output_file.h"

namespace boxgen::frontend {

namespace {

// The paper's colours: M7 red, M8 blue, M12 green, then others.
std::string colour(std::size_t i) {
  static const char* colours[] = {"#d62728", "#1f4fd6", "#2ca02c", "#9467bd",
                                  "#ff7f0e", "#17becf", "#8c564b"};
  return colours[i % 7];
}
std::string dark_colour(std::size_t i) {
  static const char* colours[] = {"#7f0000", "#00005f", "#004d00", "#3f1f5f",
                                  "#7f3f00", "#004f5f", "#3f2a20"};
  return colours[i % 7];
}

struct Curves {
  std::string key;
  std::map<std::string, std::vector<double>> e;  // prefilter name -> E
};

std::vector<double> kernel_values(const analysis::ErrorKernel& e, const analysis::Vec& d,
                                  const std::vector<double>& w, bool minimum) {
  std::vector<double> out;
  for (double x : w) {
    const analysis::Vec p{x * d[0], x * d[1], x * d[2]};
    out.push_back(static_cast<double>(minimum ? e.minimum(p) : e(p)));
  }
  return out;
}

// The curves of every SPEC at the abscissae: the one prefilter asked for, or, for a plot, none, q1,
// q2 and the minimum.
struct KernelCurves {
  std::string direction;
  std::vector<double> w;
  std::vector<Curves> all;
};

KernelCurves kernel_curves(const FrequencyOptions& o, bool plot) {
  const std::vector<NamedSpec> specs = parse_named_specs(o.specs, o.lattice, o.labels);
  const int n = specs.front().spec.dimension();
  for (const auto& s : specs)
    if (s.spec.dimension() != n)
      fail_input("all SPECs of one kernel command must have the same dimension");
  const bool known = o.prefilter == "none" || o.prefilter == "q1" || o.prefilter == "q2" ||
                     is_optimised_prefilter(o.prefilter) || o.prefilter == "min" ||
                     is_interpolation(o.prefilter) || o.prefilter.starts_with("qfir:");
  if (!known)
    fail_input("unknown prefilter '" + o.prefilter.substr(0, 40) +
               "': expected none, q1, q2, q1opt, q2opt, qfir:K, interp, interp:LAMBDA or min");
  const std::string direction = !o.direction.empty() ? o.direction : (n == 3 ? "1,1,1" : "1,1");
  const analysis::Vec d = parse_direction(direction, n, "--direction");
  // A plot defaults to the low band of Fig. 13: w from 0.05 to pi/2 (the Nyquist boundary of
  // BCC along (1,1,1)), log-spaced.
  const std::vector<double> w = abscissae(o, plot, 0.05, std::numbers::pi / 2, 120, !plot);
  if (plot) (void)support::check_output_file(o.plot);  // an unwritable --plot fails first

  std::vector<Curves> all;
  for (const auto& named : specs) {
    const auto& spec = named.spec;
    const auto taps =
        about_spec(named.text, [&] { return taps_of(autocorrelation_refinement(spec)); });
    const double det = static_cast<double>(spec.lattice.det_abs());
    const double a = density_scale(spec, o.equal_density);
    const analysis::Vec da{a * d[0], a * d[1], a * d[2]};
    Curves c{named.key, {}};
    const std::vector<std::string> names = plot
                                               ? std::vector<std::string>{"none", "q1", "q2", "min"}
                                               : std::vector<std::string>{o.prefilter};
    for (const auto& name : names) {
      std::vector<analysis::LatticeTap> prefilter;
      try {
        if (name != "min" && !is_interpolation(name))
          prefilter = about_spec(named.text, [&] { return prefilter_taps_of(spec, name); });
      } catch (const InputError& e) {
        if (!plot) throw;
        // A plot draws the curves that exist and says which one it leaves out.
        fmt::print(stderr, "boxgen: kernel: {} left out of the plot: {}\n", name, e.what());
        continue;
      }
      if (is_interpolation(name)) {
        const analysis::ErrorKernel e = about_spec(
            named.text, [&] { return interpolation_kernel(spec, named.key, taps, name); });
        c.e[name] = kernel_values(e, da, w, false);
        continue;
      }
      const analysis::ErrorKernel e(spectrum_of(spec), det, taps, prefilter);
      c.e[name] = kernel_values(e, da, w, name == "min");
    }
    all.push_back(std::move(c));
  }
  return {direction, w, std::move(all)};
}

}  // namespace

nlohmann::json kernel_json(const FrequencyOptions& o) {
  const KernelCurves k = kernel_curves(o, false);
  const std::string& name = o.prefilter;
  if (k.all.size() == 1) return {{"w", k.w}, {"E", k.all.front().e.at(name)}};
  nlohmann::json out = nlohmann::json::object();
  for (const auto& c : k.all) out[c.key] = {{"w", k.w}, {"E", c.e.at(name)}};
  return out;
}

int run_kernel(const FrequencyOptions& o) {
  const bool plot = !o.plot.empty();
  if (o.json && !plot) {
    print_json(kernel_json(o));
    return 0;
  }
  const auto [direction, w, all] = kernel_curves(o, plot);
  if (plot) {
    analysis::PlotPanel panel;
    panel.title = fmt::format("Error kernels E(w ({}))", direction);
    panel.xlabel = "w";
    panel.ylabel = "E";
    panel.log_x = panel.log_y = true;
    panel.extra = "set key bottom right font ',8'\nset autoscale xfix\nset yrange [1e-16:2]";
    const std::map<std::string, std::string> dash = {
        {"none", "dt 3"}, {"q1", "dt 2"}, {"q2", "dt 1"}};
    const std::map<std::string, std::string> label = {
        {"none", "no prefilter"}, {"q1", "Q^I"}, {"q2", "Q^{II}"}};
    for (std::size_t i = all.size(); i-- > 0;) {  // the first SPEC drawn last, on top
      for (const std::string name : {"none", "q1", "q2"})
        if (all[i].e.count(name))
          panel.series.push_back(
              {fmt::format("{} {}", all[i].key, label.at(name)), w, all[i].e.at(name),
               fmt::format("lines lw 2 lc rgb '{}' {}", colour(i), dash.at(name))});
      panel.series.push_back({fmt::format("{} E_{{min}}", all[i].key), w, all[i].e.at("min"),
                              fmt::format("lines lw 2 lc rgb '{}' dt 1", dark_colour(i))});
    }
    analysis::plot_png(o.plot, {panel}, 1, 1, 900, 700);
    return 0;
  }
  const std::string& name = o.prefilter;
  fmt::print("error kernel E(w d), d = ({}), prefilter {}\n", direction, name);
  fmt::print("{:>14}", "w");
  for (const auto& c : all) fmt::print(" {:>14}", c.key);
  fmt::print("\n");
  for (std::size_t k = 0; k < w.size(); ++k) {
    fmt::print("{:>14.8g}", w[k]);
    for (const auto& c : all) fmt::print(" {:>14.6e}", c.e.at(name)[k]);
    fmt::print("\n");
  }
  return 0;
}

}  // namespace boxgen::frontend
