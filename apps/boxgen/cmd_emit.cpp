#include <fmt/core.h>

#include <algorithm>
#include <cctype>
#include <filesystem>
#include <map>
#include <set>

#include "apps/boxgen/commands.h"
#include "apps/boxgen/progress.h"
#include "generator/emitter.h"
#include "generator/error.h"
#include "runtime/output_file.h"

namespace boxgen::cli {

namespace {

// Each file through runtime/output_file.h, as boxrecon writes its volumes: links written
// through, special files refused, a temporary file renamed into place.
void write_emitted(const std::vector<EmittedFile>& files, const std::string& directory) {
  std::error_code ec;
  std::filesystem::create_directories(directory, ec);
  if (ec || !std::filesystem::is_directory(directory))
    boxgen::fail_input("cannot create output directory '" + directory + "'");
  try {
    for (const auto& f : files)
      (void)runtime::check_output_file(std::filesystem::path(directory) / f.filename);
    for (const auto& f : files)
      runtime::write_output_file(
          std::filesystem::path(directory) / f.filename, [&](std::FILE* out) {
            return std::fwrite(f.text.data(), 1, f.text.size(), out) == f.text.size();
          });
  } catch (const runtime::OutputFileError& e) {
    boxgen::fail_input(e.what());
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

// --name becomes a namespace: a C++ identifier that is not a keyword (checked before deriving).
void check_emit_name(const std::string& name) {
  static const std::set<std::string> keywords = {"alignas",       "alignof",     "and",
                                                 "and_eq",        "asm",         "auto",
                                                 "bitand",        "bitor",       "bool",
                                                 "break",         "case",        "catch",
                                                 "char",          "char8_t",     "char16_t",
                                                 "char32_t",      "class",       "compl",
                                                 "concept",       "const",       "consteval",
                                                 "constexpr",     "constinit",   "const_cast",
                                                 "continue",      "co_await",    "co_return",
                                                 "co_yield",      "decltype",    "default",
                                                 "delete",        "do",          "double",
                                                 "dynamic_cast",  "else",        "enum",
                                                 "explicit",      "export",      "extern",
                                                 "false",         "float",       "for",
                                                 "friend",        "goto",        "if",
                                                 "inline",        "int",         "long",
                                                 "mutable",       "namespace",   "new",
                                                 "noexcept",      "not",         "not_eq",
                                                 "nullptr",       "operator",    "or",
                                                 "or_eq",         "private",     "protected",
                                                 "public",        "register",    "reinterpret_cast",
                                                 "requires",      "return",      "short",
                                                 "signed",        "sizeof",      "static",
                                                 "static_assert", "static_cast", "struct",
                                                 "switch",        "template",    "this",
                                                 "thread_local",  "throw",       "true",
                                                 "try",           "typedef",     "typeid",
                                                 "typename",      "union",       "unsigned",
                                                 "using",         "virtual",     "void",
                                                 "volatile",      "wchar_t",     "while",
                                                 "xor",           "xor_eq"};
  const auto letter = [](char ch) {
    return std::isalpha(static_cast<unsigned char>(ch)) || ch == '_';
  };
  const bool identifier =
      !name.empty() && letter(name[0]) && std::all_of(name.begin(), name.end(), [&](char ch) {
        return letter(ch) || std::isdigit(static_cast<unsigned char>(ch));
      });
  if (!identifier)
    fail_input(
        fmt::format("--name '{}' is not a C++ identifier: use letters, digits and '_', not "
                    "starting with a digit",
                    name));
  if (keywords.count(name))
    fail_input(fmt::format("--name '{}' is a C++ keyword: choose another name", name));
  if (name.find("__") != std::string::npos ||
      (name.size() > 1 && name[0] == '_' && std::isupper(name[1])))
    fail_input(fmt::format(
        "--name '{}' is reserved for the implementation in C++ ('__' or '_' and a capital)", name));
}

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

}  // namespace

int run_emit(const Common& c, const std::string& name, const std::string& out,
             const std::string& strategy, bool report, const std::vector<std::string>& registry,
             const EmitLanguage& language) {
  check_emit_name(name);
  const EmissionStrategy chosen = parse_strategy(strategy);  // before the derivation: fail fast
  const auto [target, double_precision] = parse_language(language, !registry.empty());
  const BoxSplineSpec spec = parse_spec(c.spec, c.lattice);
  ProgressPrinter progress(false);  // on a terminal, for derivations beyond two seconds
  AnalysisOptions options;
  options.progress = progress.callback();
  const Analysis a = analyze(spec, options);  // the exact checks run before anything is emitted
  progress.finish();
  EmissionRequest request{
      name,
      fmt::format(
          "boxgen emit {} {}--name {} --strategy {}{} --out <dir>",
          spec.name == "custom" ? "\"" + spec.text + "\"" : spec.name,
          c.lattice.empty() ? "" : "--lattice \"" + c.lattice + "\" ", name, strategy,
          target == EmissionTarget::Cpp
              ? ""
              : " --target " + language.target + (double_precision ? " --precision double" : "")),
      chosen, target, double_precision};
  EmissionReport r;
  auto files = emit(a, request, &r);
  if (!registry.empty()) {
    std::string names;
    for (const auto& n : registry) names += (names.empty() ? "" : ",") + n;
    files.push_back(
        emit_registry(registry, fmt::format("boxgen emit ... --registry {} --out <dir>", names)));
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

}  // namespace boxgen::cli
