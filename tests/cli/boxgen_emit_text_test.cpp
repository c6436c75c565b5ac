// What `boxgen emit` pastes into the files it writes must compile (a SPEC,
// lattice or shell list given over several lines was pasted as it was into the first comment
// line, so the headers did not compile) and item 15 (a name the checks accept compiles beside
// the usual C and C++ headers). The emitted headers are compiled with the system's c++.
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include "cli_support.h"
#include "tests/support/scratch_directory.h"

namespace boxgen::test {
namespace {

class BoxgenEmitText : public ScratchDirectoryTest {
 protected:
  BoxgenEmitText() : ScratchDirectoryTest("boxgen-emit-text") {}
  std::string read(const std::string& name) const {
    std::ifstream in(dir_ / name);
    return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
  }
  // The evaluator NAME.hpp and NAME_prefilters.hpp, after the usual headers, compiled.
  ProcessResult compile(const std::string& name) const {
    std::ofstream(dir_ / "use.cpp")
        << "#include <cassert>\n#include <cerrno>\n#include <cfloat>\n#include <climits>\n"
           "#include <cmath>\n#include <csignal>\n#include <cstdio>\n#include <cstdlib>\n"
           "#include \""
        << name << ".hpp\"\n#include \"" << name << "_prefilters.hpp\"\nint main() {}\n";
    const std::vector<std::string> args = {"c++",
                                           "-std=c++20",
                                           "-fsyntax-only",
                                           "-I",
                                           BOXGEN_SOURCE_DIR,
                                           "-I",
                                           dir_.string(),
                                           (dir_ / "use.cpp").string()};
    return run_process("/usr/bin/env", args, std::chrono::seconds(120 * kSlowdown));
  }
};

TEST_F(BoxgenEmitText, ASpecOverSeveralLinesIsQuotedOnOneLineAndCompiles) {
  const std::vector<std::string> args = {
      "emit",   "1,0;\n0,1;\r\n\t1,1", "--lattice", "1,0;\n0,1",  "--shells", "1,\n0",
      "--name", "hex_lines",           "--out",     dir_.string()};
  const ProcessResult r = boxgen(args);
  ASSERT_TRUE(r.exited && r.exit_code == 0) << describe(args, r);
  const std::string header = read("hex_lines.hpp");
  const std::string first = header.substr(0, header.find('\n'));
  EXPECT_NE(first.find("from SPEC \"1,0; 0,1; 1,1\""), std::string::npos) << first;
  const ProcessResult built = compile("hex_lines");
  EXPECT_TRUE(built.exited && built.exit_code == 0) << describe({"c++"}, built);
  // The command each file names rewrites it byte for byte, run in its folder.
  const std::string marker = "// Reproduce with (in this file's folder): boxgen ";
  const std::size_t at = header.find(marker);
  ASSERT_NE(at, std::string::npos) << header.substr(0, 400);
  const std::string command =
      header.substr(at + marker.size(), header.find('\n', at) - at - marker.size());
  EXPECT_NE(command.find("--lattice \"1,0; 0,1\" "), std::string::npos) << command;
  EXPECT_NE(command.find("--shells 0,1"), std::string::npos) << command;
  const std::string prefilters = read("hex_lines_prefilters.hpp");
  std::filesystem::remove(dir_ / "hex_lines.hpp");
  std::filesystem::remove(dir_ / "hex_lines_prefilters.hpp");
  const std::vector<std::string> again = {"-c", "cd \"$0\" && \"$1\" " + command, dir_.string(),
                                          BOXGEN_EXE};
  const ProcessResult redo = run_process("/bin/sh", again, kDefaultTimeout);
  ASSERT_TRUE(redo.exited && redo.exit_code == 0) << describe(again, redo);
  EXPECT_EQ(read("hex_lines.hpp"), header);
  EXPECT_EQ(read("hex_lines_prefilters.hpp"), prefilters);
}

// Names near the refused ones (a capital, a digit, a macro's name in lowercase) compile.
TEST_F(BoxgenEmitText, AcceptedNamesCompileBesideTheUsualHeaders) {
  for (const std::string name : {"Maxfloat", "flt_max", "bufsiz", "traits", "gl3"}) {
    const std::vector<std::string> args = {"emit", "hex3", "--name", name, "--out", dir_.string()};
    const ProcessResult r = boxgen(args);
    ASSERT_TRUE(r.exited && r.exit_code == 0) << describe(args, r);
    const ProcessResult built = compile(name);
    EXPECT_TRUE(built.exited && built.exit_code == 0) << name << "\n" << describe({"c++"}, built);
  }
}

}  // namespace
}  // namespace boxgen::test
