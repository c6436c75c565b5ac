#include "analysis/gnuplot.h"

#include <fmt/format.h>
#include <sys/wait.h>

#include <cstdio>
#include <filesystem>
#include <stdexcept>

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

}  // namespace

void plot_png(const std::string& path, const std::vector<PlotPanel>& panels, int rows, int columns,
              int width, int height, const std::string& title) {
  support::PendingOutput out(path);
  std::string script;
  script +=
      fmt::format("set terminal pngcairo size {},{} enhanced font 'Sans,10'\n", width, height);
  script += fmt::format("set output {}\n", quoted(out.temporary().string()));
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
  std::FILE* pipe = ::popen("gnuplot 2>&1 >/dev/null", "w");
  if (!pipe) throw std::runtime_error("cannot start gnuplot (install gnuplot-nox)");
  const bool written = std::fwrite(script.data(), 1, script.size(), pipe) == script.size();
  const int status = ::pclose(pipe);
  if (!written || status == -1 || !WIFEXITED(status) || WEXITSTATUS(status) != 0)
    throw std::runtime_error(
        fmt::format("gnuplot failed to draw '{}' (is gnuplot-nox installed?)", path));
  std::error_code ec;
  out.commit(std::filesystem::file_size(out.temporary(), ec) == 0 || ec
                 ? "gnuplot wrote nothing (disk full?)"
                 : "");
}

}  // namespace boxgen::analysis
