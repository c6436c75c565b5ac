// `boxgen spectrum SPEC... (--plane n | --line d)`: |psi_hat| on a plane through 0 (an image with
// the Voronoi boundaries of the dual lattice and its points, the paper's Fig. 11) or along a line
// (a plot with the Nyquist interval shaded and a x100 panel, Fig. 12).
#include <fmt/core.h>

#include <algorithm>
#include <cmath>
#include <utility>
#include <vector>

#include "analysis/gnuplot.h"
#include "analysis/png_image.h"
#include "apps/boxgen/analysis_args.h"
#include "apps/boxgen/analysis_inputs.h"
#include "apps/boxgen/commands.h"
#include "generator/error.h"
#include "support/output_file.h"

namespace boxgen::cli {

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

void require_one_lattice(const std::vector<BoxSplineSpec>& specs) {
  for (const auto& s : specs)
    if (s.lattice.generator() != specs.front().lattice.generator())
      fail_input("all SPECs of one spectrum must be on the same lattice");
}

// |psi_hat(w d)| of every SPEC along the line of o.line, with the Nyquist extent t.
struct LineCurves {
  std::vector<double> w;
  double t;
  std::vector<std::vector<double>> magnitude;
};

LineCurves line_curves(const FrequencyOptions& o, const std::vector<BoxSplineSpec>& specs, int n) {
  const analysis::Vec d = parse_direction(o.line, n, "--line");
  require_one_lattice(specs);
  const analysis::DualLattice dual = dual_of(specs.front());
  const double t = nyquist_extent(dual.cell(), d);
  const std::vector<double> w = abscissae(o, false, 0, 4 * t, 801, false);
  if (!o.plot.empty()) (void)support::check_output_file(o.plot);  // before the work
  std::vector<std::vector<double>> magnitude;
  for (const auto& spec : specs) {
    const auto psi = spectrum_of(spec);
    std::vector<double> m;
    for (double x : w) m.push_back(std::abs(psi({x * d[0], x * d[1], x * d[2]})));
    magnitude.push_back(std::move(m));
  }
  return {w, t, std::move(magnitude)};
}

nlohmann::json line_json(const FrequencyOptions& o, const LineCurves& c) {
  const double t = c.t;
  if (c.magnitude.size() == 1)
    return {{"w", c.w}, {"magnitude", c.magnitude.front()}, {"nyquist_interval", {-t, t}}};
  nlohmann::json out = nlohmann::json::object();
  for (std::size_t i = 0; i < c.magnitude.size(); ++i)
    out[o.specs[i]] = {{"w", c.w}, {"magnitude", c.magnitude[i]}, {"nyquist_interval", {-t, t}}};
  return out;
}

int run_line(const FrequencyOptions& o, const std::vector<BoxSplineSpec>& specs, int n) {
  const LineCurves curves = line_curves(o, specs, n);
  const auto& [w, t, magnitude] = curves;
  if (!o.plot.empty()) {
    const std::string shade = fmt::format(
        "set object 1 rect from {:.10g}, graph 0 to {:.10g}, graph 1 behind fc rgb '#d8d8d8' fs "
        "solid 1.0 noborder\n"
        "set xrange [{:.10g}:{:.10g}]",
        -t, t, w.front(), w.back());
    analysis::PlotPanel full{
        fmt::format("|psi_hat(w ({}))|", o.line),           "w", "|psi_hat|", false, false,
        shade + "\nset yrange [0:1.05]\nset key top right", {}};
    analysis::PlotPanel zoom{"magnified x100",
                             "w",
                             "|psi_hat|",
                             false,
                             false,
                             shade + "\nset yrange [0:0.0105]\nset key top right",
                             {}};
    for (std::size_t i = 0; i < specs.size(); ++i) {
      const std::string style = fmt::format("lines lw 2 lc rgb '{}'", colour(i));
      full.series.push_back({o.specs[i], w, magnitude[i], style});
      zoom.series.push_back({o.specs[i], w, magnitude[i], style});
    }
    analysis::plot_png(o.plot, {full, zoom}, 1, 2, 1200, 450);
    return 0;
  }
  if (o.json) {
    print_json(line_json(o, curves));
    return 0;
  }
  fmt::print("|psi_hat(w d)|, d = ({}); Nyquist interval [{:.10g}, {:.10g}]\n{:>14}", o.line, -t, t,
             "w");
  for (const auto& s : o.specs) fmt::print(" {:>14}", s);
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

PlaneWindow plane_window(const FrequencyOptions& o, const analysis::DualLattice& dual) {
  double circumradius = 0;
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

// log10 |psi_hat| from -4 (dark) to 0 (yellow); white where a Voronoi boundary of the dual
// lattice crosses the pixel.
template <class Psi>
void paint_magnitude(analysis::RgbImage& image, int x0, const Psi& psi,
                     const analysis::DualLattice& dual, const PlaneFrame& f,
                     const PlaneWindow& win) {
  const double pixel = win.pixel();
  for (int py = 0; py < win.size; ++py)
    for (int px = 0; px < win.size; ++px) {
      const double a = win.lo + (px + 0.5) * pixel, b = win.hi - (py + 0.5) * pixel;
      const analysis::Vec w{a * f.u[0] + b * f.v[0], a * f.u[1] + b * f.v[1],
                            a * f.u[2] + b * f.v[2]};
      double g = 0;
      dual.nearest(w, &g);
      std::uint8_t r = 255, gg = 255, bb = 255;
      if (g >= 1.2 * pixel)
        analysis::colour_map((std::log10(std::max(std::abs(psi(w)), 1e-300)) + 4) / 4, r, gg, bb);
      image.set(x0 + px, py, r, gg, bb);
    }
}

// The dual lattice points lying in the plane, in its (u, v) coordinates.
std::vector<std::pair<double, double>> points_in_plane(const analysis::DualLattice& dual,
                                                       const PlaneFrame& f,
                                                       const PlaneWindow& win) {
  std::vector<std::pair<double, double>> dots;
  const double reach = std::max(std::abs(win.lo), std::abs(win.hi)) * std::sqrt(2.0) + win.pixel();
  for (const auto& k : dual.points_within(reach))
    if (std::abs(dot(k, f.normal)) < 1e-9 * (1 + reach)) dots.push_back({dot(k, f.u), dot(k, f.v)});
  return dots;
}

void draw_disc(analysis::RgbImage& image, int x0, const PlaneWindow& win, double cx, double cy,
               double radius) {
  const int reach = 4 * static_cast<int>(radius);
  for (int dy = -reach; dy <= reach; ++dy)
    for (int dx = -reach; dx <= reach; ++dx) {
      const int px = static_cast<int>(std::floor(cx)) + dx,
                py = static_cast<int>(std::floor(cy)) + dy;
      if (px < 0 || px >= win.size || py < 0 || py >= win.size) continue;
      if (std::hypot(px + 0.5 - cx, py + 0.5 - cy) <= radius) image.set(x0 + px, py, 255, 255, 255);
    }
}

// One panel per filter, side by side: log10 |psi_hat|, the boundaries of the dual lattice's
// Voronoi cells in the plane (white) and the dual lattice points lying in the plane (white discs).
int run_plane(const FrequencyOptions& o, const std::vector<BoxSplineSpec>& specs, int n) {
  if (n != 3) fail_input("--plane needs 3-D filters (for 2-D filters use --line)");
  if (o.plot.empty()) fail_input("--plane draws an image: give -o out.png");
  if (o.json) fail_input("--json is for --line (a plane is an image)");
  if (!o.w.empty() || o.steps != 0)
    fail_input("--plane takes --from/--to (the square's range), not --w or --steps");
  const PlaneFrame frame = plane_frame(parse_direction(o.plane, 3, "--plane"));
  require_one_lattice(specs);
  const analysis::DualLattice dual = dual_of(specs.front());
  const PlaneWindow win = plane_window(o, dual);
  (void)support::check_output_file(o.plot);  // before the work
  const int gap = 8;
  const int count = static_cast<int>(specs.size());
  analysis::RgbImage image(count * win.size + (count - 1) * gap, win.size);
  std::fill(image.pixels.begin(), image.pixels.end(), 255);
  const auto dots = points_in_plane(dual, frame, win);
  const double radius = std::max(2.0, win.size / 120.0);
  for (int s = 0; s < count; ++s) {
    const int x0 = s * (win.size + gap);
    paint_magnitude(image, x0, spectrum_of(specs[s]), dual, frame, win);
    for (const auto& [a, b] : dots)
      draw_disc(image, x0, win, (a - win.lo) / win.pixel(), (win.hi - b) / win.pixel(), radius);
  }
  analysis::write_png(o.plot, image);
  return 0;
}

// The SPECs of one spectrum, all of one dimension.
std::vector<BoxSplineSpec> spectrum_specs(const FrequencyOptions& o) {
  std::vector<BoxSplineSpec> specs;
  for (const auto& s : o.specs) specs.push_back(parse_spec(s, o.lattice));
  for (const auto& s : specs)
    if (s.dimension() != specs.front().dimension())
      fail_input("all SPECs of one spectrum must have the same dimension");
  return specs;
}

}  // namespace

nlohmann::json spectrum_json(const FrequencyOptions& o) {
  const std::vector<BoxSplineSpec> specs = spectrum_specs(o);
  if (o.line.empty()) fail_input("a spectrum as numbers is along a line: give --line a,b,c");
  return line_json(o, line_curves(o, specs, specs.front().dimension()));
}

int run_spectrum(const FrequencyOptions& o) {
  const std::vector<BoxSplineSpec> specs = spectrum_specs(o);
  const int n = specs.front().dimension();
  if (o.plane.empty() == o.line.empty())
    fail_input("give exactly one of --plane a,b,c or --line a,b,c");
  return o.line.empty() ? run_plane(o, specs, n) : run_line(o, specs, n);
}

}  // namespace boxgen::cli
