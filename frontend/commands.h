// The boxgen subcommands, shared by the CLI (apps/boxgen/main.cpp parses their options) and the
// Python module (python/ binds the builders: *_json, bbform_output, emit_evaluator, pieces_text).
// Each run_* writes its whole result to stdout only after it has been derived, so a failure never
// leaves half an answer behind.
#pragma once
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "generator/codegen/emitter.h"
#include "generator/derivation.h"
#include "generator/piecewise_form.h"
#include "generator/rational.h"

namespace boxgen::frontend {

// The front end speaks the generator's types: they are used unqualified here.
using namespace ::boxgen::generator;  // NOLINT(google-build-using-namespace)

// A combination of options that cannot work together: main prints it as a usage error (exit 2).
struct UsageError : std::runtime_error {
  using std::runtime_error::runtime_error;
};
[[noreturn]] inline void fail_usage(const std::string& message) { throw UsageError(message); }

struct Common {
  std::string spec;
  std::string lattice;
  bool json = false;
  double max_seconds = 0;    // commands that derive: refuse beyond this predicted time (0: 600 s)
  double max_memory_mb = 0;  // and beyond this predicted memory (0: the available memory)
};
// The limits above as the derivation takes them.
inline DerivationBudget derivation_budget(const Common& c) {
  return {c.max_seconds, c.max_memory_mb * 1e6};
}

int run_presets(bool json);
struct AnalyzeOptions {
  bool verify = true;
  std::string checks = "default";  // default | full
  bool estimate_only = false;      // --estimate: predict time and memory, derive nothing
  bool progress = false;           // progress on stderr even when it is not a terminal
};
int run_analyze(const Common& c, const AnalyzeOptions& options);
// The derivation `analyze` runs (its JSON is to_json() of it), with `progress` (may be empty).
Derivation analyze_derivation(const Common& c, const AnalyzeOptions& options,
                              const ProgressFn& progress);
// What `analyze --json` prints of it (also boxgen.analyze() in Python): to_json(a) with the
// interpolation symbol (frontend/analysis_symbol.h).
nlohmann::json analyze_json(const Derivation& a);
int run_eval(const Common& c, const std::vector<std::string>& points,
             const std::string& derivative);
// What `eval --json` prints (also boxgen.eval() in Python): per point ("x y z", fractions or
// decimals) its coordinates, the derivative's orders and the exact value ("p/q") with its double.
nlohmann::json eval_json(const Common& c, const std::vector<std::string>& points,
                         const std::string& derivative);
int run_bbform(const Common& c, const std::string& region);
// What `bbform` prints: its JSON (--json; also boxgen.bbform() in Python) and its text.
struct BBFormOutput {
  nlohmann::json json;
  std::string text;
};
BBFormOutput bbform_output(const Common& c, const std::string& region);
// The prefilter on `shells` ("0,1,2"), or the one `name` names (q1, q2, qfir:K); exactly one of
// them is not empty.
int run_prefilter(const Common& c, const std::string& shells, const std::string& name);
// What `prefilter --json` prints (also boxgen.prefilter() in Python).
nlohmann::json prefilter_json(const Common& c, const std::string& shells, const std::string& name);
int run_autocorr(const Common& c, const std::string& method);
int run_table1(bool json);
// --target cpp|glsl|cuda and --precision float|double (glsl only).
struct EmitLanguage {
  std::string target = "cpp", precision = "float";
  std::string shells;  // --shells of q1 (q2: and the next); empty: the smallest that exist
};
// The files `emit SPEC --name NAME` writes (also boxgen.emit() in Python), byte for byte, with
// the report of --report in `report` when it is not null; the name, target, precision, strategy
// and shells are checked before the derivation.
std::vector<EmittedFile> emit_evaluator(const Common& c, const std::string& name,
                                        const std::string& strategy, const EmitLanguage& language,
                                        EmissionReport* report = nullptr);
int run_emit(const Common& c, const std::string& name, const std::string& out,
             const std::string& strategy, bool report, const std::vector<std::string>& registry,
             const EmitLanguage& language = {});

// The frequency-domain analysis (analysis/, docs/design.md §10): cmd_metrics.cpp, cmd_kernel.cpp,
// cmd_spectrum.cpp.
struct FrequencyOptions {
  std::vector<std::string> specs;   // each SPEC or SPEC@LATTICE (frontend/analysis_specs.h)
  std::string lattice;              // the lattice of a SPEC without '@'
  std::vector<std::string> labels;  // --label: one per SPEC, or none
  bool json = false;
  std::string prefilter = "q2";    // kernel: none | q1 | q2 | min
  std::string direction;           // kernel: w * direction (default: all ones)
  std::vector<double> w;           // explicit abscissae
  std::optional<double> from, to;  // or a range
  int steps = 0;
  std::string plot;         // kernel --plot, spectrum -o
  std::string plane, line;  // spectrum
  int size = 400;           // spectrum plane: image side in pixels (16..4096)
  // metrics, kernel, spectrum: each SPEC's frequencies scaled to its lattice at unit sample
  // density (density_scale, analysis_inputs.h).
  bool equal_density = false;
};
int run_metrics(const FrequencyOptions& o);
int run_kernel(const FrequencyOptions& o);
int run_spectrum(const FrequencyOptions& o);
int run_pieces(const Common& c, const std::string& of, const std::string& region,
               const std::string& format);
// What `metrics --json`, `kernel --json` and `spectrum --line --json` print (also the Python
// module's metrics(), kernel() and spectrum(); kernel_json ignores o.plot, spectrum_json needs
// o.line), and the text `pieces` prints (JSON when c.json).
nlohmann::json metrics_json(const FrequencyOptions& o);
nlohmann::json kernel_json(const FrequencyOptions& o);
nlohmann::json spectrum_json(const FrequencyOptions& o);
std::string pieces_text(const Common& c, const std::string& of, const std::string& region,
                        const std::string& format);

// Shared output helpers.
nlohmann::json rational_list(const RatVec& v);
std::string format_point(const IntVec& p);
void print_json(const nlohmann::json& j);

}  // namespace boxgen::frontend
