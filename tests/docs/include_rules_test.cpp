// The include rules between the project's folders (the code generator's: docs/design.md §15):
// which folder's code may include which. An #include "FOLDER/..." line of the project's own files
// is checked against the rules below; system and third-party headers (<...>) are not.
//   - support/ includes nothing of the project's other folders;
//   - runtime/ never includes the generator (it links against what the generator wrote);
//   - generator/ (the derivation) never includes generator/codegen/, which depends on it;
//   - in generator/codegen/: ir/ includes no strategy, target or the emitter; strategies/ no
//     target nor the emitter; targets/ not the emitter;
//   - python/ and frontend/ (the front end the CLI and Python share) never include apps/, and
//     frontend/ never includes python/;
//   - the generator's front end (frontend/ but for the files of boxgen_volume_frontend, which
//     choose filters and grids for volumes) includes neither the runtime nor the loader, so the
//     program `boxgen` does not link them.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <set>
#include <string>
#include <vector>

namespace {

namespace fs = std::filesystem;

struct Include {
  std::string file;    // relative to the source tree
  std::string target;  // what the line includes, as written between the quotes
};

// Every `#include "..."` of the C++ files below `folder` (relative to the source tree).
std::vector<Include> includes_under(const std::string& folder) {
  const fs::path root = BOXGEN_SOURCE_DIR;
  std::vector<Include> out;
  for (const auto& entry : fs::recursive_directory_iterator(root / folder)) {
    const std::string ext = entry.path().extension().string();
    if (ext != ".cpp" && ext != ".h" && ext != ".hpp" && ext != ".cu") continue;
    std::ifstream in(entry.path());
    std::string line;
    while (std::getline(in, line)) {
      const std::string head = "#include \"";
      if (line.rfind(head, 0) != 0) continue;
      const std::size_t end = line.find('"', head.size());
      if (end == std::string::npos) continue;
      out.push_back(
          {fs::relative(entry.path(), root).string(), line.substr(head.size(), end - head.size())});
    }
  }
  return out;
}

bool starts_with(const std::string& s, const std::string& prefix) {
  return s.rfind(prefix, 0) == 0;
}

// The includes of `folder` whose target starts with one of `forbidden`.
std::vector<std::string> violations(const std::string& folder,
                                    const std::vector<std::string>& forbidden) {
  std::vector<std::string> out;
  for (const Include& i : includes_under(folder))
    for (const std::string& f : forbidden)
      if (starts_with(i.target, f)) out.push_back(i.file + " includes " + i.target);
  return out;
}

std::string lines(const std::vector<std::string>& v) {
  std::string out;
  for (const auto& s : v) out += "\n  " + s;
  return out;
}

TEST(IncludeRules, SupportIncludesNothingOfTheOtherFolders) {
  const auto v =
      violations("support", {"generator/", "runtime/", "loader/", "apps/", "analysis/", "python/"});
  EXPECT_TRUE(v.empty()) << lines(v);
}

TEST(IncludeRules, RuntimeNeverIncludesTheGenerator) {
  const auto v = violations("runtime", {"generator/", "apps/"});
  EXPECT_TRUE(v.empty()) << lines(v);
}

TEST(IncludeRules, TheDerivationNeverIncludesTheCodeGenerator) {
  std::vector<std::string> v;
  for (const Include& i : includes_under("generator"))
    if (!starts_with(i.file, "generator/codegen/") && starts_with(i.target, "generator/codegen/"))
      v.push_back(i.file + " includes " + i.target);
  EXPECT_TRUE(v.empty()) << lines(v);
}

TEST(IncludeRules, CodegenLayersIncludeOnlyDownwards) {
  const std::string codegen = "generator/codegen/";
  const std::string emitter = codegen + "emitter.h";
  auto v = violations(codegen + "ir", {codegen + "strategies/", codegen + "targets/", emitter});
  const auto strategies = violations(codegen + "strategies", {codegen + "targets/", emitter});
  const auto targets = violations(codegen + "targets", {emitter});
  v.insert(v.end(), strategies.begin(), strategies.end());
  v.insert(v.end(), targets.begin(), targets.end());
  EXPECT_TRUE(v.empty()) << lines(v);
  // The rules see the layers: each folder has includes of its own to check.
  for (const char* layer : {"ir", "strategies", "targets"})
    EXPECT_FALSE(includes_under(codegen + layer).empty()) << layer;
}

TEST(IncludeRules, PythonAndTheFrontEndNeverIncludeApps) {
  auto v = violations("python", {"apps/"});
  const auto frontend = violations("frontend", {"apps/", "python/"});
  v.insert(v.end(), frontend.begin(), frontend.end());
  EXPECT_TRUE(v.empty()) << lines(v);
  // The rule sees what Python and the CLI share: the bindings include the front end.
  int shared = 0;
  for (const Include& i : includes_under("python")) shared += starts_with(i.target, "frontend/");
  EXPECT_GE(shared, 3);
}

TEST(IncludeRules, TheGeneratorsFrontEndNeverIncludesTheRuntime) {
  const std::set<std::string> volume_frontend{
      "frontend/filter_choice.h",  "frontend/filter_choice.cpp", "frontend/input_checks.h",
      "frontend/input_checks.cpp", "frontend/sample_grid.h",     "frontend/sample_grid.cpp"};
  std::vector<std::string> v;
  for (const std::string& i : violations("frontend", {"runtime/", "loader/"}))
    if (!volume_frontend.count(i.substr(0, i.find(' ')))) v.push_back(i);
  for (const std::string& file : volume_frontend)  // the list names files that exist
    EXPECT_TRUE(fs::exists(fs::path(BOXGEN_SOURCE_DIR) / file)) << file;
  EXPECT_TRUE(v.empty()) << lines(v);
}

}  // namespace
