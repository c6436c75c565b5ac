// Regression tests for two robustness bugs found while writing the CLI tests: a failed write to
// stdout was reported as success, and small generic direction matrices hung in cell enumeration
// instead of being refused up front.
#include <fcntl.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "cli_support.h"

namespace boxgen::test {
namespace {

// Brief: never "a silently wrong answer". With stdout on a full disk the answer is lost, yet boxgen
// exits 0 with nothing on stderr, so `boxgen analyze m7 --json > out.json && use out.json` goes on
// with an empty file. Expected: a non-zero exit and one line on stderr.
// The child's stderr read to its end (the pipe then closed), and its exit status.
std::string drain_and_wait(int err_fd, pid_t pid, int& status) {
  std::string text;
  char buffer[256];
  for (ssize_t n; (n = ::read(err_fd, buffer, sizeof buffer)) > 0;) text.append(buffer, n);
  ::close(err_fd);
  ::waitpid(pid, &status, 0);
  return text;
}

TEST(CliRobustness, AFailedWriteToStdoutIsAnError) {
  for (const std::vector<std::string>& args :
       {std::vector<std::string>{"presets", "--json"},
        std::vector<std::string>{"eval", "hex3", "--at", "0 0"},
        std::vector<std::string>{"pieces", "m7", "--region", "all"}}) {
    const ProcessResult r = run_process(BOXGEN_EXE, args, kDefaultTimeout, "/dev/full");
    ASSERT_TRUE(r.exited) << describe(args, r);
    EXPECT_EQ(r.exit_code, 1) << "output was lost: an output error (1), not success or internal\n"
                              << describe(args, r);
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << describe(args, r);
    EXPECT_EQ(r.err.rfind("boxgen: ", 0), 0u) << describe(args, r);
  }
}

// A reader that has gone (`boxgen pieces m7 | head -c 0`): the program ends quietly with a
// non-zero status, as coreutils do, instead of dying of SIGPIPE or printing an error.
TEST(CliRobustness, AClosedPipeEndsQuietlyWithStatusOne) {
  int ends[2];
  ASSERT_EQ(::pipe(ends), 0);
  int err[2];
  ASSERT_EQ(::pipe(err), 0);
  const pid_t pid = ::fork();
  if (pid == 0) {
    ::close(ends[0]);
    ::dup2(ends[1], 1);
    ::dup2(err[1], 2);
    ::close(err[0]);
    const int null = ::open("/dev/null", O_RDONLY);
    ::dup2(null, 0);
    ::execl(BOXGEN_EXE, BOXGEN_EXE, "pieces", "m7", "--region", "all", nullptr);
    ::_exit(127);
  }
  ::close(ends[0]);  // nobody reads: the child's first write fails
  ::close(ends[1]);
  ::close(err[1]);
  int status = 0;
  const std::string stderr_text = drain_and_wait(err[0], pid, status);
  ASSERT_TRUE(WIFEXITED(status)) << "killed by signal " << WTERMSIG(status);
  EXPECT_EQ(WEXITSTATUS(status), 1);
  EXPECT_EQ(stderr_text, "");
}

// `boxrecon eval ... | head -c1`: the reader goes after the first byte, while
// boxrecon has more to write. The write that meets EPIPE is long past when boxrecon finishes, so
// errno no longer says so; it printed "could not write the output: disk full or closed pipe?".
TEST(CliRobustness, AReaderGoneMidwayEndsQuietlyWithStatusOne) {
  const std::string dir = ::testing::TempDir() + "closed-pipe-" + std::to_string(::getpid());
  std::filesystem::create_directories(dir);
  const std::vector<std::string> sample = {"sample",   "--function", "ml", "--n",          "8",
                                           "--filter", "m7",         "-o", dir + "/v.nrrd"};
  ASSERT_EQ(run_process(BOXRECON_EXE, sample, kDefaultTimeout).exit_code, 0);
  {
    std::ofstream points(dir + "/points.txt");
    for (int i = 0; i < 20000; ++i)
      points << (i % 7) * 0.05 - 0.15 << ' ' << (i % 11) * 0.03 - 0.15 << ' '
             << (i % 13) * 0.02 - 0.12 << '\n';
  }
  int ends[2], err[2];
  ASSERT_EQ(::pipe(ends), 0);
  ASSERT_EQ(::pipe(err), 0);
  const std::string volume = dir + "/v.nrrd", points = dir + "/points.txt";
  const pid_t pid = ::fork();
  if (pid == 0) {
    ::close(ends[0]);
    ::close(err[0]);
    ::dup2(ends[1], 1);
    ::dup2(err[1], 2);
    ::execl(BOXRECON_EXE, BOXRECON_EXE, "eval", "--filter", "m7", "--volume", volume.c_str(),
            "--points", points.c_str(), nullptr);
    ::_exit(127);
  }
  ::close(ends[1]);
  ::close(err[1]);
  char first = 0;
  EXPECT_EQ(::read(ends[0], &first, 1), 1);  // head -c1
  ::close(ends[0]);
  int status = 0;
  const std::string stderr_text = drain_and_wait(err[0], pid, status);
  std::filesystem::remove_all(dir);
  ASSERT_TRUE(WIFEXITED(status)) << "killed by signal " << WTERMSIG(status);
  EXPECT_EQ(WEXITSTATUS(status), 1);
  EXPECT_EQ(stderr_text, "");
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
