// boxrecon's bounds on work and memory: arguments inside their allowed
// ranges that once ran for ever or died of std::bad_alloc (exit 3) are refused up front with one
// line naming the bound and the size asked for, exit 1, within seconds.
#include <fcntl.h>
#include <sys/wait.h>
#include <unistd.h>
#include <znzlib.h>

#include <algorithm>
#include <cctype>
#include <csignal>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include "cli_support.h"
#include "tests/support/scratch_directory.h"

namespace boxgen::test {
namespace {

// Half of this machine's memory, the budget boxrecon allows (frontend/input_checks.h).
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
    // A refusal must come quickly: the deadline is far below what the unbounded work would take.
    const ProcessResult r = boxrecon(args, {.stdout_file = "", .stdin_file = stdin_file},
                                     std::chrono::seconds(30 * kSlowdown));
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
    refused({"render", "--function", "ml", "--n", "8", "--width", "64", "--height", "64", "--step",
             step, "-o", file("r.png")},
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
  if (memory_budget_bytes() > 16e9)  // the render case below needs 17.5 GB to be refused
    GTEST_SKIP() << "this machine holds more than the sizes asked for here";
  // ml at N = 1024 on BCC with M7's margin for q1 (3 cells a side): 2 x 1030^3 doubles, 16.3 GiB,
  // beyond half of a 24 GiB machine (the other half is for the prefiltered copy).
  refused({"render", "--function", "ml", "--n", "1024", "--prefilter", "q1", "-o", file("r.png")},
          {"--n 1024", "GiB"});
  // 10^9 random and ray points of 24 bytes and a value each: 52 GiB.
  refused({"bench", "--points", "1000000000"}, {"--points 1000000000", "GiB"});
}

// Under a 4 GiB address-space limit (ulimit -v), requests that fit the
// machine's memory but not the process's ended in std::bad_alloc (exit 3). Each limit now comes
// from the memory the process may still take, checked before allocating: one line, exit 1.
class BoxreconMemoryLimit : public BoxreconLimits {
 protected:
  void SetUp() override {
    if (kAddressSanitizer) GTEST_SKIP() << "an AddressSanitizer build cannot start under ulimit -v";
    BoxreconLimits::SetUp();
  }
  // boxrecon `args` run by sh under `ulimit -v 4 GiB`, after `before |` when given.
  void refused_under_limit(const std::vector<std::string>& args,
                           const std::vector<std::string>& mentions,
                           const std::string& before = "") {
    const char* other = std::getenv("BOXRECON_UNDER_TEST");
    std::vector<std::string> sh{"-c", "ulimit -v 4194304 && " + before + " \"$0\" \"$@\"",
                                other ? other : BOXRECON_EXE};
    sh.insert(sh.end(), args.begin(), args.end());
    const ProcessResult r = run_process("/bin/sh", sh, std::chrono::seconds(120 * kSlowdown));
    const std::string what = describe(sh, r);
    ASSERT_FALSE(r.timed_out) << what;
    EXPECT_TRUE(r.exited && r.exit_code == 1) << what;
    EXPECT_EQ(r.out, "") << what;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << what;
    EXPECT_EQ(r.err.find("internal error"), std::string::npos) << what;
    for (const std::string& m : mentions)
      EXPECT_NE(r.err.find(m), std::string::npos) << "expected '" << m << "'\n" << what;
  }
};

TEST_F(BoxreconMemoryLimit, SubsampleBeyondTheProcesssMemoryIsRefused) {
  const ProcessResult made = boxrecon(
      {"sample", "--function", "ml", "--n", "20", "--lattice", "cartesian", "-o", file("in.nrrd")});
  ASSERT_TRUE(made.exited && made.exit_code == 0) << describe({"sample"}, made);
  refused_under_limit({"subsample", "--volume", file("in.nrrd"), "--lattice", "bcc", "--spacing",
                       "1e-3", "-o", file("out.nrrd")},
                      {"--spacing 0.001 needs", "what this process may still take"});
  EXPECT_FALSE(std::filesystem::exists(file("out.nrrd")));
}

// A .nii.gz of a few kilobytes that declares 1500^3 uint8 voxels (3.4 GB, and a float copy).
TEST_F(BoxreconMemoryLimit, NiftiDeclaringMoreThanTheProcesssMemoryIsRefused) {
  std::string header(352, '\0');
  const auto put16 = [&](std::size_t at, std::int16_t v) { std::memcpy(&header[at], &v, 2); };
  const auto putf = [&](std::size_t at, float v) { std::memcpy(&header[at], &v, 4); };
  const std::int32_t size = 348;
  std::memcpy(&header[0], &size, 4);
  put16(40, 3);
  for (int a = 0; a < 3; ++a) put16(42 + 2 * a, 1500);
  for (int a = 3; a < 7; ++a) put16(42 + 2 * a, 1);
  put16(70, 2);  // DT_UINT8
  put16(72, 8);
  for (int a = 0; a < 4; ++a) putf(76 + 4 * a, 1);
  putf(108, 352);
  std::memcpy(&header[344], "n+1", 4);
  const std::string path = file("big.nii.gz");
  znzFile out = znzopen(path.c_str(), "wb", 1);
  ASSERT_FALSE(znz_isnull(out));
  const std::string zeros(1 << 20, '\0');
  znzwrite(header.data(), 1, header.size(), out);
  for (int i = 0; i < 4; ++i) znzwrite(zeros.data(), 1, zeros.size(), out);
  znzclose(out);
  refused_under_limit({"subsample", "--volume", path, "--lattice", "bcc", "--fraction", "0.03",
                       "-o", file("out.nrrd")},
                      {"big.nii.gz", "this process may still take"});
  EXPECT_FALSE(std::filesystem::exists(file("out.nrrd")));
}

TEST_F(BoxreconMemoryLimit, EndlessPointsAreRefusedWithinTheProcesssMemory) {
  const ProcessResult made = boxrecon(
      {"sample", "--function", "cubic", "--n", "6", "--filter", "m7", "-o", file("v.nrrd")});
  ASSERT_TRUE(made.exited && made.exit_code == 0) << describe({"sample"}, made);
  refused_under_limit({"eval", "--filter", "m7", "--volume", file("v.nrrd"), "--points", "-"},
                      {"points, the most whose 128 bytes each fit in the memory"}, "yes '0 0 0' |");
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

// SIGINT while resample writes its output: the temporary is removed, the old output stays.
TEST_F(BoxreconLimits, AnInterruptedWriteLeavesNoTemporary) {
  const ProcessResult made = boxrecon(
      {"sample", "--function", "cubic", "--n", "12", "--filter", "m7", "-o", file("v.nrrd")});
  ASSERT_TRUE(made.exited && made.exit_code == 0) << describe({"sample"}, made);
  { std::ofstream(file("out.nrrd")) << "old"; }
  const pid_t pid = ::fork();
  if (pid == 0) {
    const int null = ::open("/dev/null", O_RDWR);
    ::dup2(null, 0);
    ::dup2(null, 1);
    ::dup2(null, 2);
    ::execl(BOXRECON_EXE, BOXRECON_EXE, "resample", "--filter", "m7", "--volume",
            file("v.nrrd").c_str(), "--n", "300", "--precision", "float", "-o",
            file("out.nrrd").c_str(), nullptr);
    ::_exit(127);
  }
  // Wait for the temporary to appear, then interrupt.
  const auto temporary_exists = [&] {
    for (const auto& e : std::filesystem::directory_iterator(dir_))
      if (e.path().filename().string().rfind(".out.nrrd.tmp-", 0) == 0) return true;
    return false;
  };
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(120 * kSlowdown);
  bool seen = false;
  int status = 0;
  while (std::chrono::steady_clock::now() < deadline) {
    if ((seen = temporary_exists())) break;
    if (::waitpid(pid, &status, WNOHANG) == pid) break;  // finished before we saw it
    ::usleep(500);
  }
  if (seen) {
    ::kill(pid, SIGINT);
    ::waitpid(pid, &status, 0);
  }
  ASSERT_TRUE(seen) << "the temporary never appeared";
  EXPECT_FALSE(temporary_exists()) << "SIGINT left the temporary behind";
  if (WIFSIGNALED(status)) {
    EXPECT_EQ(WTERMSIG(status), SIGINT);
    std::ifstream in(file("out.nrrd"));
    std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    EXPECT_EQ(text, "old");
  }
}

}  // namespace
}  // namespace boxgen::test
