#include "analysis/gnuplot.h"

#include <fmt/format.h>
#include <sys/wait.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <stdexcept>
#include <string_view>

#include "analysis/png_image.h"
#include "support/output_file.h"

namespace boxgen::analysis {

namespace {

// gnuplot single-quoted string: a quote is doubled.
std::string quoted(const std::string& s) {
  std::string out = "'";
  for (char c : s) {
    if (c == '\'')
      out += "''";
    else if (c != '\n')
      out += c;
  }
  return out + "'";
}

// Whether the file ends with a PNG's IEND chunk: gnuplot exits 0 even when its output was cut
// short (a file size limit, a full disk).
bool png_complete(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary | std::ios::ate);
  const auto size = static_cast<std::streamoff>(in.tellg());
  if (!in || size < 12) return false;
  char tail[8] = {};
  in.seekg(size - 8);
  in.read(tail, 8);
  return in && std::string_view(tail, 8) == std::string_view("IEND\xae\x42\x60\x82", 8);
}

// Runs gnuplot on `script` (everything after the terminal and output) and commits the PNG.
void run_gnuplot(const std::string& path, int width, int height, const std::string& body) {
  support::PendingOutput out(path);
  std::string script =
      fmt::format("set terminal pngcairo size {},{} enhanced font 'Sans,10'\n", width, height);
  script += fmt::format("set output {}\n", quoted(out.temporary().string()));
  script += body;
  std::FILE* pipe = ::popen("gnuplot 2>&1 >/dev/null", "w");
  if (!pipe) throw std::runtime_error("cannot start gnuplot (install gnuplot-nox)");
  const bool written = std::fwrite(script.data(), 1, script.size(), pipe) == script.size();
  const int status = ::pclose(pipe);
  if (!written || status == -1 || !WIFEXITED(status) || WEXITSTATUS(status) != 0)
    throw std::runtime_error(
        fmt::format("gnuplot failed to draw '{}' (is gnuplot-nox installed?)", path));
  out.commit(png_complete(out.temporary())
                 ? ""
                 : "gnuplot could not write the whole PNG (file too large, or the disk is full)");
}

// gnuplot's palette: for viridis colour_map()'s colours at six evenly spaced stops, linear
// between.
std::string palette(Palette p) {
  if (p == Palette::grey) return "set palette defined (0 '#000000', 1 '#ffffff')\n";
  if (p == Palette::difference)
    return "set palette defined (0 '#0000ff', 1 '#ffffff', 2 '#ff0000')\n";
  std::string out = "set palette defined (";
  for (int i = 0; i <= 5; ++i) {
    std::uint8_t r = 0, g = 0, b = 0;
    colour_map(i / 5.0, r, g, b);
    out += fmt::format("{}{} '#{:02x}{:02x}{:02x}'", i ? ", " : "", i, r, g, b);
  }
  return out + ")\n";
}

// A step of 1, 2 or 5 times a power of ten that puts tics at least `gap` pixels apart on an axis
// of `pixels` pixels spanning `range`.
double tic_step(double range, int pixels, int gap) {
  const double least = range * gap / std::max(pixels, 1);
  if (!(least > 0 && std::isfinite(least))) return 1;
  const double power = std::pow(10.0, std::floor(std::log10(least)));
  for (const double m : {1.0, 2.0, 5.0})
    if (m * power >= least) return m * power;
  return 10 * power;
}

// Values below this are written for NaN (gnuplot warns about NaN in a matrix) and drawn as NaN.
constexpr double kBlank = -1e300;

}  // namespace

void image_png(const std::string& path, const std::vector<ImagePanel>& panels) {
  // Each panel: 70 pixels for the y axis, the image, a gap of 15, the colour bar 20 wide, 95 for
  // its tics and label; 60 below the image for the x axis, 40 above it for the title.
  int width = 0, height = 0;
  for (const auto& panel : panels) {
    width += panel.columns * panel.zoom + kImagePanelMarginX;
    height = std::max(height, panel.rows * panel.zoom + kImagePanelMarginY);
  }
  std::string script;
  for (std::size_t p = 0; p < panels.size(); ++p) {
    const auto& panel = panels[p];
    script += fmt::format("$i{} << EOD\n", p);
    for (int y = 0; y < panel.rows; ++y) {
      for (int x = 0; x < panel.columns; ++x) {
        const double v = panel.values[static_cast<std::size_t>(y) * panel.columns + x];
        script += fmt::format("{}{:.6g}", x ? " " : "", std::isnan(v) ? kBlank : v);
      }
      script += "\n";
    }
    script += fmt::format("EOD\n$p{} << EOD\n", p);
    for (const auto& [a, b] : panel.dots) script += fmt::format("{:.10g} {:.10g}\n", a, b);
    script += "EOD\n";
  }
  script += "set multiplot\n";
  int x0 = 0;  // the panel's left edge, pixels
  for (std::size_t p = 0; p < panels.size(); ++p) {
    const auto& panel = panels[p];
    const double dx = (panel.x_hi - panel.x_lo) / panel.columns,
                 dy = (panel.y_hi - panel.y_lo) / panel.rows;
    const int w = panel.columns * panel.zoom, h = panel.rows * panel.zoom;  // the image, pixels
    const auto sx = [&](int px) { return static_cast<double>(px) / width; };
    const auto sy = [&](int px) { return static_cast<double>(px) / height; };
    const int left = x0 + 70, bottom = 60;
    // Tics outside, so that they do not hide pixels of the image.
    script += "reset\nset tics out nomirror\n" + palette(panel.palette);
    if (!panel.blank.empty())  // under the image: shows through its NaN pixels
      script += fmt::format(
          "set object 1 rect from graph 0, 0 to graph 1, 1 behind fillcolor rgb {} fillstyle "
          "solid noborder\n",
          quoted(panel.blank));
    const std::array<const char*, 4> where = {
        "graph 0.02, graph 0.5 left", "graph 0.98, graph 0.5 right", "graph 0.5, graph 0.04 center",
        "graph 0.5, graph 0.96 center"};
    for (std::size_t e = 0; e < 4; ++e)
      if (!panel.edge_letters[e].empty())
        script += fmt::format("set label {} {} at {} front boxed noenhanced\n", e + 1,
                              quoted(panel.edge_letters[e]), where[e]);
    script += "set style textbox opaque fillcolor rgb 'white' noborder\n";
    script += fmt::format(
        "set lmargin at screen {:.8f}\nset rmargin at screen {:.8f}\nset bmargin at screen "
        "{:.8f}\nset tmargin at screen {:.8f}\nset colorbox user origin screen {:.8f}, screen "
        "{:.8f} size screen {:.8f}, screen {:.8f}\n",
        sx(left), sx(left + w), sy(bottom), sy(bottom + h), sx(left + w + 15), sy(bottom), sx(20),
        sy(h));
    x0 += w + kImagePanelMarginX;
    // Tics at a round step, far enough apart for their numbers.
    script += fmt::format("set xtics {:.10g}\nset ytics {:.10g}\n",
                          tic_step(panel.x_hi - panel.x_lo, w, 50),
                          tic_step(panel.y_hi - panel.y_lo, h, 25));
    script += fmt::format(
        "set title {} noenhanced\nset xlabel {} noenhanced\nset ylabel {} noenhanced\n"
        "set cblabel {} noenhanced\nset xrange [{:.10g}:{:.10g}]\nset yrange [{:.10g}:{:.10g}]\n"
        "set cbrange [{:.10g}:{:.10g}]\n",
        quoted(panel.title), quoted(panel.xlabel), quoted(panel.ylabel), quoted(panel.value_label),
        panel.x_lo, panel.x_hi, panel.y_lo, panel.y_hi, panel.value_lo, panel.value_hi);
    script += fmt::format(
        "plot $i{0} matrix using ({1:.10g} + ($1 + 0.5) * {2:.10g}):({3:.10g} + ($2 + 0.5) * "
        "{4:.10g}):($3 < {5} ? NaN : $3) with image notitle",
        p, panel.x_lo, dx, panel.y_lo, dy, kBlank / 10);
    if (!panel.dots.empty())
      script += fmt::format(", $p{} using 1:2 with points pt 7 ps 0.5 lc rgb 'white' notitle", p);
    script += "\n";
  }
  script += "unset multiplot\nset output\n";
  run_gnuplot(path, width, height, script);
}

void plot_png(const std::string& path, const std::vector<PlotPanel>& panels, int rows, int columns,
              int width, int height, const std::string& title) {
  std::string script;
  // Data first: one inline block per series.
  for (std::size_t p = 0; p < panels.size(); ++p)
    for (std::size_t s = 0; s < panels[p].series.size(); ++s) {
      const auto& series = panels[p].series[s];
      script += fmt::format("$d{}_{} << EOD\n", p, s);
      for (std::size_t i = 0; i < series.x.size(); ++i)
        script += fmt::format("{:.10g} {:.10g}\n", series.x[i], series.y[i]);
      script += "EOD\n";
    }
  script += fmt::format("set multiplot layout {},{}{}\n", rows, columns,
                        title.empty() ? "" : " title " + quoted(title));
  for (std::size_t p = 0; p < panels.size(); ++p) {
    const auto& panel = panels[p];
    script += "reset\nset grid\nset key top left\n";
    script +=
        fmt::format("set title {} noenhanced\nset xlabel {} noenhanced\nset ylabel {} noenhanced\n",
                    quoted(panel.title), quoted(panel.xlabel), quoted(panel.ylabel));
    if (panel.log_x) script += "set logscale x\nset format x '10^{%L}'\n";
    if (panel.log_y) script += "set logscale y\nset format y '10^{%L}'\n";
    script += panel.extra + "\n";
    script += "plot ";
    for (std::size_t s = 0; s < panel.series.size(); ++s) {
      if (s) script += ", \\\n  ";
      script += fmt::format("$d{}_{} using 1:2 with {} title {}", p, s, panel.series[s].style,
                            quoted(panel.series[s].title));
    }
    if (panel.series.empty()) script += "NaN notitle";
    script += "\n";
  }
  script += "unset multiplot\nset output\n";
  run_gnuplot(path, width, height, script);
}

}  // namespace boxgen::analysis
