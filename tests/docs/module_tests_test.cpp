// The tree's conventions that docs/testing.md states: every generator module
// generator/<path>/<m>.cpp, in generator/ and in its subfolders (codegen/ir, codegen/strategies,
// codegen/targets, ...), has its test file tests/generator/<path>/<m>_test.cpp. Build-time tools
// (a folder named tools/) are tested by what they write, not by a file of their own.
#include <gtest/gtest.h>

#include <filesystem>

namespace {

namespace fs = std::filesystem;

TEST(TreeConventions, EveryGeneratorModuleHasATestFileNamedAfterIt) {
  const fs::path root = BOXGEN_SOURCE_DIR;
  const fs::path generator = root / "generator";
  int modules = 0, nested = 0;
  for (auto it = fs::recursive_directory_iterator(generator); it != fs::end(it); ++it) {
    if (it->is_directory() && it->path().filename() == "tools") {
      it.disable_recursion_pending();
      continue;
    }
    if (it->path().extension() != ".cpp") continue;
    ++modules;
    const fs::path relative = fs::relative(it->path(), generator);
    if (relative.has_parent_path()) ++nested;
    const fs::path test = relative.parent_path() / (it->path().stem().string() + "_test.cpp");
    EXPECT_TRUE(fs::exists(root / "tests" / "generator" / test))
        << "generator/" << relative.string() << " has no tests/generator/" << test.string();
  }
  EXPECT_GT(modules, 20);
  EXPECT_GT(nested, 5);  // the subfolders are walked
}

}  // namespace
