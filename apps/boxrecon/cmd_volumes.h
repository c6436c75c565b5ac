// boxrecon's commands for real volumes (a scan, an MRI template): subsample one onto BCC, FCC or
// a coarser Cartesian grid, compare a reconstruction with the original, and look at slices (the
// paper's Fig. 10 on real data; docs/fig10.md). Each add_* declares the command's options, each
// run_* runs it once CLI11 has parsed them; bad input is std::invalid_argument or NrrdError, one
// line, and nothing is written.
#pragma once
#include <CLI/CLI.hpp>

namespace boxgen::recon {

CLI::App* add_subsample_command(CLI::App& app);
int run_subsample();

CLI::App* add_compare_command(CLI::App& app);
int run_compare();

CLI::App* add_slice_command(CLI::App& app);
int run_slice();

}  // namespace boxgen::recon
