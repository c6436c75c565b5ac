// docs/cli.md documents every command and option of boxgen and boxrecon, and nothing else: the
// options each program's `--help` and each command's `--help` list are compared with the options
// docs/cli.md lists under that command's heading. A new option without documentation, a removed
// option still documented, or a command without a section fails with a message that says which
// line to add or remove where.
//
// The convention in docs/cli.md (also stated at its top): a command's section is headed by the
// command alone in backticks ("## `boxgen`", "### `boxgen analyze`"); its options are the rows of
// the section's tables whose first cell holds them in backticks (`--lattice L`, `-o, --output
// FILE`, `SPEC`). `-h, --help` is left out on both sides: every command has it.
#include <gtest/gtest.h>

#include <algorithm>
#include <cctype>
#include <map>
#include <set>
#include <sstream>
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

using Names = std::set<std::string>;

std::string lower(std::string s) {
  for (char& c : s) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return s;
}

// CLI11's help: a heading line ("Options:", "Positionals:", "Subcommands:"), then one entry per
// line indented by two spaces, the name(s) first ("-o,--output TEXT ...", "SPEC TEXT REQUIRED",
// "analyze   derive ..."). Returns the names listed under the heading, without -h and --help.
Names help_entries(const std::string& help, const std::string& heading) {
  Names names;
  bool inside = false;
  for (const std::string& line : split_lines(help)) {
    if (!line.empty() && line[0] != ' ') {
      inside = lower(line) == lower(heading) + ":";
      continue;
    }
    if (!inside || line.size() < 3 || line.compare(0, 2, "  ") != 0 || line[2] == ' ') continue;
    std::string first = line.substr(2, line.find(' ', 2) - 2);
    std::stringstream parts(first);
    for (std::string name; std::getline(parts, name, ',');)
      if (!name.empty() && name != "-h" && name != "--help") names.insert(name);
  }
  return names;
}

bool is_placeholder_name(const std::string& word) {  // a positional: SPEC, FILE
  return !word.empty() && std::all_of(word.begin(), word.end(), [](char c) {
    return std::isupper(static_cast<unsigned char>(c)) || c == '_';
  });
}

// The first cell of a table row "| a | b |": up to the first '|' not escaped as "\|".
std::string first_cell(const std::string& row) {
  std::size_t end = 1;
  while (end < row.size() && !(row[end] == '|' && row[end - 1] != '\\')) ++end;
  return row.substr(1, end - 1);
}

// The names a table row's first cell documents: in each backticked span, every word that starts
// with '-' (commas stripped), or the span's first word when it is a positional in capitals.
Names names_in_first_cell(const std::string& row) {
  Names names;
  for (const std::string& span : backticked(first_cell(row))) {
    std::stringstream words(span);
    std::string word;
    for (bool first = true; words >> word; first = false) {
      while (!word.empty() && word.back() == ',') word.pop_back();
      if (word.empty()) continue;
      if (word[0] == '-' || (first && is_placeholder_name(word))) names.insert(word);
    }
  }
  names.erase("-h");
  names.erase("--help");
  return names;
}

// docs/cli.md's sections: "boxgen" or "boxgen analyze" -> the names its tables document. A
// section is headed by a command alone in backticks and runs to the next heading.
std::map<std::string, Names> documented_commands(const std::string& markdown) {
  std::map<std::string, Names> sections;
  Names* current = nullptr;
  bool in_fence = false;
  for (const std::string& line : split_lines(markdown)) {
    if (starts_with(line, "```")) in_fence = !in_fence;
    if (in_fence) continue;
    if (starts_with(line, "#")) {
      current = nullptr;
      const std::size_t text = line.find_first_not_of('#');
      const std::string heading = text == std::string::npos ? "" : line.substr(text);
      const auto spans = backticked(heading);
      if (spans.size() == 1 && heading == " `" + spans[0] + "`") current = &sections[spans[0]];
      continue;
    }
    if (current && starts_with(line, "|")) {
      const Names names = names_in_first_cell(line);
      current->insert(names.begin(), names.end());
    }
  }
  return sections;
}

std::string help_of(const std::string& exe, const std::vector<std::string>& args) {
  const ProcessResult r = run_process(exe, args, std::chrono::seconds(60));
  if (!r.exited || r.exit_code != 0) return "";
  return r.out;
}

// The parts of a message, joined (one string, no temporaries per part).
template <class... Parts>
std::string concat(const Parts&... parts) {
  std::string out;
  ((out += parts), ...);
  return out;
}

std::string join(const Names& names) {
  std::string out;
  for (const auto& n : names) out += (out.empty() ? "" : ", ") + n;
  return out;
}

// Every difference between one command's --help and its section, as instructions.
std::string compare(const std::string& command, const Names& in_help, const Names& in_docs) {
  Names missing, extra;
  std::set_difference(in_help.begin(), in_help.end(), in_docs.begin(), in_docs.end(),
                      std::inserter(missing, missing.end()));
  std::set_difference(in_docs.begin(), in_docs.end(), in_help.begin(), in_help.end(),
                      std::inserter(extra, extra.end()));
  std::string problems;
  if (!missing.empty())
    problems += concat("`", command, " --help` lists ", join(missing),
                       ", which docs/cli.md does not document: add a table row for each (its name "
                       "in backticks in the first cell) to the section headed \"`",
                       command, "`\".\n");
  if (!extra.empty())
    problems += concat("docs/cli.md documents ", join(extra), " under \"`", command, "`\", but `",
                       command, " --help` does not list it: remove or rename the row.\n");
  return problems;
}

// The whole comparison for one program: its own options, its commands, each command's options.
std::string check_program(const std::string& program, const std::string& exe,
                          const std::map<std::string, Names>& docs) {
  const std::string help = help_of(exe, {"--help"});
  if (help.empty()) return "`" + program + " --help` failed\n";
  std::string problems;
  const auto own = docs.find(program);
  if (own == docs.end())
    problems += concat("docs/cli.md has no section headed \"## `", program,
                       "`\" (the program's own options)\n");
  else
    problems += compare(program, help_entries(help, "Options"), own->second);
  const Names commands = help_entries(help, "Subcommands");
  if (commands.empty()) problems += concat("`", program, " --help` lists no commands\n");
  for (const std::string& command : commands) {
    const std::string name = concat(program, " ", command);
    const auto section = docs.find(name);
    if (section == docs.end()) {
      problems += concat("`", program, " --help` lists the command `", command,
                         "`, but docs/cli.md has no section headed \"### `", name,
                         "`\": add one with a table of its options.\n");
      continue;
    }
    const std::string sub = help_of(exe, {command, "--help"});
    if (sub.empty()) {
      problems += concat("`", name, " --help` failed\n");
      continue;
    }
    Names in_help = help_entries(sub, "Options");
    const Names positionals = help_entries(sub, "Positionals");
    in_help.insert(positionals.begin(), positionals.end());
    problems += compare(name, in_help, section->second);
  }
  for (const auto& [name, names] : docs)
    if (starts_with(name, program + " ") && !commands.count(name.substr(program.size() + 1)))
      problems += concat("docs/cli.md has a section for `", name, "`, but `", program,
                         " --help` lists no such command: remove the section.\n");
  return problems;
}

TEST(CliReference, TheReadersFindOptionsInHelpAndInTheDocs) {
  const std::string help =
      "title\nUsage: x sub [OPTIONS] SPEC\n\nPositionals:\n  SPEC TEXT REQUIRED   spec\n\n"
      "Options:\n  -h,--help   help\n  -o,--output TEXT   out\n  --min FLOAT x 3   corner\n"
      "                      wrapped description --not-an-option\n\nSubcommands:\n"
      "  sample   sample it\n";
  EXPECT_EQ(help_entries(help, "Options"), (Names{"-o", "--output", "--min"}));
  EXPECT_EQ(help_entries(help, "Positionals"), (Names{"SPEC"}));
  EXPECT_EQ(help_entries(help, "Subcommands"), (Names{"sample"}));

  const std::string md =
      "# t\n## `x`\n| option | meaning |\n|---|---|\n| `--threads N` | cap |\n"
      "### `x sub`\ntext `--not-in-a-table`\n| `SPEC`, `--lattice L` | s |\n"
      "| `-o, --output FILE` | o `--not-first-cell` |\n| `-h, --help` | help |\n"
      "| `--of a\\|b` | c `--after-an-escaped-bar` |\n"
      "```sh\n| `--in-a-fence` |\n```\n### `x sub` options, more\n| `--not-a-command-heading` |\n";
  const auto docs = documented_commands(md);
  ASSERT_EQ(docs.size(), 2U);
  EXPECT_EQ(docs.at("x"), (Names{"--threads"}));
  EXPECT_EQ(docs.at("x sub"), (Names{"SPEC", "--lattice", "-o", "--output", "--of"}));

  // The comparison fails both ways, naming what to do.
  EXPECT_NE(compare("x sub", {"--new"}, {}).find("add a table row"), std::string::npos);
  EXPECT_NE(compare("x sub", {}, {"--old"}).find("remove or rename"), std::string::npos);
  EXPECT_EQ(compare("x sub", {"--a", "SPEC"}, {"SPEC", "--a"}), "");
}

TEST(CliReference, DocsCliMdListsEveryCommandAndOptionOfBoxgen) {
  const auto docs =
      documented_commands(read_text_file(std::string(BOXGEN_SOURCE_DIR) + "/docs/cli.md"));
  EXPECT_EQ(check_program("boxgen", BOXGEN_EXE, docs), "");
}

TEST(CliReference, DocsCliMdListsEveryCommandAndOptionOfBoxrecon) {
  const auto docs =
      documented_commands(read_text_file(std::string(BOXGEN_SOURCE_DIR) + "/docs/cli.md"));
  EXPECT_EQ(check_program("boxrecon", BOXRECON_EXE, docs), "");
}

}  // namespace
}  // namespace boxgen::test
