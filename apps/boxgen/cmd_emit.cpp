#include <fmt/core.h>

#include <filesystem>

#include "apps/boxgen/commands.h"
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
  if (ec || !std::filesystem::is_directory(directory)) boxgen::fail_input("cannot create output directory '" + directory + "'");
  try {
    for (const auto& f : files) (void)runtime::check_output_file(std::filesystem::path(directory) / f.filename);
    for (const auto& f : files)
      runtime::write_output_file(std::filesystem::path(directory) / f.filename,
                                 [&](std::FILE* out) { return std::fwrite(f.text.data(), 1, f.text.size(), out) == f.text.size(); });
  } catch (const runtime::OutputFileError& e) {
    boxgen::fail_input(e.what());
  }
}

}  // namespace

int run_emit(const Common& c, const std::string& name, const std::string& out, const std::string& strategy) {
  const EmissionStrategy chosen = parse_strategy(strategy);  // before the derivation: fail fast
  const BoxSplineSpec spec = parse_spec(c.spec, c.lattice);
  const Analysis a = analyze(spec);  // the exact checks run before anything is emitted
  EmissionRequest request{name,
                          fmt::format("boxgen emit {} {}--name {} --strategy {} --out <dir>",
                                      spec.name == "custom" ? "\"" + spec.text + "\"" : spec.name,
                                      c.lattice.empty() ? "" : "--lattice \"" + c.lattice + "\" ", name, strategy),
                          chosen};
  const auto files = emit(a, request);
  write_emitted(files, out);
  if (c.json) {
    nlohmann::json j = nlohmann::json::array();
    for (const auto& f : files) j.push_back(out + "/" + f.filename);
    print_json({{"files", j}});
  } else {
    for (const auto& f : files) fmt::print("{}/{}\n", out, f.filename);
  }
  return 0;
}

}  // namespace boxgen::cli
