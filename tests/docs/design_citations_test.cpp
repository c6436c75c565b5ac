// Every citation of the design document resolves: a source file that cites a section writes
// "docs/design.md §N" (or "§N-§M, §K"), and docs/design.md has a heading "## N. ..." for each
// cited N. A bare "design.md" (the old, out-of-tree notes) or a section that does not exist fails.
// Markdown files may also name docs/design.md without a section.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#ifndef BOXGEN_SOURCE_DIR
#error "BOXGEN_SOURCE_DIR must name the source tree (set by tests/docs/CMakeLists.txt)"
#endif

namespace {

namespace fs = std::filesystem;
const std::string kCitation = "docs/design.md";
const std::string kSection = "\xC2\xA7";  // §, UTF-8

std::set<int> sections_of(const std::string& design) {
  std::set<int> out;
  std::istringstream in(design);
  std::string line;
  while (std::getline(in, line)) {
    if (line.rfind("## ", 0) != 0) continue;
    std::size_t digits = 3;
    while (digits < line.size() && std::isdigit(static_cast<unsigned char>(line[digits]))) ++digits;
    if (digits > 3 && digits < line.size() && line[digits] == '.')
      out.insert(std::stoi(line.substr(3, digits - 3)));
  }
  return out;
}

// Problems with the citations on one line ("" when there are none).
std::string check_line(const std::string& line, const std::set<int>& sections, bool markdown) {
  std::string problems;
  for (std::size_t at = line.find("design.md"); at != std::string::npos;
       at = line.find("design.md", at + 1)) {
    const std::size_t start = at >= 5 ? at - 5 : 0;
    if (at < 5 || line.compare(start, kCitation.size(), kCitation) != 0) {
      problems += "cites design.md outside docs/; ";
      continue;
    }
    // The run of section numbers after the citation: " §3", " §3-§5, §7".
    std::size_t p = at + 9;
    int cited = 0;
    while (p + 1 < line.size()) {
      std::size_t q = p;
      while (q < line.size() && (line[q] == ' ' || line[q] == ',' || line[q] == '-')) ++q;
      if (line.compare(q, kSection.size(), kSection) != 0) break;
      q += kSection.size();
      std::size_t end = q;
      while (end < line.size() && std::isdigit(static_cast<unsigned char>(line[end]))) ++end;
      if (end == q) {
        problems += "a section sign without a number; ";
        break;
      }
      const int n = std::stoi(line.substr(q, end - q));
      if (!sections.count(n)) problems += "section " + std::to_string(n) + " does not exist; ";
      ++cited;
      p = end;
    }
    if (cited == 0 && !markdown) problems += "cites docs/design.md without a section; ";
  }
  return problems;
}

TEST(DesignCitations, TheCheckerCatchesBadCitations) {
  const std::set<int> sections{1, 2, 3, 5, 7};
  EXPECT_EQ(check_line("// see (docs/design.md §3-§5, §7)", sections, false), "");
  EXPECT_EQ(check_line("no citation here", sections, false), "");
  EXPECT_NE(check_line("// see design.md 7", sections, false), "");
  EXPECT_NE(check_line("// see docs/design.md §4", sections, false), "");
  EXPECT_NE(check_line("// see docs/design.md 3", sections, false), "");
  EXPECT_NE(check_line("// see docs/design.md §3, §9", sections, false), "");
  EXPECT_EQ(check_line("see [the design](docs/design.md).", sections, true), "");
  EXPECT_EQ(sections_of("# t\n## 1. A\ntext\n## 12. B\n### 3. not a section\n## x. no\n"),
            (std::set<int>{1, 12}));
}

TEST(DesignCitations, EveryCitationInTheTreeResolves) {
  const fs::path root = BOXGEN_SOURCE_DIR;
  std::ifstream design_file(root / "docs" / "design.md");
  ASSERT_TRUE(design_file) << "docs/design.md is missing";
  const std::string design((std::istreambuf_iterator<char>(design_file)),
                           std::istreambuf_iterator<char>());
  const std::set<int> sections = sections_of(design);
  ASSERT_FALSE(sections.empty());
  // The sections are numbered 1..N without gaps.
  EXPECT_EQ(*sections.begin(), 1);
  EXPECT_EQ(*sections.rbegin(), static_cast<int>(sections.size()));

  std::vector<fs::path> files{root / "README.md", root / "CMakeLists.txt"};
  for (const auto& entry : fs::directory_iterator(root / "docs"))  // the other pages cite it too
    if (entry.path().extension() == ".md" && entry.path().filename() != "design.md")
      files.push_back(entry.path());
  const std::set<std::string> extensions{".h",   ".hpp", ".cpp", ".fmt", ".cmake",
                                         ".txt", ".sh",  ".md",  ".in",  ".json"};
  for (const char* dir : {"apps", "bench", "cmake", "examples", "frontend", "fuzz", "generated",
                          "generator", "runtime", "scripts", "support", "templates", "tests"}) {
    if (!fs::exists(root / dir)) continue;
    for (const auto& entry : fs::recursive_directory_iterator(root / dir))
      if (entry.is_regular_file() && extensions.count(entry.path().extension().string()))
        files.push_back(entry.path());
  }
  int citations = 0;
  for (const auto& file : files) {
    if (!fs::exists(file) || file.filename() == "design_citations_test.cpp")
      continue;  // its own examples
    std::ifstream in(file);
    std::string line;
    for (int number = 1; std::getline(in, line); ++number) {
      if (line.find("design.md") == std::string::npos) continue;
      ++citations;
      const std::string problems = check_line(line, sections, file.extension() == ".md");
      EXPECT_EQ(problems, "") << fs::relative(file, root).string() << ":" << number << ": " << line;
    }
  }
  EXPECT_GT(citations, 30) << "the sources cite the design document throughout";
}

}  // namespace
