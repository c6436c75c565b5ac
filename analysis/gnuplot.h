// Line plots through gnuplot (Debian's gnuplot-nox) with its pngcairo terminal: the program
// writes a script with inline data blocks into a pipe to gnuplot.
#pragma once
#include <array>
#include <string>
#include <utility>
#include <vector>

namespace boxgen::analysis {

struct PlotSeries {
  std::string title;
  std::vector<double> x, y;
  std::string style;  // gnuplot "with ..." clause, e.g. "lines lw 2 lc rgb '#d62728' dt 2"
};

struct PlotPanel {
  std::string title, xlabel, ylabel;
  bool log_x = false, log_y = false;
  std::string extra;  // further gnuplot commands for this panel (ranges, shaded objects, keys)
  std::vector<PlotSeries> series;
};

// The colours of an image panel's values from value_lo to value_hi: colour_map() (png_image.h),
// black to white, or blue - white - red (a signed difference).
enum class Palette { viridis, grey, difference };

// An image panel: `values` (columns x rows, row-major, bottom row first) filling [x_lo, x_hi] x
// [y_lo, y_hi], coloured by `palette` over [value_lo, value_hi] with a colour bar labelled
// `value_label`, each value drawn as `zoom` x `zoom` pixels; NaN values show `blank` ("#rrggbb";
// default the white page), `dots` are drawn as white discs, and `edge_letters` (left, right,
// bottom, top; empty: none) are written inside the image at the middle of each edge, in white
// boxes.
struct ImagePanel {
  std::string title, xlabel, ylabel, value_label;
  int columns = 0, rows = 0;
  std::vector<double> values;
  double x_lo = 0, x_hi = 1, y_lo = 0, y_hi = 1, value_lo = 0, value_hi = 1;
  std::vector<std::pair<double, double>> dots;
  Palette palette = Palette::viridis;
  std::string blank;
  std::array<std::string, 4> edge_letters;
  int zoom = 1;
};

// Draws the panels (rows x columns, in reading order) into a PNG of the given size at `path`,
// atomically. Throws std::invalid_argument for an unwritable path and std::runtime_error if
// gnuplot is missing or fails.
void plot_png(const std::string& path, const std::vector<PlotPanel>& panels, int rows, int columns,
              int width, int height, const std::string& title = "");
// The pixels around each image panel: its title, axes and colour bar.
inline constexpr int kImagePanelMarginX = 200, kImagePanelMarginY = 100;
// Draws image panels side by side into a PNG at `path`, atomically, each image's values on zoom x
// zoom pixels: the PNG is the sum of (zoom columns + kImagePanelMarginX) by the largest zoom rows
// + kImagePanelMarginY. Throws as plot_png.
void image_png(const std::string& path, const std::vector<ImagePanel>& panels);

}  // namespace boxgen::analysis
