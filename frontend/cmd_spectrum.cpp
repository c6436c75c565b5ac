// `boxgen spectrum SPEC... (--plane n | --line d)`: |psi_hat| on a plane through 0 (an image with
// the Voronoi boundaries of the dual lattice and its points, the paper's Fig. 11) or along a line
// (a plot with the Nyquist interval shaded and a x100 panel, Fig. 12).
#include <fmt/core.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <utility>
#include <vector>

#include "analysis/gnuplot.h"
#include "frontend/analysis_args.h"
#include "frontend/analysis_inputs.h"
#include "frontend/analysis_specs.h"
#include "frontend/commands.h"
#include "generator/error.h"
#include "support/output_file.h"

namespace boxgen::frontend {

namespace {

double dot(const analysis::Vec& a, const analysis::Vec& b) {
  return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

std::string colour(std::size_t i) {
  static const char* colours[] = {"#d62728", "#1f4fd6", "#2ca02c", "#9467bd",
                                  "#ff7f0e", "#17becf", "#8c564b"};
  return colours[i % 7];
}

// The largest t with t d in the Voronoi cell.
double nyquist_extent(const analysis::VoronoiCell& cell, const analysis::Vec& d) {
  double t = 1e300;
  for (const auto& f : cell.faces) {
    const double a = dot(f.normal, d);
    if (a > 1e-14) t = std::min(t, f.offset / a);
  }
  return t;
}

// |psi_hat(w d)| of every SPEC along the line of o.line, with the Nyquist extent t of each SPEC's
// lattice.
struct LineCurves {
  std::vector<double> w;
  std::vector<double> t;
  std::vector<std::vector<double>> magnitude;
  bool one_lattice() const {
    return std::all_of(t.begin(), t.end(), [&](double x) { return x == t.front(); });
  }
};

LineCurves line_curves(const FrequencyOptions& o, const std::vector<NamedSpec>& specs, int n) {
  const analysis::Vec d = parse_direction(o.line, n, "--line");
  std::vector<double> t;
  for (const auto& s : specs)
    t.push_back(nyquist_extent(dual_of(s.spec).cell(), d) / density_scale(s.spec, o.equal_density));
  const std::vector<double> w =
      abscissae(o, false, 0, 4 * *std::max_element(t.begin(), t.end()), 801, false);
  if (!o.plot.empty()) (void)support::check_output_file(o.plot);  // before the work
  std::vector<std::vector<double>> magnitude;
  for (const auto& s : specs) {
    const auto psi = spectrum_of(s.spec);
    const double a = density_scale(s.spec, o.equal_density);
    std::vector<double> m;
    for (double x : w) m.push_back(std::abs(psi({a * x * d[0], a * x * d[1], a * x * d[2]})));
    magnitude.push_back(std::move(m));
  }
  return {w, std::move(t), std::move(magnitude)};
}

nlohmann::json line_json(const std::vector<NamedSpec>& specs, const LineCurves& c) {
  auto entry = [&](std::size_t i) {
    return nlohmann::json{
        {"w", c.w}, {"magnitude", c.magnitude[i]}, {"nyquist_interval", {-c.t[i], c.t[i]}}};
  };
  if (c.magnitude.size() == 1) return entry(0);
  nlohmann::json out = nlohmann::json::object();
  for (std::size_t i = 0; i < c.magnitude.size(); ++i) out[specs[i].key] = entry(i);
  return out;
}

// The Nyquist interval shaded when all SPECs share it, else each SPEC's bounds as dashed lines
// in its colour.
std::string nyquist_marks(const LineCurves& c) {
  if (c.one_lattice())
    return fmt::format(
        "set object 1 rect from {:.10g}, graph 0 to {:.10g}, graph 1 behind fc rgb '#d8d8d8' fs "
        "solid 1.0 noborder\n",
        -c.t.front(), c.t.front());
  std::string out;
  for (std::size_t i = 0; i < c.t.size(); ++i)
    for (const double x : {-c.t[i], c.t[i]})
      if (x >= c.w.front() && x <= c.w.back())  // gnuplot does not clip arrows to the graph
        out += fmt::format(
            "set arrow from {:.10g}, graph 0 to {:.10g}, graph 1 nohead lc rgb '{}' dt 2 lw 1.5\n",
            x, x, colour(i));
  return out;
}

int run_line(const FrequencyOptions& o, const std::vector<NamedSpec>& specs, int n) {
  const LineCurves curves = line_curves(o, specs, n);
  const auto& [w, t, magnitude] = curves;
  if (!o.plot.empty()) {
    const std::string marks =
        nyquist_marks(curves) + fmt::format("set xrange [{:.10g}:{:.10g}]", w.front(), w.back());
    analysis::PlotPanel full{
        fmt::format("|psi_hat(w ({}))|", o.line),           "w", "|psi_hat|", false, false,
        marks + "\nset yrange [0:1.05]\nset key top right", {}};
    analysis::PlotPanel zoom{"magnified x100",
                             "w",
                             "|psi_hat|",
                             false,
                             false,
                             marks + "\nset yrange [0:0.0105]\nset key top right",
                             {}};
    for (std::size_t i = 0; i < specs.size(); ++i) {
      const std::string style = fmt::format("lines lw 2 lc rgb '{}'", colour(i));
      full.series.push_back({specs[i].key, w, magnitude[i], style});
      zoom.series.push_back({specs[i].key, w, magnitude[i], style});
    }
    analysis::plot_png(o.plot, {full, zoom}, 1, 2, 1200, 450);
    return 0;
  }
  if (o.json) {
    print_json(line_json(specs, curves));
    return 0;
  }
  fmt::print("|psi_hat(w d)|, d = ({}); Nyquist interval", o.line);
  if (curves.one_lattice())
    fmt::print(" [{:.10g}, {:.10g}]\n", -t.front(), t.front());
  else
    for (std::size_t i = 0; i < specs.size(); ++i)
      fmt::print("{} {} [{:.10g}, {:.10g}]{}", i ? "," : "", specs[i].key, -t[i], t[i],
                 i + 1 == specs.size() ? "\n" : "");
  fmt::print("{:>14}", "w");
  for (const auto& s : specs) fmt::print(" {:>14}", s.key);
  fmt::print("\n");
  for (std::size_t k = 0; k < w.size(); ++k) {
    fmt::print("{:>14.8g}", w[k]);
    for (const auto& m : magnitude) fmt::print(" {:>14.6e}", m[k]);
    fmt::print("\n");
  }
  return 0;
}

// An orthonormal frame of the plane through 0 with this normal: u, v span it.
struct PlaneFrame {
  analysis::Vec normal, u, v;
};

analysis::Vec unit_cross(const analysis::Vec& a, const analysis::Vec& b) {
  analysis::Vec c{a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
  const double len = std::sqrt(dot(c, c));
  for (double& x : c) x /= len;
  return c;
}

PlaneFrame plane_frame(analysis::Vec normal) {
  const double len = std::sqrt(dot(normal, normal));
  for (double& x : normal) x /= len;
  const analysis::Vec helper =
      std::abs(normal[0]) < 0.9 ? analysis::Vec{1, 0, 0} : analysis::Vec{0, 1, 0};
  const analysis::Vec u = unit_cross(normal, helper);
  return {normal, u, unit_cross(normal, u)};
}

// The square [lo, hi]^2 of the plane, `size` pixels a side.
struct PlaneWindow {
  double lo, hi;
  int size;
  double pixel() const { return (hi - lo) / size; }
};

// The default square holds 2.5 circumradii of the largest Voronoi cell of the SPECs' dual
// lattices, so every panel shows the same frequencies.
PlaneWindow plane_window(const FrequencyOptions& o,
                         const std::vector<analysis::DualLattice>& duals) {
  double circumradius = 0;
  for (const auto& dual : duals)
    for (const auto& x : dual.cell().vertices)
      circumradius = std::max(circumradius, std::sqrt(dot(x, x)));
  if ((o.from.has_value()) != (o.to.has_value())) fail_input("--from and --to go together");
  const double lo = o.from.value_or(-2.5 * circumradius), hi = o.to.value_or(2.5 * circumradius);
  if (!std::isfinite(lo) || !std::isfinite(hi) || !(hi > lo))
    fail_input(fmt::format("empty or inverted range: --from {} --to {} (need from < to)", lo, hi));
  const int size = o.size;
  if (size < 16 || size > 4096)
    fail_input(fmt::format("--size must be between 16 and 4096, got {}", size));
  return {lo, hi, size};
}

// One panel: log10 |psi_hat| over [-4, 0] (the colour bar); NaN (white) where a Voronoi boundary
// of the dual lattice crosses the pixel; the dual lattice points lying in the plane as white
// discs.
template <class Psi>
analysis::ImagePanel magnitude_panel(const Psi& psi, const analysis::DualLattice& dual,
                                     const PlaneFrame& f, const PlaneWindow& win, double scale) {
  analysis::ImagePanel panel;
  panel.columns = panel.rows = win.size;
  panel.x_lo = panel.y_lo = win.lo;
  panel.x_hi = panel.y_hi = win.hi;
  panel.value_lo = -4;
  panel.value_hi = 0;
  panel.value_label = "log10 |psi_hat|";
  panel.xlabel = "u";
  panel.ylabel = "v";
  const double pixel = win.pixel();
  for (int py = 0; py < win.size; ++py)  // bottom row first
    for (int px = 0; px < win.size; ++px) {
      const double a = win.lo + (px + 0.5) * pixel, b = win.lo + (py + 0.5) * pixel;
      // The SPEC's own frequency (scale: --equal-density's a; distances to the dual lattice
      // measured in the plane's units).
      const analysis::Vec w{scale * (a * f.u[0] + b * f.v[0]), scale * (a * f.u[1] + b * f.v[1]),
                            scale * (a * f.u[2] + b * f.v[2])};
      double g = 0;
      dual.nearest(w, &g);
      panel.values.push_back(g / scale >= 1.2 * pixel
                                 ? std::log10(std::max(std::abs(psi(w)), 1e-300))
                                 : std::numeric_limits<double>::quiet_NaN());
    }
  const double reach = std::max(std::abs(win.lo), std::abs(win.hi)) * std::sqrt(2.0) + pixel;
  for (const auto& k : dual.points_within(reach * scale))
    if (std::abs(dot(k, f.normal)) < 1e-9 * (1 + reach * scale))
      panel.dots.push_back({dot(k, f.u) / scale, dot(k, f.v) / scale});
  return panel;
}

// One panel per filter, side by side, each titled with its key and lattice, with a colour bar.
int run_plane(const FrequencyOptions& o, const std::vector<NamedSpec>& specs, int n) {
  if (n != 3) fail_input("--plane needs 3-D filters (for 2-D filters use --line)");
  if (o.plot.empty()) fail_input("--plane draws an image: give -o out.png");
  if (o.json) fail_input("--json is for --line (a plane is an image)");
  if (!o.w.empty() || o.steps != 0)
    fail_input("--plane takes --from/--to (the square's range), not --w or --steps");
  const PlaneFrame frame = plane_frame(parse_direction(o.plane, 3, "--plane"));
  std::vector<analysis::DualLattice> duals;
  for (const auto& s : specs) duals.push_back(dual_of(s.spec));
  const PlaneWindow win = plane_window(o, duals);
  (void)support::check_output_file(o.plot);  // before the work
  std::vector<analysis::ImagePanel> panels;
  for (std::size_t i = 0; i < specs.size(); ++i) {
    panels.push_back(magnitude_panel(spectrum_of(specs[i].spec), duals[i], frame, win,
                                     density_scale(specs[i].spec, o.equal_density)));
    panels.back().title = fmt::format("{} ({})", specs[i].key, specs[i].spec.lattice.name());
  }
  analysis::image_png(o.plot, panels);  // count * (size + 200) by size + 100 pixels
  return 0;
}

// The SPECs of one spectrum, all of one dimension.
std::vector<NamedSpec> spectrum_specs(const FrequencyOptions& o) {
  std::vector<NamedSpec> specs = parse_named_specs(o.specs, o.lattice, o.labels);
  for (const auto& s : specs)
    if (s.spec.dimension() != specs.front().spec.dimension())
      fail_input("all SPECs of one spectrum must have the same dimension");
  return specs;
}

}  // namespace

nlohmann::json spectrum_json(const FrequencyOptions& o) {
  const std::vector<NamedSpec> specs = spectrum_specs(o);
  if (o.line.empty()) fail_input("a spectrum as numbers is along a line: give --line a,b,c");
  return line_json(specs, line_curves(o, specs, specs.front().spec.dimension()));
}

int run_spectrum(const FrequencyOptions& o) {
  const std::vector<NamedSpec> specs = spectrum_specs(o);
  const int n = specs.front().spec.dimension();
  if (o.plane.empty() == o.line.empty())
    fail_input("give exactly one of --plane a,b,c or --line a,b,c");
  return o.line.empty() ? run_plane(o, specs, n) : run_line(o, specs, n);
}

}  // namespace boxgen::frontend
