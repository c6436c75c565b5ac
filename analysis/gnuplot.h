// Line plots through gnuplot (Debian's gnuplot-nox) with its pngcairo terminal: the program
// writes a script with inline data blocks into a pipe to gnuplot.
#pragma once
#include <string>
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

// Draws the panels (rows x columns, in reading order) into a PNG of the given size at `path`,
// atomically. Throws std::invalid_argument for an unwritable path and std::runtime_error if
// gnuplot is missing or fails.
void plot_png(const std::string& path, const std::vector<PlotPanel>& panels, int rows, int columns,
              int width, int height, const std::string& title = "");

}  // namespace boxgen::analysis
