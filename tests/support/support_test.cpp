// The support library (support/): the one floor_div and UnionFind, the glue's nearest_cell
// (support/cell_glue.h, on a table written here; every filter's tables: tests/gpu), the atomic
// writer's guarantees (support/output_file.h): complete files or none, sets all or nothing,
// temporaries removed on signals and after SIGKILL, never an input overwritten.
#include <gtest/gtest.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cmath>
#include <csignal>
#include <cstdio>
#include <fstream>
#include <iterator>
#include <set>
#include <string>
#include <vector>

#include "support/available_memory.h"
#include "support/cell_glue.h"
#include "support/integer_math.h"
#include "support/lattice_text.h"
#include "support/output_file.h"
#include "support/union_find.h"
#include "tests/support/scratch_directory.h"

namespace boxgen::support {
namespace {

namespace fs = std::filesystem;

TEST(IntegerMath, FloorDivIsTheMathematicalFloorForEverySignCombination) {
  for (std::int64_t a = -50; a <= 50; ++a)
    for (std::int64_t b = -7; b <= 7; ++b) {
      if (b == 0) continue;
      // Reference: the quotient of small integers is exact in long double, so floor is exact.
      const auto expected = static_cast<std::int64_t>(
          std::floor(static_cast<long double>(a) / static_cast<long double>(b)));
      EXPECT_EQ(floor_div(a, b), expected) << a << " / " << b;
    }
  static_assert(floor_div(-1, 2) == -1 && floor_div(7, -2) == -4 && floor_div(-8, 4) == -2);
  EXPECT_EQ(floor_div(-(std::int64_t{1} << 40) - 1, 1 << 20), -(std::int64_t{1} << 20) - 1);
}

// Cells as the glue reads them: the cube, and per knot-plane normal the slab [key, key + 1].
struct TestCell {
  int cube;
  int keys[2];
};

// One normal, x + y, and its unused row; cube 0 holds the slabs [0, 1] and [1, 2] of it, cube 1
// the slab [0, 1]. The expected cells are worked out by hand from s = x + y.
template <class T>
void nearest_cell_cases() {
  static constexpr TestCell kCells[] = {{0, {0, 0}}, {1, {0, 0}}, {0, {1, 0}}};
  static constexpr int kNormals[2][2] = {{1, 1}, {0, 0}};
  const T on_plane[] = {T(0.5), T(0.5)};  // s = 1: in both slabs of cube 0, the first wins
  const T above[] = {T(0.75), T(0.75)};   // s = 1.5: only in [1, 2]
  const T below[] = {T(0.25), T(0.5)};    // s = 0.75: only in [0, 1]
  const T far[] = {T(0.5), T(2.5)};       // s = 3: violates [1, 2] by 1 and [0, 1] by 2
  EXPECT_EQ(nearest_cell(0, on_plane, kCells, kNormals), 0);
  EXPECT_EQ(nearest_cell(0, above, kCells, kNormals), 2);
  EXPECT_EQ(nearest_cell(0, below, kCells, kNormals), 0);
  EXPECT_EQ(nearest_cell(0, far, kCells, kNormals), 2);
  EXPECT_EQ(nearest_cell(1, above, kCells, kNormals), 1);   // the only cell of cube 1
  EXPECT_EQ(nearest_cell(2, above, kCells, kNormals), -1);  // a cube with no cell
}

TEST(CellGlue, NearestCellIsTheFirstOfTheLeastSlabViolation) {
  nearest_cell_cases<float>();
  nearest_cell_cases<double>();
}

// The memory a process may still take is bounded by its address-space limit
// (ulimit -v), not only by the machine's MemAvailable. A child sets RLIMIT_AS 256 MiB above what
// it has mapped; what it may still take must come out at most 256 MiB (and not 0).
TEST(AvailableMemory, AnAddressSpaceLimitBoundsIt) {
  const pid_t pid = ::fork();
  ASSERT_GE(pid, 0);
  if (pid == 0) {
    std::ifstream status("/proc/self/status");
    std::string line;
    double mapped = -1;
    while (std::getline(status, line))
      if (line.rfind("VmSize:", 0) == 0) mapped = std::stod(line.substr(7)) * 1024;
    constexpr double kRoom = 256.0 * 1024 * 1024;
    const rlimit limit{static_cast<rlim_t>(mapped + kRoom), static_cast<rlim_t>(mapped + kRoom)};
    if (mapped < 0 || ::setrlimit(RLIMIT_AS, &limit) != 0) ::_exit(2);
    const double available = boxgen::support::available_memory_bytes();
    ::_exit(available > 0 && available <= kRoom ? 0 : 1);
  }
  int status = 0;
  ASSERT_EQ(::waitpid(pid, &status, 0), pid);
  ASSERT_TRUE(WIFEXITED(status));
  EXPECT_EQ(WEXITSTATUS(status), 0) << "1: not bounded by RLIMIT_AS; 2: the test's set-up failed";
}

TEST(UnionFind, MergesExactlyTheUnitedSets) {
  UnionFind sets(8);
  sets.unite(0, 3);
  sets.unite(3, 5);
  sets.unite(6, 7);
  const std::vector<std::set<int>> expected = {{0, 3, 5}, {1}, {2}, {4}, {6, 7}};
  for (const auto& group : expected)
    for (int a : group)
      for (int b = 0; b < 8; ++b)
        EXPECT_EQ(sets.find(a) == sets.find(b), group.count(b) == 1) << a << ", " << b;
}

class OutputFile : public test::ScratchDirectoryTest {
 protected:
  OutputFile() : ScratchDirectoryTest("boxgen-support") {}

  static std::string read(const fs::path& p) {
    std::ifstream in(p, std::ios::binary);
    return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
  }
  static void write(const fs::path& p, const std::string& text) {
    std::ofstream(p, std::ios::binary) << text;
  }
  // Every file in the scratch directory, by name.
  std::set<std::string> names() const {
    std::set<std::string> out;
    for (const auto& e : fs::directory_iterator(dir_)) out.insert(e.path().filename().string());
    return out;
  }
  // Runs `body` in a child process and returns its wait status.
  template <class F>
  static int in_child(F body) {
    const pid_t pid = ::fork();
    if (pid == 0) {
      body();
      ::_exit(0);
    }
    int status = 0;
    ::waitpid(pid, &status, 0);
    return status;
  }
};

TEST_F(OutputFile, PendingOutputReplacesTheTargetOnlyOnCommit) {
  const fs::path target = dir_ / "a.txt";
  write(target, "old");
  {
    PendingOutput out(target);
    std::fputs("new", out.file());
    EXPECT_EQ(read(target), "old");  // nothing visible before commit
  }
  EXPECT_EQ(read(target), "old");  // abandoned by the destructor
  EXPECT_EQ(names(), std::set<std::string>{"a.txt"});
  {
    PendingOutput out(target);
    std::fputs("new", out.file());
    out.commit();
  }
  EXPECT_EQ(read(target), "new");
  EXPECT_EQ(names(), std::set<std::string>{"a.txt"});
}

TEST_F(OutputFile, AnOutputThatIsAnInputIsRefusedBeforeAnyWork) {
  const fs::path input = dir_ / "in.nrrd";
  write(input, "volume");
  fs::create_symlink(input, dir_ / "link.png");
  const std::vector<fs::path> inputs = {input};
  EXPECT_THROW(PendingOutput(dir_ / "link.png", inputs), OutputFileError);
  EXPECT_THROW((void)check_output_file(input, inputs), OutputFileError);
  EXPECT_EQ(read(input), "volume");
}

TEST_F(OutputFile, AFullDiskLeavesEveryFileOfASetAsItWas) {
  write(dir_ / "h.hpp", "old evaluator");
  write(dir_ / "h_prefilters.hpp", "old prefilters");
  // A file size limit makes the second file's write fail as a full disk does (EFBIG).
  const int status = in_child([&] {
    std::signal(SIGXFSZ, SIG_IGN);
    const rlimit limit{1000, 1000};
    ::setrlimit(RLIMIT_FSIZE, &limit);
    const std::vector<NamedText> set = {{"h.hpp", "new evaluator"},
                                        {"h_prefilters.hpp", std::string(100000, 'x')}};
    try {
      write_file_set(dir_, set);
    } catch (const OutputFileError&) {
      ::_exit(7);
    }
  });
  ASSERT_TRUE(WIFEXITED(status));
  EXPECT_EQ(WEXITSTATUS(status), 7) << "the write should have failed";
  EXPECT_EQ(read(dir_ / "h.hpp"), "old evaluator");
  EXPECT_EQ(read(dir_ / "h_prefilters.hpp"), "old prefilters");
  EXPECT_EQ(names(), (std::set<std::string>{"h.hpp", "h_prefilters.hpp"}));
}

TEST_F(OutputFile, ASetWithAnUnwritableMemberWritesNothing) {
  fs::create_directory(dir_ / "b.hpp");  // a directory where a file should go
  const std::vector<NamedText> set = {{"a.hpp", "a"}, {"b.hpp", "b"}};
  EXPECT_THROW(write_file_set(dir_, set), OutputFileError);
  EXPECT_EQ(names(), std::set<std::string>{"b.hpp"});
}

TEST_F(OutputFile, TwoWritersOfOneSetNeverMixTheirFiles) {
  for (int round = 0; round < 40; ++round) {
    std::vector<pid_t> writers;
    for (char who : {'A', 'B'}) {
      const pid_t pid = ::fork();
      if (pid == 0) {
        const std::string text(20000, who);
        const std::vector<NamedText> set = {{"h.hpp", text}, {"h_prefilters.hpp", text}};
        write_file_set(dir_, set);
        ::_exit(0);
      }
      writers.push_back(pid);
    }
    for (pid_t pid : writers) {
      int status = 0;
      ::waitpid(pid, &status, 0);
      ASSERT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) == 0);
    }
    ASSERT_EQ(read(dir_ / "h.hpp"), read(dir_ / "h_prefilters.hpp")) << "round " << round;
    ASSERT_EQ(names(), (std::set<std::string>{"h.hpp", "h_prefilters.hpp"}));
  }
}

TEST_F(OutputFile, ASignalRemovesThePendingTemporaries) {
  for (int signal : {SIGINT, SIGTERM, SIGHUP}) {
    const int status = in_child([&] {
      handle_signals();
      PendingOutput out(dir_ / "out.nrrd");
      std::fputs("half", out.file());
      std::fflush(out.file());
      std::raise(signal);
    });
    ASSERT_TRUE(WIFSIGNALED(status)) << "signal " << signal;
    EXPECT_EQ(WTERMSIG(status), signal);
    EXPECT_TRUE(names().empty()) << "signal " << signal << " left " << *names().begin();
  }
}

// A signal between the two renames of a set left a new h.hpp beside the old
// h_prefilters.hpp. The writer stops itself there (the test hook raises SIGSTOP), the signal is
// sent, and the writer goes on: SIGINT, SIGTERM and SIGHUP are held until both renames are done;
// SIGKILL cannot be held, and the next write of a set into the folder completes the first one.
TEST_F(OutputFile, ASignalBetweenTheRenamesOfASetNeverSplitsIt) {
  for (int signal : {SIGINT, SIGTERM, SIGHUP, SIGKILL}) {
    write(dir_ / "h.hpp", "old");
    write(dir_ / "h_prefilters.hpp", "old");
    const pid_t pid = ::fork();
    if (pid == 0) {
      handle_signals();
      set_between_renames_hook_for_tests([] { std::raise(SIGSTOP); });
      const std::vector<NamedText> set = {{"h.hpp", "new"}, {"h_prefilters.hpp", "new"}};
      write_file_set(dir_, set);
      ::_exit(0);
    }
    int status = 0;
    ASSERT_EQ(::waitpid(pid, &status, WUNTRACED), pid);
    ASSERT_TRUE(WIFSTOPPED(status)) << "the writer did not reach its renames";
    EXPECT_EQ(read(dir_ / "h.hpp"), "new");  // stopped between the two renames
    EXPECT_EQ(read(dir_ / "h_prefilters.hpp"), "old");
    ::kill(pid, signal);
    ::kill(pid, SIGCONT);
    ASSERT_EQ(::waitpid(pid, &status, 0), pid);
    ASSERT_TRUE(WIFSIGNALED(status)) << "signal " << signal;
    EXPECT_EQ(WTERMSIG(status), signal);
    if (signal == SIGKILL) {
      EXPECT_EQ(read(dir_ / "h_prefilters.hpp"), "old");  // what no process can prevent
      const std::vector<NamedText> other = {{"other.hpp", "x"}};
      write_file_set(dir_, other);
      fs::remove(dir_ / "other.hpp");
    }
    EXPECT_EQ(read(dir_ / "h.hpp"), "new") << "signal " << signal;
    EXPECT_EQ(read(dir_ / "h_prefilters.hpp"), "new") << "signal " << signal;
    EXPECT_EQ(names(), (std::set<std::string>{"h.hpp", "h_prefilters.hpp"})) << "signal " << signal;
  }
}

TEST_F(OutputFile, ALaterWriteRemovesTheLeftoversOfAKilledWriter) {
  // A process that has ended (and been reaped): its pid names no process now.
  const pid_t gone = ::fork();
  if (gone == 0) ::_exit(0);
  ::waitpid(gone, nullptr, 0);
  const std::string stale = ".out.nrrd.tmp-" + std::to_string(gone) + "-0";
  const std::string live = ".out.nrrd.tmp-" + std::to_string(::getppid()) + "-0";
  write(dir_ / stale, "left by SIGKILL");
  write(dir_ / live, "another writer at work");
  write_output_file(dir_ / "out.nrrd", [](std::FILE* f) { return std::fputs("v", f) >= 0; });
  EXPECT_EQ(names(), (std::set<std::string>{"out.nrrd", live}));
}

TEST_F(OutputFile, AClosedPipeIsAnErrorNotADeadProcess) {
  const int status = in_child([] {
    handle_signals();
    int ends[2];
    if (::pipe(ends) != 0) ::_exit(2);
    ::close(ends[0]);
    const bool failed = ::write(ends[1], "x", 1) < 0 && errno == EPIPE;
    ::_exit(failed ? 5 : 6);
  });
  ASSERT_TRUE(WIFEXITED(status)) << "killed by signal " << WTERMSIG(status);
  EXPECT_EQ(WEXITSTATUS(status), 5);
}

// The one parser of lattices (the generator's and the runtime's): every spelling, one wording.
TEST(LatticeText, NamesInAnyCaseAndRowsWithBlanksOrCommas) {
  EXPECT_EQ(parse_lattice_text(" BCC ", 3, "x", 1000).name, "bcc");
  EXPECT_EQ(parse_lattice_text("Cartesian", 2, "x", 1000).name, "cartesian");
  const IntegerRows g{{2, 0, 0}, {0, 2, 0}, {1, 1, 1}};
  for (const char* text :
       {"2,0,0; 0,2,0; 1,1,1", "2 0 0;0 2 0;1 1 1;", "2, 0 ,0;\n0 2 0;\t1,1,+1 ;"}) {
    const LatticeText l = parse_lattice_text(text, 3, "x", 1000);
    EXPECT_TRUE(l.name.empty()) << text;
    EXPECT_EQ(l.rows, g) << text;
  }
}

TEST(LatticeText, EachMistakeHasOneLine) {
  struct Case {
    const char* text;
    int dimension;  // of the directions
    const char* message;
  };
  const Case cases[] = {
      {"", 3,
       "empty lattice: expected bcc, fcc, cartesian or the rows of G such as '1,1,0; 1,0,1; "
       "0,1,1'"},
      {"hex", 3,
       "unknown lattice 'hex': expected bcc, fcc, cartesian or the rows of G such as '1,1,0; "
       "1,0,1; 0,1,1'"},
      {"bcc", 2, "the bcc lattice is 3-dimensional but the directions are 2-dimensional"},
      {"1,0; 0,1", 3, "the lattice is 2-dimensional but the directions are 3-dimensional"},
      {"1,0,0; 0,1,0", 3,
       "the lattice generator must be square: got 2 rows of 3 entries, expected 3 rows"},
      {"1,0,0; 0,1,0; 0,0,1; 1,1,1", 3, "4 lattice rows given: at most 3 are supported"},
      {"1,0,0; 0,1,0; 0,0,x", 3,
       "invalid lattice: lattice row 3 has the entry 'x', which is not an integer"},
      {"1,0,0; 0,1,0; 0,0,1001", 3,
       "lattice row 3 has the entry '1001', which is too large for a lattice generator: entries "
       "must be at most 1000 in magnitude"},
      {"1,0,0;; 0,0,1", 3, "invalid lattice: lattice row 2 is empty (two ';' in a row?)"},
      {"1,,0; 0,1,0; 0,0,1", 3,
       "invalid lattice: lattice row 1 ('1,,0') has an empty entry (stray ',')"},
      {"1,0,0; 0,1; 0,0,1", 3,
       "invalid lattice: lattice row 2 has 2 entries but lattice row 1 has 3; all must have the "
       "same dimension"},
  };
  for (const Case& c : cases) {
    const std::string because =
        "the directions are " + std::to_string(c.dimension) + "-dimensional";
    try {
      (void)parse_lattice_text(c.text, c.dimension, because, 1000);
      ADD_FAILURE() << c.text << ": no error";
    } catch (const TextError& e) {
      EXPECT_STREQ(e.what(), c.message) << c.text;
    }
  }
}

}  // namespace
}  // namespace boxgen::support
