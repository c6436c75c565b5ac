// boxrecon's bounds on work and memory (issue 19, items 4-6): arguments inside their allowed
// ranges that once ran for ever or died of std::bad_alloc (exit 3) are refused up front with one
// line naming the bound and the size asked for, exit 1, within seconds.
#include <unistd.h>

#include <algorithm>
#include <cctype>
#include <cstdint>
#include <cstdlib>
#include <string>
#include <vector>

#include "cli_support.h"
#include "tests/support/scratch_directory.h"

#ifndef BOXRECON_EXE
#error "BOXRECON_EXE must name the boxrecon binary (set by tests/cli/CMakeLists.txt)"
#endif

namespace boxgen::test {
namespace {

// A refusal must come quickly: the deadline is far below what the unbounded work would take.
ProcessResult boxrecon(const std::vector<std::string>& args, const std::string& stdin_file = "") {
  const char* other = std::getenv("BOXRECON_UNDER_TEST");
  return run_process(other && *other ? other : BOXRECON_EXE, args,
                     std::chrono::seconds(30 * kSlowdown), "", stdin_file);
}

std::string lower(std::string s) {
  std::transform(s.begin(), s.end(), s.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return s;
}

// Half of this machine's memory, the budget boxrecon allows (apps/boxrecon/input_checks.h).
double memory_budget_bytes() {
  return static_cast<double>(::sysconf(_SC_PHYS_PAGES)) / 2 *
         static_cast<double>(::sysconf(_SC_PAGE_SIZE));
}

class BoxreconLimits : public ScratchDirectoryTest {
 protected:
  BoxreconLimits() : ScratchDirectoryTest("boxrecon-limits") {}
  std::string file(const std::string& name) const { return (dir_ / name).string(); }

  void refused(const std::vector<std::string>& args, const std::vector<std::string>& mentions,
               const std::string& stdin_file = "") {
    const ProcessResult r = boxrecon(args, stdin_file);
    const std::string what = describe(args, r);
    ASSERT_FALSE(r.timed_out) << "not refused up front\n" << what;
    ASSERT_TRUE(r.exited) << what;
    EXPECT_EQ(r.exit_code, 1) << what;
    EXPECT_EQ(r.out, "") << what;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << what;
    for (const std::string& m : mentions)
      EXPECT_NE(lower(r.err).find(lower(m)), std::string::npos) << "expected '" << m << "'\n"
                                                                << what;
  }
};

TEST_F(BoxreconLimits, AMarchingStepWithTooManySamplesPerRayIsRefused) {
  // The box [-1,1]^3 has the diagonal 2 sqrt(3) = 3.46: 1e-300 and 1e-12 ask for 3.5e300 and
  // 3.5e12 samples per ray, beyond the bound of 65536.
  for (const std::string step : {"1e-300", "1e-12"}) {
    refused({"render", "--function", "ml", "--n", "8", "--width", "64", "--height", "64",
             "--step", step, "-o", file("r.png")},
            {"samples per ray", "65536"});
    EXPECT_FALSE(std::filesystem::exists(file("r.png")));
  }
}

TEST_F(BoxreconLimits, PointsThatAreNotTextAreRefusedBeforeMemoryRunsOut) {
  // A volume to evaluate on.
  const ProcessResult made = boxrecon(
      {"sample", "--function", "cubic", "--n", "6", "--filter", "m7", "-o", file("v.nrrd")});
  ASSERT_TRUE(made.exited && made.exit_code == 0) << describe({"sample"}, made);
  // /dev/zero has no line end: the first line passes the 4096-byte bound at once. Endless standard
  // input is the same file on stdin.
  refused({"eval", "--filter", "m7", "--volume", file("v.nrrd"), "--points", "/dev/zero"},
          {"longer than 4096 bytes"});
  refused({"eval", "--filter", "m7", "--volume", file("v.nrrd"), "--points", "-"},
          {"longer than 4096 bytes", "<stdin>"}, "/dev/zero");
}

TEST_F(BoxreconLimits, SizesBeyondMemoryAreRefusedNamingTheSizeNeeded) {
  if (memory_budget_bytes() > 48e9)
    GTEST_SKIP() << "this machine holds more than the sizes asked for here";
  // ml at N = 1024 on BCC with M7's margin for q1 (3 cells a side): 2 x 1030^3 doubles and the
  // prefiltered copy, 32.6 GiB.
  refused({"render", "--function", "ml", "--n", "1024", "--prefilter", "q1", "-o", file("r.png")},
          {"--n 1024", "GiB"});
  // 10^9 random and ray points of 24 bytes and a value each: 52 GiB.
  refused({"bench", "--points", "1000000000"}, {"--points 1000000000", "GiB"});
}

// A full disk while a file is written: one line in the project's words with the system's reason,
// exit 1, no file and no temporary left. A file size limit stands in for the full disk (the write
// fails with EFBIG; SIGXFSZ is ignored, as the shell's trap leaves it for the exec'd program).
TEST_F(BoxreconLimits, AFullDiskIsAnOutputErrorInOurWords) {
  const std::vector<std::vector<std::string>> writers = {
      {BOXRECON_EXE, "render", "--function", "sphere", "--n", "8", "--width", "64", "--height",
       "64", "-o", file("r.png")},
      {BOXRECON_EXE, "sample", "--function", "cubic", "--n", "12", "-o", file("v.nrrd")},
      {BOXGEN_EXE, "spectrum", "m7", "--plane", "1,0,0", "--size", "64", "-o", file("p.png")}};
  for (const auto& command : writers) {
    std::vector<std::string> args = {"-c", "trap '' XFSZ; ulimit -f 1; exec \"$0\" \"$@\""};
    args.insert(args.end(), command.begin(), command.end());
    const ProcessResult r = run_process("/bin/sh", args, std::chrono::seconds(60 * kSlowdown));
    const std::string what = describe(command, r);
    ASSERT_TRUE(r.exited) << what;
    EXPECT_EQ(r.exit_code, 1) << what;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << what;
    EXPECT_NE(lower(r.err).find("file too large"), std::string::npos) << what;
    EXPECT_EQ(lower(r.err).find("fwrite"), std::string::npos) << what;  // no library's words
    EXPECT_EQ(lower(r.err).find("internal"), std::string::npos) << what;
    std::size_t left = 0;
    for ([[maybe_unused]] const auto& entry : std::filesystem::directory_iterator(dir_)) ++left;
    EXPECT_EQ(left, 0u) << what;
  }
}

}  // namespace
}  // namespace boxgen::test
