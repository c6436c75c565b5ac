// `boxrecon render`: a ray-cast isosurface of a reconstructed spline as a PNG (cmd_render.cpp).
#pragma once
#include <CLI/CLI.hpp>

namespace boxgen::recon {

// Registers the subcommand and its options on `app`; run_render() runs it after parsing.
CLI::App* add_render_command(CLI::App& app);
int run_render();
// Whether render was given --quiet (which also silences a SPEC filter's compile).
bool render_quiet();

}  // namespace boxgen::recon
