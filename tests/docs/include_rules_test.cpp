// The include rules between the project's folders (the code generator's: docs/design.md §15):
// which folder's code may include which. An #include "FOLDER/..." line of the project's own files
// is checked against the rules below; system and third-party headers (<...>) are not.
//   - support/ includes nothing of the project's other folders;
//   - runtime/ never includes the generator (it links against what the generator wrote);
//   - generator/ (the derivation) never includes generator/codegen/, which depends on it;
//   - in generator/codegen/: ir/ includes no strategy, target or the emitter; strategies/ no
//     target nor the emitter; targets/ not the emitter;
//   - python/ does not include apps/, but for the known includes listed below (the JSON builders
//     and option checks the CLI and Python share still live in apps/: issue 34, item 6). The
//     list must stay exact: a new include fails, and so does one that is gone.
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

TEST(IncludeRules, PythonIncludesAppsOnlyWhereKnown) {
  const std::set<std::string> known{
      "python/analysis_bindings.cpp includes apps/boxgen/commands.h",
      "python/module.cpp includes apps/boxgen/commands.h",
      "python/runtime_bindings.cpp includes apps/boxrecon/filter_choice.h",
      "python/runtime_bindings.cpp includes apps/boxrecon/sample_command.h"};
  const auto v = violations("python", {"apps/"});
  EXPECT_EQ(std::set<std::string>(v.begin(), v.end()), known);
}

}  // namespace
