// One version string: project(VERSION) in CMakeLists.txt reaches both programs' --version.
#include "cli_support.h"

#ifndef BOXGEN_PROJECT_VERSION
#error "BOXGEN_PROJECT_VERSION must be set by tests/cli/CMakeLists.txt"
#endif

namespace boxgen::test {
namespace {

TEST(CliVersion, BothProgramsReportTheProjectVersion) {
  EXPECT_EQ(boxgen_ok({"--version"}), std::string("boxgen ") + BOXGEN_PROJECT_VERSION + "\n");
  const ProcessResult r = run_process(BOXRECON_EXE, {"--version"}, kDefaultTimeout);
  EXPECT_TRUE(r.exited && r.exit_code == 0) << describe({"--version"}, r);
  EXPECT_EQ(r.out, std::string("boxrecon ") + BOXGEN_PROJECT_VERSION + "\n");
}

}  // namespace
}  // namespace boxgen::test
