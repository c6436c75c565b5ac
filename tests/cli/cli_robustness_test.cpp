// Regression tests for two robustness bugs found while writing the CLI tests: a failed write to
// stdout was reported as success, and small generic direction matrices hung in cell enumeration
// instead of being refused up front.
#include <algorithm>

#include "cli_support.h"

namespace boxgen::test {
namespace {

// Brief: never "a silently wrong answer". With stdout on a full disk the answer is lost, yet boxgen
// exits 0 with nothing on stderr, so `boxgen analyze m7 --json > out.json && use out.json` goes on
// with an empty file. Expected: a non-zero exit and one line on stderr.
TEST(CliRobustness, AFailedWriteToStdoutIsAnError) {
  for (const std::vector<std::string>& args :
       {std::vector<std::string>{"presets", "--json"},
        std::vector<std::string>{"eval", "hex3", "--at", "0 0"}}) {
    const ProcessResult r = run_process(BOXGEN_EXE, args, kDefaultTimeout, "/dev/full");
    ASSERT_TRUE(r.exited) << describe(args, r);
    EXPECT_NE(r.exit_code, 0) << "output was lost but boxgen reported success\n"
                              << describe(args, r);
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << describe(args, r);
    EXPECT_EQ(r.err.rfind("boxgen: ", 0), 0u) << describe(args, r);
  }
}

// Brief: never "a hang". A linear box spline (degree 4 - 3 = 1) of four small integer directions on
// the Cartesian lattice once ran for minutes with memory growing past 450 MB (every integer level
// of every knot normal was a cell boundary), for `eval` as for `analyze`. Expected: an answer
// within the deadline or one line saying the SPEC is too complex to derive. (On the knot-plane
// cells it now answers in well under a second.)
TEST(CliRobustness, SmallGenericDirectionMatrixFinishesOrRefuses) {
  const std::vector<std::string> args{"eval", "1,2,3; 3,1,2; 2,3,1; -1,2,3", "--at", "0 0 0"};
  const ProcessResult r = boxgen(args, std::chrono::seconds(60 * kSlowdown));
  ASSERT_FALSE(r.timed_out) << describe(args, r);
  ASSERT_TRUE(r.exited) << describe(args, r);
  if (r.exit_code == 0) {
    EXPECT_EQ(r.err, "") << describe(args, r);
  } else {
    EXPECT_NE(r.exit_code, 3) << describe(args, r);
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << describe(args, r);
  }
}

}  // namespace
}  // namespace boxgen::test
