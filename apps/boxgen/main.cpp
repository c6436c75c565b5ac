// boxgen: the generator's command-line interface. Every command takes --json; errors are one
// line on stderr with a non-zero exit code (1: bad input, 2: bad usage, 3: internal failure).
#include <CLI/CLI.hpp>

#include <cstdio>
#include <iostream>

#include "apps/common/exit_status.h"
#include "boxgen/version.h"
#include "frontend/commands.h"
#include "generator/error.h"
#include "support/output_file.h"

namespace {

void add_common(CLI::App* cmd, boxgen::frontend::Common& c, bool needs_spec = true) {
  if (needs_spec)
    cmd->add_option("SPEC", c.spec,
                    "preset name (see `boxgen presets`) or the directions, i.e. the COLUMNS of Xi, "
                    "one per ';': "
                    "\"1,1,1; 1,-1,-1; ...\"")
        ->required();
  cmd->add_option(
         "--lattice", c.lattice,
         "bcc | fcc | cartesian | the ROWS of G, one per ';', whose columns are the lattice basis: "
         "\"2,0; 0,1\" (default: the preset's, else cartesian)")
      ->check(boxgen::app::kNonEmpty);
  cmd->add_flag("--json", c.json, "machine-readable output");
}

// The limits of every command that derives: each refuses up front what the cost estimate
// (generator/cost_estimate.h) puts beyond them.
void add_limits(CLI::App* cmd, boxgen::frontend::Common& c) {
  cmd->add_option("--max-seconds", c.max_seconds,
                  "refuse up front if the predicted time exceeds this (default 600)")
      ->check(boxgen::app::kFinitePositive);
  cmd->add_option("--max-memory", c.max_memory_mb,
                  "refuse up front if the predicted memory exceeds this many MB (default: the "
                  "machine's available memory)")
      ->check(boxgen::app::kFinitePositive);
}

}  // namespace

int run(int argc, char** argv);

int main(int argc, char** argv) {
  boxgen::support::handle_signals();  // temporaries removed on SIGINT/SIGTERM; EPIPE, not SIGPIPE
  return boxgen::app::finish(run(argc, argv), "boxgen");
}

int run(int argc, char** argv) {
  CLI::App app{
      "boxgen: exact analysis of box splines on lattices and code generation for their evaluators"};
  app.require_subcommand(1);
  app.set_version_flag("--version", boxgen::kVersionBanner);
  boxgen::frontend::Common c;
  bool verify = true, no_verify = false;
  std::vector<std::string> points;
  std::string derivative, region = "reference", shells, method = "refinement";

  auto* presets = app.add_subcommand("presets", "list the preset direction matrices");
  presets->add_flag("--json", c.json, "machine-readable output");
  auto* analyze =
      app.add_subcommand("analyze", "derive the properties and structure of a box spline");
  add_common(analyze, c);
  analyze->add_flag("--no-verify", no_verify,
                    "skip the exact checks (second derivation, integral, symmetry, ...)");
  boxgen::frontend::AnalyzeOptions analyze_options;
  analyze->add_option(
      "--checks", analyze_options.checks,
      "default (integral and continuity on one cell per symmetry orbit) or full (every cell)");
  analyze->add_flag("--estimate", analyze_options.estimate_only,
                    "predict time and memory without deriving");
  add_limits(analyze, c);
  analyze->add_flag("--progress", analyze_options.progress,
                    "progress on stderr even when it is not a terminal");
  auto* eval = app.add_subcommand("eval", "exact value of the filter M = |det G| M^c at points");
  add_common(eval, c);
  add_limits(eval, c);
  eval->add_option("--at", points, "a point \"x y z\" (fractions or decimals); repeatable")
      ->required();
  eval->add_option("--derivative", derivative, "orders \"a b c\" of the partial derivative");
  auto* bbform =
      app.add_subcommand("bbform", "stencil and exact BB-coefficients on the reference region");
  add_common(bbform, c);
  add_limits(bbform, c);
  bbform->add_option("--region", region,
                     "reference (every orbit's reference region) or an orbit index");
  auto* prefilter =
      app.add_subcommand("prefilter", "exact quasi-interpolation prefilter on lattice shells");
  add_common(prefilter, c);
  std::string prefilter_name;
  prefilter->add_option("--shells", shells, "shells of the lattice, e.g. 0,1 or 0,1,2");
  prefilter->add_option("--prefilter", prefilter_name,
                        "q1, q2, q1opt, q2opt (the free parameters optimised) or qfir:K (the FIR "
                        "interpolation prefilter on shells 0..K); instead of --shells");
  auto* autocorr =
      app.add_subcommand("autocorr", "lattice samples of the doubled box spline (autocorrelation)");
  add_common(autocorr, c);
  autocorr->add_option("--method", method, "refinement (default) or continuity");
  std::string emit_name, emit_out, emit_strategy = "auto", emit_target = "cpp",
                                   emit_precision = "float";
  bool emit_report = false;
  std::vector<std::string> emit_registry;
  auto* emit = app.add_subcommand(
      "emit", "emit the evaluator (C++ and prefilter headers, GLSL or CUDA) of a box spline");
  emit->add_option("SPEC", c.spec,
                   "preset name or the directions, as for analyze (leave out to write only "
                   "--registry)");
  add_common(emit, c, false);
  add_limits(emit, c);
  emit->add_option("--name", emit_name,
                   "C++ identifier: namespace boxgen::generated::<name> (with a SPEC)");
  emit->add_option("--out", emit_out, "output directory")->required();
  emit->add_option(
      "--strategy", emit_strategy,
      "how polynomials are written: auto (default: the cheapest), horner, shifted, bernstein, "
      "separable or monomial");
  emit->add_option("--target", emit_target,
                   "cpp (default: NAME.hpp and NAME_prefilters.hpp), glsl (NAME.glsl, GLSL 4.30) "
                   "or cuda (NAME.cuh)");
  emit->add_option("--precision", emit_precision, "glsl: float (default) or double");
  emit->add_flag("--report", emit_report, "also print the strategy and operation counts per orbit");
  std::string emit_shells;
  emit->add_option("--shells", emit_shells,
                   "shells of the prefilter q1, e.g. 0,1 (q2: these and the next shell); default: "
                   "the smallest on which a prefilter of full order exists");
  emit->add_option("--registry", emit_registry,
                   "also (or, without a SPEC, only) write registry.hpp listing these filters "
                   "(comma-separated; each emitted into --out already or now)")
      ->delimiter(',');
  std::string pieces_of = "spline", pieces_region = "reference", pieces_format = "text";
  auto* pieces = app.add_subcommand(
      "pieces", "explicit piecewise polynomials of the spline or the filter, with their regions");
  add_common(pieces, c);
  add_limits(pieces, c);
  pieces->add_option("--of", pieces_of,
                     "spline (default): s(x) = sum_j V(j) M(x - j); filter: M itself");
  pieces->add_option("--region", pieces_region,
                     "reference (one piece per orbit, default), all, or an orbit index");
  pieces->add_option("--format", pieces_format,
                     "text (default), latex, c or json (--json is --format json)");
  auto* table1 =
      app.add_subcommand("table1", "derive M12, M8, M7 and print the paper's Table 1 beside ours");
  table1->add_flag("--json", c.json, "machine-readable output");

  // Frequency-domain analysis of one or more filters (analysis/).
  boxgen::frontend::FrequencyOptions ao;
  auto add_specs = [&](CLI::App* cmd) {
    cmd->add_option("SPEC", ao.specs,
                    "one or more presets or direction lists, each optionally SPEC@LATTICE "
                    "(e.g. m7 fcc6@fcc \"1,1,1; ...@bcc\")")
        ->required();
    cmd->add_option("--lattice", ao.lattice,
                    "lattice of every SPEC without @: bcc | fcc | cartesian | \"<rows of G>\" "
                    "(default: each preset's)")
        ->check(boxgen::app::kNonEmpty);
    cmd->add_option("--label", ao.labels,
                    "name of a SPEC in tables, JSON keys and legends; repeat once per SPEC, in "
                    "order (default: the SPEC as given)");
    cmd->add_flag("--json", ao.json, "machine-readable output");
  };
  auto add_density = [&](CLI::App* cmd) {
    cmd->add_flag("--equal-density", ao.equal_density,
                  "scale each SPEC's frequencies to its lattice at one sample per unit volume "
                  "(compares lattices at equal sample density)");
  };
  auto add_range = [&](CLI::App* cmd) {
    cmd->add_option("--from", ao.from, "first abscissa");
    cmd->add_option("--to", ao.to, "last abscissa");
    cmd->add_option("--steps", ao.steps, "number of abscissae from --from to --to");
  };
  auto* metrics = app.add_subcommand(
      "metrics", "Marschner-Lobb smoothing and postaliasing (the paper's Table 3)");
  add_specs(metrics);
  add_density(metrics);
  auto* kernel = app.add_subcommand(
      "kernel", "Blu-Unser frequency error kernel E(w * direction) (the paper's Fig. 13)");
  add_specs(kernel);
  add_density(kernel);
  kernel->add_option("--prefilter", ao.prefilter,
                     "none | q1 | q2 | q1opt | q2opt | qfir:K | interp | min (E_min), default q2");
  kernel->add_option("--direction", ao.direction,
                     "direction d of w * d (default 1,1,1, or 1,1 in 2-D)");
  kernel->add_option("--w", ao.w, "abscissae w (comma or space separated)")->delimiter(',');
  add_range(kernel);
  kernel->add_option("--plot", ao.plot,
                     "draw every prefilter and E_min of each SPEC, log axes (PNG)");
  auto* spectrum = app.add_subcommand(
      "spectrum", "|psi_hat| on a plane or along a line (the paper's Figs. 11-12)");
  add_specs(spectrum);
  add_density(spectrum);
  spectrum->add_option("--plane", ao.plane, "normal a,b,c of a plane through 0 (image)");
  spectrum->add_option("--line", ao.line, "direction a,b,c of a line through 0 (plot)");
  spectrum->add_option("--w", ao.w, "line: abscissae w (comma or space separated)")->delimiter(',');
  add_range(spectrum);
  spectrum->add_option("--size", ao.size,
                       "plane image: pixels per filter panel side (default 400)");
  spectrum->add_option("-o,--output", ao.plot, "PNG to write");

  // Name an unknown command instead of CLI11's "A subcommand is required".
  if (argc > 1 && argv[1][0] != '-') {
    const std::string first = argv[1];
    const auto known = app.get_subcommands([&](CLI::App* s) { return s->check_name(first); });
    if (known.empty()) {
      std::cerr << "boxgen: usage error: unknown command '" << first << "' (see boxgen --help)\n";
      return 2;
    }
  }
  if (const auto stop = boxgen::app::parse_command_line(app, argc, argv, "boxgen")) return *stop;
  verify = !no_verify;
  try {
    if (presets->parsed()) return boxgen::frontend::run_presets(c.json);
    if (analyze->parsed()) {
      analyze_options.verify = verify;
      return boxgen::frontend::run_analyze(c, analyze_options);
    }
    if (eval->parsed()) return boxgen::frontend::run_eval(c, points, derivative);
    if (bbform->parsed()) return boxgen::frontend::run_bbform(c, region);
    if (prefilter->parsed()) return boxgen::frontend::run_prefilter(c, shells, prefilter_name);
    if (autocorr->parsed()) return boxgen::frontend::run_autocorr(c, method);
    if (table1->parsed()) return boxgen::frontend::run_table1(c.json);
    if (metrics->parsed()) return boxgen::frontend::run_metrics(ao);
    if (kernel->parsed()) return boxgen::frontend::run_kernel(ao);
    if (spectrum->parsed()) return boxgen::frontend::run_spectrum(ao);
    if (emit->parsed())
      return boxgen::frontend::run_emit(c, emit_name, emit_out, emit_strategy, emit_report,
                                        emit_registry, {emit_target, emit_precision, emit_shells});
    if (pieces->parsed())
      return boxgen::frontend::run_pieces(c, pieces_of, pieces_region, pieces_format);
  } catch (const boxgen::frontend::UsageError& e) {
    std::cerr << "boxgen: usage error: " << e.what() << " (see boxgen --help)\n";
    return 2;
  } catch (const boxgen::generator::InputError& e) {
    std::cerr << "boxgen: error: " << e.what() << '\n';
    return 1;
  } catch (const boxgen::support::OutputFileError& e) {  // a file that could not be written
    std::cerr << "boxgen: error: " << e.what() << '\n';
    return 1;
  } catch (
      const std::invalid_argument& e) {  // the analysis module's bad input (an unwritable -o, ...)
    std::cerr << "boxgen: error: " << e.what() << '\n';
    return 1;
  } catch (const std::exception& e) {
    if (boxgen::app::is_output_error(e)) return boxgen::app::report_output_error(e, "boxgen");
    std::cerr << "boxgen: internal error: " << e.what() << '\n';
    return 3;
  }
  return 2;
}
