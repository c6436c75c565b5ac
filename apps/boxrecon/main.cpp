// boxrecon: sampling and reconstruction of volumes on the BCC, FCC, Cartesian and custom
// lattices with every filter of generated/registry.hpp (M7, M8, M12 on BCC, fcc6 on FCC,
// tricubic and cart7 on the Cartesian lattice).
//   boxrecon sample --function ml --n N [--h H] [--lattice L | --filter F] [--precision P] -o
//   v.nrrd boxrecon eval --filter F [--prefilter none|q1|q2|interp[:L]] [--boundary B] --volume
//   v.nrrd --points pts.txt|-
//                 [--gradient] [--hessian]
//   boxrecon error --function ml --n N --filter F [--prefilter q2] [--points K] [--seed S]
//                  [--gradient] [--json]
//   boxrecon error --table [--points K] [--seed S] [--json]
//   boxrecon resample --filter F [--prefilter P] --volume v.nrrd -o grid.nrrd [--n N]
//                     [--box LO HI | --min X Y Z --max X Y Z] [--precision float|double]
//   boxrecon render (--function F --n N | --volume v.nrrd) [--filter F] ... -o out.png
//   boxrecon subsample --volume IN --lattice L (--fraction F | --spacing H) [--filter F] ... -o OUT
//   boxrecon compare --reference IN --volume LAT --filter F [--prefilter P] [--mask-above V] ...
//   boxrecon slice (--volume V --filter F[,F2,...] | --reference IN) --axis x|y|z --at W ... -o
//   s.png boxrecon bench [--quick] [--json] [--points K] [--repeats R] [--filter F]
// eval, resample, render and bench take --device cpu|gl: gl runs them on the GL device
// (runtime/gl, OpenGL compute through EGL; docs/gpu.md).
// Every command: --threads N caps the batch paths' threads, like BOXGEN_THREADS. Every filter on
// every lattice goes through the one runtime API (runtime/reconstruction.h,
// apps/boxrecon/lattice_commands.h).
// Errors are one line on stderr with a non-zero exit (1: bad input, 2: bad usage, 3: internal).
#include <fmt/format.h>
#include <CLI/CLI.hpp>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <optional>
#include <random>
#include <stdexcept>
#include <string>
#include <vector>

#include "apps/boxrecon/cmd_bench.h"
#include "apps/boxrecon/cmd_bench_prefilter.h"
#include "apps/boxrecon/cmd_error_table.h"
#include "apps/boxrecon/cmd_render.h"
#include "apps/boxrecon/cmd_volumes.h"
#include "apps/boxrecon/device_choice.h"
#include "apps/boxrecon/lattice_commands.h"
#include "apps/boxrecon/output_volume.h"
#include "apps/boxrecon/prefilter_options.h"
#include "apps/boxrecon/sample_command.h"
#include "apps/common/exit_status.h"
#include "boxgen/version.h"
#include "frontend/filter_choice.h"
#include "frontend/input_checks.h"
#include "runtime/batch_threads.h"
#include "runtime/gl/gl_context.h"
#include "runtime/nrrd_io.h"
#include "runtime/spline_filter.h"
#include "support/output_file.h"

namespace {

using namespace boxgen::runtime;

// A mistake in the user's input (exit code 1), like the runtime's std::invalid_argument.
struct InputError : std::invalid_argument {
  using std::invalid_argument::invalid_argument;
};

// Exit code for an exception: 1 when the input was at fault (a bad argument or file, a point or
// box outside the volume) or the GL device cannot do the work (no context, a shader the driver
// refuses, a volume beyond its limits), 3 for anything else (an internal error).
int exit_code_for(const std::exception& e) {
  const bool bad_input =
      dynamic_cast<const std::invalid_argument*>(&e) ||
      dynamic_cast<const std::out_of_range*>(&e) || dynamic_cast<const std::domain_error*>(&e) ||
      dynamic_cast<const NrrdError*>(&e) || dynamic_cast<const boxgen::runtime::gl::GlError*>(&e) ||
      dynamic_cast<const boxgen::support::OutputFileError*>(&e);
  return bad_input ? 1 : 3;
}

// "m7 (bcc) | ... | cart7 (cartesian)": every filter of the registry with its lattice.
std::string filter_choices() {
  std::string out;
  for (int i = 0; i < SplineFilter::count(); ++i) {
    const SplineFilter f = SplineFilter::at(i);
    out += fmt::format("{}{} ({})", i ? " | " : "", f.name(), f.lattice().name());
  }
  return out;
}

int run(int argc, char** argv) {
  CLI::App app{"boxrecon: reconstruct lattice volumes with the generated box-spline evaluators"};
  app.require_subcommand(1);
  app.set_version_flag("--version", std::string("boxrecon ") + boxgen::kVersion);
  const std::string filters =
      filter_choices() + ", or any SPEC of boxgen (on --lattice), compiled on first use";
  const std::string spec_lattice =
      "the lattice of a SPEC --filter: bcc | fcc | cartesian | \"a,b,c; d,e,f; g,h,i\" (rows of "
      "G); default the volume's with --volume, else the preset's, else cartesian";
  bool quiet = false;
  const auto add_quiet = [&](CLI::App* command) {
    command->add_flag("--quiet", quiet,
                      "no progress on stderr (a SPEC filter's compile, long steps)");
  };
  std::string function = "ml", lattice, sample_filter, output, filter = "m7", volume, points_path,
              precision = "double";
  boxgen::app::PrefilterOptions pre;
  int n = 33, count = 100000;
  std::optional<double> h;
  std::string seed = "1";
  bool gradient = false, json = false, allow_nonfinite = false;
  boxgen::app::OutputGridOptions grid_options;
  int threads = 0;
  app.add_option("--threads", threads,
                 "threads of the batch paths (default: BOXGEN_THREADS, else all cores)")
      ->check(CLI::PositiveNumber);  // the upper bound is the machine's (max_batch_threads)

  auto* sample = app.add_subcommand(
      "sample", "sample a test function on N^3 x K lattice points over [-1,1]^3");
  sample->add_option("--function", function, "ml | cubic | sphere | gaussian");
  sample->add_option("--n", n, "N: N^3 x K samples, K cosets of N^3 with cells of 2/(N-1)")
      ->required();
  sample->add_option("--h", h, "spacing override (finite, > 0)");
  sample->add_option("--lattice", lattice,
                     "bcc (default) | fcc | cartesian | \"a,b,c; d,e,f; g,h,i\" (rows of G)");
  sample->add_option("--filter", sample_filter,
                     "the lattice of this filter (default of --lattice), and a check that "
                     "--lattice agrees: " +
                         filters);
  sample->add_option("--precision", precision, "float | double");
  sample
      ->add_option("-o,--output", output,
                   "output volume: NRRD (.nrrd), or NIfTI-1 (.nii, .nii.gz) on the Cartesian "
                   "lattice")
      ->required();
  std::string output_type;
  boxgen::app::add_type_option(sample, output_type, "-o");
  auto* eval = app.add_subcommand("eval", "evaluate the reconstruction at the points of a file");
  eval->add_option("--filter", filter, filters)->required();
  eval->add_option("--lattice", lattice, spec_lattice);
  boxgen::app::add_prefilter_options(eval, pre);
  eval->add_option("--volume", volume,
                   "volume on the filter's lattice (NRRD, or NIfTI .nii/.nii.gz: Cartesian)")
      ->required();
  eval->add_option("--points", points_path,
                   "file with one 'x y z' (world) per line, '#' comments; - reads stdin")
      ->required();
  eval->add_flag("--gradient", gradient, "also print the three partial derivatives");
  bool hessian = false;
  eval->add_flag("--hessian", hessian, "then the second derivatives h_xx h_xy h_xz h_yy h_yz h_zz");
  auto* eval_precision = eval->add_option(
      "--precision", precision, "float | double (default double; float with --device gl)");
  std::string device = "cpu";
  bool verbose = false;
  boxgen::app::add_device_option(eval, device, &verbose);
  eval->add_flag("--allow-nonfinite", allow_nonfinite,
                 "accept NaN and infinite samples in the volume (refused by default)");
  auto* error = app.add_subcommand(
      "error", "RMS and max error of a reconstruction over random points of [-1,1]^3");
  error->add_option("--function", function, "ml | cubic | sphere | gaussian");
  auto* error_n = error->add_option("--n", n, "N (required unless --table)");
  auto* error_filter =
      error->add_option("--filter", filter, filters + " (required unless --table)");
  bool table = false;
  auto* table_flag = error->add_flag(
      "--table", table,
      "ML errors for N in {17,25,33,41,57} x {m7,m8,m12} x {none,q1,q2,q2opt,qfir:3,interp} "
      "and the tricubic on Cartesian");
  error
      ->add_option("--lattice", lattice,
                   "the lattice it samples on, and of a SPEC --filter: only the filter's own (bcc "
                   "| fcc | cartesian | rows of G), default the filter's")
      ->excludes(table_flag);
  boxgen::app::add_prefilter_options(error, pre);
  error->add_option("--points", count, "number of random points");
  error->add_option("--seed", seed, "random seed, 0..2^64-1");
  error->add_flag("--gradient", gradient, "also the RMS error of the gradient");
  error->add_flag("--json", json, "JSON with keys rms, max, gradient_rms");
  auto* resample = app.add_subcommand("resample",
                                      "resample the reconstruction onto a Cartesian grid (NRRD or "
                                      "NIfTI) or another lattice (NRRD)");
  resample->add_option("--filter", filter, filters)->required();
  resample->add_option("--lattice", lattice,
                       "the output lattice: cartesian | bcc | fcc | \"a,b,c; d,e,f; g,h,i\" (rows "
                       "of G); default the --like image's, else cartesian (a SPEC --filter is on "
                       "the volume's lattice)");
  boxgen::app::add_prefilter_options(resample, pre);
  resample
      ->add_option("--volume", volume,
                   "volume on the filter's lattice (NRRD, or NIfTI .nii/.nii.gz: Cartesian)")
      ->required();
  resample
      ->add_option("-o,--output", output,
                   "output Cartesian grid: NRRD (.nrrd) or NIfTI-1 (.nii, .nii.gz)")
      ->required();
  boxgen::app::add_type_option(resample, output_type, "-o");
  auto* n_option = resample->add_option("--n", grid_options.n,
                                        "N: a cube of N^3 grid points over the box (default 64)");
  auto* size_option =
      resample
          ->add_option("--size", grid_options.size,
                       "NX NY NZ: grid points per axis over the box, instead of --n")
          ->expected(3);
  auto* spacing_option =
      resample
          ->add_option("--spacing", grid_options.spacing,
                       "H or HX HY HZ: grid spacing (world units), points from the box's lower "
                       "corner as far as they fit, instead of --n")
          ->expected(1, 3);
  auto* like_option = resample->add_option(
      "--like", grid_options.like,
      "IMAGE: the grid of this Cartesian image (NRRD or NIfTI: its sizes, spacings and origin), "
      "instead of --n and the box");
  const auto box_options = boxgen::app::add_box_options(
      resample, grid_options.box,
      "default: the largest box in which the filter's stencil lies inside the volume");
  n_option->excludes(size_option)->excludes(spacing_option)->excludes(like_option);
  size_option->excludes(spacing_option)->excludes(like_option);
  spacing_option->excludes(like_option);
  for (auto* box_option : box_options) like_option->excludes(box_option);
  auto* resample_precision = resample->add_option(
      "--precision", precision, "float | double (default double; float with --device gl)");
  boxgen::app::add_device_option(resample, device, &verbose);
  resample->add_flag("--allow-nonfinite", allow_nonfinite,
                     "accept NaN and infinite samples in the volume (refused by default)");
  auto* render = boxgen::recon::add_render_command(app);
  auto* subsample = boxgen::recon::add_subsample_command(app);
  auto* compare = boxgen::recon::add_compare_command(app);
  auto* slice = boxgen::recon::add_slice_command(app);
  boxrecon::BenchOptions bench_options;
  auto* bench = app.add_subcommand(
      "bench", "evaluation speed: the paper's Table 2, fetch floors, tricubic, threads");
  bench->add_flag("--quick", bench_options.quick,
                  "only the ratios, on one cache-resident volume (under a minute)");
  bench->add_flag("--json", bench_options.json, "one JSON object");
  bench
      ->add_option("--points", bench_options.points,
                   "points per measurement (default 10^7, quick 2 10^5)")
      ->check(CLI::Range(1L, 1000000000L));
  std::string bench_filter;
  bench->add_option("--filter", bench_filter,
                    "only this filter: ns per point on its lattice, 1 and all threads: " + filters);
  bench->add_option("--lattice", lattice, spec_lattice);
  bench
      ->add_option("--repeats", bench_options.repeats,
                   "runs per measurement; the fastest counts (default 3)")
      ->check(CLI::Range(1, 100));
  boxgen::app::add_device_option(bench, device, nullptr);
  boxgen::app::PrefilterOptions bench_prefilter{""};
  boxgen::app::add_prefilter_options(bench, bench_prefilter, "no default");
  int bench_n = 256;
  bench->add_option(
      "--n", bench_n,
      "with --prefilter: N^3 samples per coset of the filter's lattice (default 256)");
  for (auto* command : {sample, eval, error, resample, bench, subsample, compare, slice})
    add_quiet(command);
  auto* filters_command = app.add_subcommand(
      "filters", "list the registry's filters and the SPEC filters compiled into the cache");
  if (const auto stop = boxgen::app::parse_command_line(app, argc, argv, "boxrecon")) return *stop;
  try {
    if (threads > 0) set_batch_threads(threads);
    boxgen::frontend::set_quiet(quiet || boxgen::recon::render_quiet());
    if (filters_command->parsed()) return boxgen::frontend::run_filters();
    if (bench->parsed() && !bench_prefilter.prefilter.empty()) {
      if (boxgen::app::parse_device(device) == boxgen::app::Device::Gl)
        throw InputError("bench --prefilter runs on the CPU (the GL device's prefilter does too)");
      return boxgen::app::run_prefilter_bench(
          boxgen::frontend::filter_from(bench_filter.empty() ? "m8" : bench_filter, lattice),
          boxgen::app::parse_prefilter_options(bench_prefilter), bench_n,
          bench->get_option("--repeats")->count() ? bench_options.repeats : 1, bench_options.json);
    }
    if (bench->parsed() && !bench_filter.empty() &&
        boxgen::app::parse_device(device) == boxgen::app::Device::Gl)
      throw InputError("bench --filter runs on the CPU; --device gl measures m7, m8 and m12");
    if (bench->parsed() && !bench_filter.empty())
      return boxgen::app::run_filter_bench(boxgen::frontend::filter_from(bench_filter, lattice),
                                           bench_options.points, bench_options.repeats,
                                           bench_options.json);
    if (bench->parsed() && boxgen::app::parse_device(device) == boxgen::app::Device::Gl)
      return boxrecon::run_gl_bench(bench_options);
    if (bench->parsed()) return boxrecon::run_bench(bench_options);
    if (precision != "float" && precision != "double")
      throw InputError("--precision must be float or double, got '" + precision.substr(0, 40) +
                       "'");
    if (sample->parsed())
      return boxgen::app::run_sample(function, n, h, lattice, sample_filter, precision, output,
                                     output_type);
    const boxgen::app::Device on = boxgen::app::parse_device(device);
    // The GL device computes in float unless --precision double is given.
    if (on == boxgen::app::Device::Gl && eval_precision->count() == 0 &&
        resample_precision->count() == 0)
      precision = "float";
    NrrdReadLimits limits;
    limits.allow_non_finite = allow_nonfinite;
    if (eval->parsed())
      return precision == "float"
                 ? boxgen::app::run_eval<float>(filter, lattice, pre, volume, points_path, gradient,
                                                hessian, limits, on, verbose)
                 : boxgen::app::run_eval<double>(filter, lattice, pre, volume, points_path,
                                                 gradient, hessian, limits, on, verbose);
    if (render->parsed()) return boxgen::recon::run_render();
    if (subsample->parsed()) return boxgen::recon::run_subsample();
    if (compare->parsed()) return boxgen::recon::run_compare();
    if (slice->parsed()) return boxgen::recon::run_slice();
    if (error->parsed() && table)
      return boxgen::recon::run_error_table(count, boxgen::frontend::parse_seed(seed), json);
    if (error->parsed() && (error_n->count() == 0 || error_filter->count() == 0)) {
      std::cerr << "boxrecon: usage error: error needs --n and --filter (or --table) (see boxrecon "
                   "--help)\n";
      return 2;
    }
    if (error->parsed())
      return boxgen::app::run_error(function, n, filter, lattice, pre, count,
                                    boxgen::frontend::parse_seed(seed), gradient, json);
    if (resample->parsed())
      return precision == "float"
                 ? boxgen::app::run_resample<float>(filter, lattice, pre, volume, output,
                                                    output_type, grid_options, limits, on, verbose)
                 : boxgen::app::run_resample<double>(filter, lattice, pre, volume, output,
                                                     output_type, grid_options, limits, on,
                                                     verbose);
  } catch (const std::exception& e) {
    if (boxgen::app::is_output_error(e)) return boxgen::app::report_output_error(e, "boxrecon");
    const int code = exit_code_for(e);
    std::cerr << (code == 1 ? "boxrecon: error: " : "boxrecon: internal error: ") << e.what()
              << '\n';
    return code;
  }
  return 2;
}

}  // namespace

int main(int argc, char** argv) {
  boxgen::support::handle_signals();  // temporaries removed on SIGINT/SIGTERM; EPIPE, not SIGPIPE
  return boxgen::app::finish(run(argc, argv), "boxrecon");
}
