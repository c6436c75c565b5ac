// The filter cache from the command line: `boxrecon filters` shows
// what an entry's .json says only as plain text, a cache others can write is refused in one line,
// and a compile stopped by SIGTERM or SIGINT leaves no compiler running and no temporary behind.
// The caches and compilers (shell scripts) are made here. BOXRECON_UNDER_TEST runs them against
// another boxrecon (an older build fails them).
#include <signal.h>
#include <spawn.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>
#include <thread>
#include <vector>

#include "boxrecon_scratch_test.h"
#include "cli_support.h"

extern char** environ;  // NOLINT(readability-redundant-declaration): POSIX, for posix_spawn

namespace boxgen::test {
namespace {

namespace fs = std::filesystem;

constexpr const char* kSpec = "1,1,1; 1,-1,-1; -1,1,-1; -1,-1,1; 2,0,0; 0,2,0";

void write_text(const fs::path& path, const std::string& text, fs::perms perms = fs::perms(0644)) {
  std::ofstream(path, std::ios::binary) << text;
  fs::permissions(path, perms);
}

// True while `pid` runs (a zombie waiting for a reaper that is not ours does not).
bool running(pid_t pid) {
  std::ifstream in("/proc/" + std::to_string(pid) + "/stat");
  std::string stat;
  if (!std::getline(in, stat)) return false;
  const std::size_t paren = stat.rfind(')');
  return paren == std::string::npos || stat.size() <= paren + 2 || stat[paren + 2] != 'Z';
}

class BoxreconCache : public BoxreconScratchTest {
 protected:
  BoxreconCache() : BoxreconScratchTest("boxrecon-cache") {}
  void TearDown() override {
    ::unsetenv("BOXGEN_CACHE_DIR");
    ::unsetenv("BOXGEN_CXX");
    BoxreconScratchTest::TearDown();
  }
  // An entry as the loader writes it, with `spec` in its .json.
  void entry(const fs::path& cache, const std::string& key, const std::string& spec) {
    const nlohmann::json j{{"spec", spec},
                           {"lattice", "bcc"},
                           {"rows", "2,0,0; 0,2,0; 1,1,1"},
                           {"stamp", "s"},
                           {"so_hash", "0"},
                           {"so_size", 0},
                           {"glsl_hash", "0"},
                           {"glsl_double_hash", "0"},
                           {"glsl_buffered_hash", "0"},
                           {"glsl_buffered_double_hash", "0"},
                           {"glsl_block", nlohmann::json::array()}};
    write_text(cache / (key + ".json"), j.dump(2));
    write_text(cache / (key + ".so"), "");
  }
};

// The trial's .json held ESC sequences and newlines, which reached the terminal.
TEST_F(BoxreconCache, FiltersPrintsOnlyPlainText) {
  const fs::path cache = dir_ / "cache";
  fs::create_directory(cache);
  entry(cache, "0123456789abcdef", "1,1,1; 2,0,0");
  entry(cache, "1123456789abcdef", "\x1b]0;owned\x07\x1b[31m1,1,1\nfake line\r");
  entry(cache, "\x1b[31m3456789abcdef", "1,0,0");
  ::setenv("BOXGEN_CACHE_DIR", cache.c_str(), 1);
  const std::string out = ok({"filters"});
  for (const char bad : {'\x1b', '\x07', '\r'})
    EXPECT_EQ(out.find(bad), std::string::npos) << "a control character reached the terminal";
  EXPECT_EQ(out.find("fake line"), std::string::npos) << out;
  EXPECT_NE(out.find("): 1\n  \"1,1,1; 2,0,0\" --lattice bcc"), std::string::npos) << out;
}

TEST_F(BoxreconCache, SharedCacheIsRefusedInOneLine) {
  const fs::path cache = dir_ / "cache";
  fs::create_directory(cache);
  ASSERT_EQ(::chmod(cache.c_str(), 01777), 0);
  ::setenv("BOXGEN_CACHE_DIR", cache.c_str(), 1);
  for (const std::vector<std::string>& args :
       {std::vector<std::string>{"filters"},
        {"sample", "--function", "ml", "--n", "5", "--filter", kSpec, "--lattice", "bcc", "-o",
         file("v.nrrd")}}) {
    const ProcessResult r = boxrecon(args);
    EXPECT_TRUE(r.exited && r.exit_code == 1) << describe(args, r);
    EXPECT_EQ(r.out, "") << describe(args, r);
    EXPECT_EQ(r.err.find("boxrecon: error: the filter cache '" + cache.string() +
                         "' is writable by others (mode 1777)"),
              0U)
        << describe(args, r);
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << describe(args, r);
  }
  EXPECT_TRUE(fs::is_empty(cache));
  EXPECT_FALSE(fs::exists(file("v.nrrd")));
}

// The trial's compiler ran on after boxrecon was stopped and re-created a `.KEY.so.tmp-PID`. Here
// the compiler writes its pid, waits 2 s and then writes its output, as a linker would; boxrecon is
// stopped while it waits. Afterwards no process of the compiler runs and the cache holds no
// temporary.
TEST_F(BoxreconCache, StoppedCompileLeavesNothingBehind) {
  for (const int signal : {SIGTERM, SIGINT}) {
    const fs::path cache = dir_ / ("cache-" + std::to_string(signal)), pid_file = dir_ / "pid";
    fs::remove(pid_file);
    const fs::path cxx = dir_ / "cxx";
    write_text(cxx,
               "#!/bin/sh\nif [ \"$1\" = --version ]; then echo slow-cxx; exit 0; fi\n"
               "out=\nwhile [ $# -gt 0 ]; do [ \"$1\" = -o ] && out=$2; shift; done\n"
               "echo $$ > '" +
                   pid_file.string() + "'\nsleep 2\necho object > \"$out\"\n",
               fs::perms(0755));
    ::setenv("BOXGEN_CACHE_DIR", cache.c_str(), 1);
    ::setenv("BOXGEN_CXX", cxx.c_str(), 1);
    const char* other = std::getenv("BOXRECON_UNDER_TEST");
    std::string program = other ? other : BOXRECON_EXE;
    std::vector<std::string> args{program,    "sample", "--function", "ml",  "--n", "5",
                                  "--filter", kSpec,    "--lattice",  "bcc", "-o",  file("v.nrrd")};
    std::vector<char*> argv;
    for (auto& a : args) argv.push_back(a.data());
    argv.push_back(nullptr);
    pid_t pid = -1;
    ASSERT_EQ(::posix_spawn(&pid, program.c_str(), nullptr, nullptr, argv.data(), environ), 0);
    for (int wait = 0; wait < 600 && !fs::exists(pid_file); ++wait)
      std::this_thread::sleep_for(std::chrono::milliseconds(100));
    ASSERT_TRUE(fs::exists(pid_file)) << "the compiler was never started";
    std::this_thread::sleep_for(std::chrono::milliseconds(200));
    ::kill(pid, signal);
    int status = 0;
    ASSERT_EQ(::waitpid(pid, &status, 0), pid);
    EXPECT_TRUE(WIFSIGNALED(status) && WTERMSIG(status) == signal) << status;
    pid_t compiler = 0;
    std::ifstream(pid_file) >> compiler;
    std::this_thread::sleep_for(std::chrono::seconds(3));  // the compiler's 2 s, and a margin
    EXPECT_FALSE(running(compiler)) << "the compiler outlived boxrecon";
    for (const auto& e : fs::directory_iterator(cache))
      EXPECT_EQ(e.path().filename().string().find(".tmp-"), std::string::npos)
          << e.path() << " was left behind (signal " << signal << ")";
    EXPECT_FALSE(fs::exists(file("v.nrrd")));
  }
}

}  // namespace
}  // namespace boxgen::test
