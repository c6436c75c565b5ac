// The tree's conventions that docs/testing.md states: every generator module generator/<m>.cpp has
// its test file tests/generator/<m>_test.cpp.
#include <gtest/gtest.h>

#include <filesystem>

namespace {

namespace fs = std::filesystem;

TEST(TreeConventions, EveryGeneratorModuleHasATestFileNamedAfterIt) {
  const fs::path root = BOXGEN_SOURCE_DIR;
  int modules = 0;
  for (const auto& entry : fs::directory_iterator(root / "generator")) {
    if (entry.path().extension() != ".cpp") continue;
    ++modules;
    const std::string module = entry.path().stem().string();
    EXPECT_TRUE(fs::exists(root / "tests" / "generator" / (module + "_test.cpp")))
        << "generator/" << module << ".cpp has no tests/generator/" << module << "_test.cpp";
  }
  EXPECT_GT(modules, 20);
}

}  // namespace
