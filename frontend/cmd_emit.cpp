#include <fmt/core.h>
#include <fmt/format.h>

#include <algorithm>
#include <cctype>
#include <filesystem>
#include <map>
#include <optional>
#include <set>
#include <string_view>
#include <utility>

#include "frontend/commands.h"
#include "frontend/optimised_prefilter.h"
#include "frontend/progress.h"
#include "generator/codegen/emitter.h"
#include "generator/codegen/evaluator_name.h"
#include "generator/codegen/targets/emission_report.h"
#include "generator/error.h"
#include "generator/prefilter.h"
#include "support/output_file.h"

namespace boxgen::frontend {

namespace {

// The files of one emission as a set (support/output_file.h): all written or none, links written
// through, special files refused, never a half-written or mixed pair.
void write_emitted(const std::vector<EmittedFile>& files, const std::string& directory) {
  std::vector<support::NamedText> set;
  for (const auto& f : files) set.push_back({f.filename, f.text});
  try {
    support::write_file_set(directory, set);
  } catch (const support::OutputFileError& e) {
    boxgen::generator::fail_input(e.what());
  }
}

nlohmann::json counts_json(const OperationCount& c) {
  return {{"adds", c.adds},   {"muls", c.muls},     {"negs", c.negs},
          {"loads", c.loads}, {"total", c.total()}, {"temporaries", c.temporaries}};
}

void print_report(const EmissionReport& r) {
  fmt::print(
      "strategy {}: operations per point (adds + muls), value / value+gradient / +hessian: {} / {} "
      "/ {}\n",
      r.strategy, r.value.total(), r.gradient.total(), r.hessian.total());
  for (std::size_t o = 0; o < r.orbits.size(); ++o) {
    const OrbitReport& orbit = r.orbits[o];
    fmt::print("  orbit {}: {}{}, {} / {} / {}\n", o, orbit.strategy,
               orbit.form.empty() ? "" : " " + orbit.form, orbit.value.total(),
               orbit.gradient.total(), orbit.hessian.total());
    fmt::print(
        "    adds {} / {} / {}, muls {} / {} / {}, loads {} / {} / {}, temporaries {} / {} / {}\n",
        orbit.value.adds, orbit.gradient.adds, orbit.hessian.adds, orbit.value.muls,
        orbit.gradient.muls, orbit.hessian.muls, orbit.value.loads, orbit.gradient.loads,
        orbit.hessian.loads, orbit.value.temporaries, orbit.gradient.temporaries,
        orbit.hessian.temporaries);
    if (!orbit.considered.empty())
      fmt::print("    chosen by value + gradient from {}\n", considered_text(orbit.considered));
  }
}

// --name becomes a namespace, file names and function prefixes: generator/codegen/evaluator_name.h.
void check_emit_name(const std::string& name) { check_evaluator_name(name); }

// The target and precision, checked before the derivation.
std::pair<EmissionTarget, bool> parse_language(const EmitLanguage& l, bool registry) {
  const std::map<std::string, EmissionTarget> targets = {
      {"cpp", EmissionTarget::Cpp}, {"glsl", EmissionTarget::Glsl}, {"cuda", EmissionTarget::Cuda}};
  const auto it = targets.find(l.target);
  if (it == targets.end())
    fail_input(fmt::format("--target must be cpp, glsl or cuda, got '{}'", l.target.substr(0, 40)));
  if (l.precision != "float" && l.precision != "double")
    fail_input(
        fmt::format("--precision must be float or double, got '{}'", l.precision.substr(0, 40)));
  if (l.precision == "double" && it->second != EmissionTarget::Glsl)
    fail_input("--precision double is for --target glsl (C++ and CUDA evaluators are templates)");
  if (registry && it->second != EmissionTarget::Cpp)
    fail_input("--registry lists C++ headers: use it with --target cpp");
  return {it->second, l.precision == "double"};
}

// --registry: the names must be identifiers, each once, and each an evaluator that exists in the
// output folder or is emitted now; checked before any work.
void check_registry(const std::vector<std::string>& registry, const std::string& emitted,
                    const std::string& out) {
  std::set<std::string> seen;
  for (const auto& n : registry) {
    if (!seen.insert(n).second)
      fail_input(fmt::format("--registry lists '{}' twice", n.substr(0, 40)));
    if (n == emitted) continue;
    check_emit_name(n);
    for (const std::string& file : {n + ".hpp", n + "_prefilters.hpp"})
      if (!std::filesystem::is_regular_file(std::filesystem::path(out) / file))
        fail_input(fmt::format(
            "--registry: '{}' has no {} in '{}': emit it there first (boxgen emit SPEC --name {} "
            "--out {})",
            n, file, out, n, out));
  }
}

}  // namespace

std::vector<EmittedFile> emit_evaluator(const Common& c, const std::string& name,
                                        const std::string& strategy, const EmitLanguage& language,
                                        EmissionReport* report) {
  check_emit_name(name);
  const auto [target, double_precision] = parse_language(language, false);
  const EmissionStrategy chosen = parse_strategy(strategy);  // before the derivation
  const std::vector<int> shells =
      language.shells.empty() ? std::vector<int>{} : parse_shells(language.shells);
  const BoxSplineSpec spec = parse_spec(c.spec, c.lattice);
  ProgressPrinter progress(false);  // on a terminal, for derivations beyond two seconds
  DerivationOptions options;
  options.progress = progress.callback();
  options.max_seconds = c.max_seconds;
  options.max_bytes = c.max_memory_mb * 1e6;
  const Derivation a = derive(spec, options);  // the exact checks run before anything is emitted
  progress.finish();
  // The command that rewrites the file byte for byte, run in the file's folder.
  const EmissionRequest request{
      name,
      fmt::format(
          "boxgen emit {} {}--name {} --strategy {}{} --out .",
          spec.name == "custom" ? "\"" + one_line(spec.text) + "\"" : spec.name,
          c.lattice.empty() ? "" : "--lattice \"" + one_line(c.lattice) + "\" ", name, strategy,
          target == EmissionTarget::Cpp
              ? (shells.empty() ? "" : fmt::format(" --shells {}", fmt::join(shells, ",")))
              : " --target " + language.target + (double_precision ? " --precision double" : "")),
      chosen,
      target,
      double_precision,
      shells,
      target == EmissionTarget::Cpp ? optimised_table(spec, "q1opt", shells) : std::nullopt,
      target == EmissionTarget::Cpp ? optimised_table(spec, "q2opt", shells) : std::nullopt};
  Emission emission = emit(a, request);
  if (report) *report = std::move(emission.report);
  return std::move(emission.files);
}

int run_emit(const Common& c, const std::string& name, const std::string& out,
             const std::string& strategy, bool report, const std::vector<std::string>& registry,
             const EmitLanguage& language) {
  if (c.spec.empty() != name.empty() || (c.spec.empty() && registry.empty()))
    fail_usage("emit needs a SPEC and --name (an evaluator), or --registry alone, or both");
  if (!name.empty()) check_emit_name(name);
  (void)parse_language(language, !registry.empty());  // checked before any work
  if (!registry.empty()) check_registry(registry, name, out);
  std::vector<EmittedFile> files;
  EmissionReport r;
  if (!name.empty()) {
    files = emit_evaluator(c, name, strategy, language, &r);
  } else if (report) {
    fail_usage("--report needs an evaluator to report on (a SPEC and --name)");
  }
  if (!registry.empty()) {
    std::string names;
    for (const auto& n : registry) names += (names.empty() ? "" : ",") + n;
    files.push_back(
        emit_registry(registry, fmt::format("boxgen emit --registry {} --out .", names)));
  }
  write_emitted(files, out);
  if (c.json) {
    nlohmann::json j = nlohmann::json::array();
    for (const auto& f : files) j.push_back(out + "/" + f.filename);
    nlohmann::json result{{"files", j}};
    if (report) {
      nlohmann::json orbits = nlohmann::json::array();
      for (const auto& o : r.orbits) {
        nlohmann::json considered = nlohmann::json::array();
        for (const auto& s : o.considered)
          considered.push_back({{"strategy", strategy_name(s.strategy)},
                                {"value", counts_json(s.value)},
                                {"gradient", counts_json(s.gradient)},
                                {"hessian", counts_json(s.hessian)}});
        orbits.push_back({{"strategy", o.strategy},
                          {"form", o.form},
                          {"value", counts_json(o.value)},
                          {"gradient", counts_json(o.gradient)},
                          {"hessian", counts_json(o.hessian)},
                          {"considered", considered}});
      }
      result["report"] = {{"strategy", r.strategy},
                          {"value", counts_json(r.value)},
                          {"gradient", counts_json(r.gradient)},
                          {"hessian", counts_json(r.hessian)},
                          {"orbits", orbits}};
    }
    print_json(result);
  } else {
    for (const auto& f : files) fmt::print("{}/{}\n", out, f.filename);
    if (report) print_report(r);
  }
  return 0;
}

}  // namespace boxgen::frontend
