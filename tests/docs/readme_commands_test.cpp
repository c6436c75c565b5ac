// Every command line README.md shows runs, and prints what the README says it prints.
//
// The convention in README.md: in a fenced block marked ```sh, a line that starts with `boxgen `
// or `boxrecon `, or pipes into one (`printf ... | boxrecon eval ...`), is a command; the test
// runs these lines in order, each with /bin/sh in one fresh directory (so a later command reads the
// files of an earlier one), with the build's boxgen and boxrecon first on PATH. Every command must
// exit with 0. Other lines (set-up, cmake) are not run. A ```text block that follows a ```sh block
// (blank lines between them allowed) is the stdout of that block's commands, compared line by
// line (trailing blanks aside); a line `...` in it stands for any number of lines (times, long
// listings). The README's commands use small sizes so that this test stays fast.
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <string>
#include <vector>

#include "markdown.h"
#include "run_process.h"

#ifndef BOXGEN_SOURCE_DIR
#error "BOXGEN_SOURCE_DIR must name the source tree (set by tests/docs/CMakeLists.txt)"
#endif
#if !defined(BOXGEN_EXE) || !defined(BOXRECON_EXE)
#error "BOXGEN_EXE and BOXRECON_EXE must name the programs (set by tests/docs/CMakeLists.txt)"
#endif

namespace boxgen::test {
namespace {

namespace fs = std::filesystem;

struct Command {
  int line = 0;  // in README.md
  std::string text;
};

struct Example {
  std::vector<Command> commands;
  bool has_output = false;
  int output_line = 0;              // the opening fence of the ```text block
  std::vector<std::string> output;  // its lines
};

bool is_command(const std::string& line) {
  return starts_with(line, "boxgen ") || starts_with(line, "boxrecon ") ||
         line.find("| boxgen ") != std::string::npos ||
         line.find("| boxrecon ") != std::string::npos;
}

bool blank_between(const std::vector<std::string>& lines, int after, int before) {
  for (int n = after + 1; n < before; ++n)
    if (lines[n - 1].find_first_not_of(" \t") != std::string::npos) return false;
  return true;
}

// The ```sh blocks with at least one command, each with the ```text block that follows it.
std::vector<Example> examples_of(const std::vector<std::string>& lines) {
  const std::vector<FencedBlock> blocks = fenced_blocks(lines);
  std::vector<Example> examples;
  for (std::size_t b = 0; b < blocks.size(); ++b) {
    if (blocks[b].info != "sh") continue;
    Example example;
    std::string pending;  // a command continued with a trailing backslash
    int pending_line = 0;
    for (std::size_t i = 0; i < blocks[b].lines.size(); ++i) {
      std::string line = blocks[b].lines[i];
      const int number = blocks[b].open_line + 1 + static_cast<int>(i);
      if (pending.empty() && !is_command(line)) continue;
      if (pending.empty()) pending_line = number;
      const bool continued = !line.empty() && line.back() == '\\';
      if (continued) line.pop_back();
      pending += line;
      if (continued) continue;
      example.commands.push_back({pending_line, pending});
      pending.clear();
    }
    if (example.commands.empty()) continue;
    if (b + 1 < blocks.size() && blocks[b + 1].info == "text" &&
        blank_between(lines, blocks[b].close_line, blocks[b + 1].open_line)) {
      example.has_output = true;
      example.output_line = blocks[b + 1].open_line;
      example.output = blocks[b + 1].lines;
    }
    examples.push_back(example);
  }
  return examples;
}

std::string without_trailing_blanks(const std::string& s) {
  return s.substr(0, s.find_last_not_of(" \t") + 1);
}

// Does `actual` match `expected`, where an expected line "..." matches any run of lines? Trailing
// blanks do not count (editors strip them from the README; tables pad their columns).
bool matches(const std::vector<std::string>& expected, std::size_t e,
             const std::vector<std::string>& actual, std::size_t a) {
  if (e == expected.size()) return a == actual.size();
  if (expected[e] == "...") {
    for (std::size_t skip = a; skip <= actual.size(); ++skip)
      if (matches(expected, e + 1, actual, skip)) return true;
    return false;
  }
  return a < actual.size() &&
         without_trailing_blanks(expected[e]) == without_trailing_blanks(actual[a]) &&
         matches(expected, e + 1, actual, a + 1);
}

TEST(ReadmeCommands, TheReaderFindsCommandsAndTheirOutput) {
  const std::vector<std::string> md = split_lines(
      "text\n```sh\nbash scripts/main.sh\n```\n```sh\nboxgen presets\n# comment\n"
      "printf '0 0 0\\n' | boxrecon eval --points - \\\n  --filter m7\n```\n\n```text\nm7\n...\n"
      "```\n```sh\nboxrecon sample --n 9\n```\nprose\n```text\nnot its output\n```\n");
  const auto examples = examples_of(md);
  ASSERT_EQ(examples.size(), 2U);
  ASSERT_EQ(examples[0].commands.size(), 2U);
  EXPECT_EQ(examples[0].commands[0].text, "boxgen presets");
  EXPECT_EQ(examples[0].commands[0].line, 6);
  EXPECT_EQ(examples[0].commands[1].text,
            "printf '0 0 0\\n' | boxrecon eval --points -   --filter m7");
  EXPECT_TRUE(examples[0].has_output);
  EXPECT_EQ(examples[0].output, (std::vector<std::string>{"m7", "..."}));
  EXPECT_FALSE(examples[1].has_output);

  EXPECT_TRUE(matches({"a", "...", "d"}, 0, {"a", "b", "c", "d"}, 0));
  EXPECT_TRUE(matches({"a", "..."}, 0, {"a"}, 0));
  EXPECT_FALSE(matches({"a", "...", "d"}, 0, {"a", "b"}, 0));
  EXPECT_FALSE(matches({"a", "b"}, 0, {"a", "c"}, 0));
  EXPECT_TRUE(matches({"a", "b"}, 0, {"a  ", "b"}, 0));
}

TEST(ReadmeCommands, EveryCommandRunsAndPrintsWhatTheReadmeShows) {
  const std::vector<std::string> readme =
      split_lines(read_text_file(std::string(BOXGEN_SOURCE_DIR) + "/README.md"));
  const std::vector<Example> examples = examples_of(readme);
  std::size_t commands = 0;
  for (const auto& e : examples) commands += e.commands.size();
  ASSERT_GE(commands, 8U) << "README.md's tour shows its commands in ```sh blocks";

  const fs::path dir = fs::temp_directory_path() / ("boxgen-readme-" + std::to_string(::getpid()));
  fs::remove_all(dir);
  fs::create_directories(dir);
  const std::string path = fs::path(BOXGEN_EXE).parent_path().string() + ":" +
                           fs::path(BOXRECON_EXE).parent_path().string();
  for (const Example& example : examples) {
    std::string out;
    for (const Command& c : example.commands) {
      const std::string script =
          "cd '" + dir.string() + "' && PATH='" + path + "':\"$PATH\" && export PATH && " + c.text;
      const ProcessResult r = run_process("/bin/sh", {"-c", script}, std::chrono::seconds(300));
      EXPECT_TRUE(r.exited && r.exit_code == 0)
          << "README.md:" << c.line << ": `" << c.text << "` failed\n"
          << describe({c.text}, r);
      out += r.out;
    }
    if (!example.has_output) continue;
    const std::vector<std::string> actual = split_lines(out);
    EXPECT_TRUE(matches(example.output, 0, actual, 0))
        << "README.md:" << example.output_line << ": the output shown is not what `"
        << example.commands.back().text << "` (and the commands before it in its block) print. "
        << "Update the ```text block (a line `...` skips any lines) to:\n"
        << out;
  }
  fs::remove_all(dir);
}

// The README is a user's guide (what, set-up, a tour, dependencies, links); reference and
// measurements live in docs/.
TEST(ReadmeCommands, TheReadmeStaysAShortGuide) {
  const auto lines = split_lines(read_text_file(std::string(BOXGEN_SOURCE_DIR) + "/README.md"));
  EXPECT_LT(lines.size(), 350U) << "README.md has " << lines.size()
                                << " lines: move reference material to the pages of docs/";
}

}  // namespace
}  // namespace boxgen::test
