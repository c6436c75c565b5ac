// Small Markdown readers for the documentation tests: a file's text, its fenced code blocks and
// the backticked spans of a line. Only what README.md and docs/*.md use is understood: fences of
// three backticks at the start of a line, with an optional info string ("sh", "text").
#pragma once
#include <fstream>
#include <iterator>
#include <stdexcept>
#include <string>
#include <vector>

namespace boxgen::test {

inline std::string read_text_file(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw std::runtime_error("cannot read " + path);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

inline std::vector<std::string> split_lines(const std::string& text) {
  std::vector<std::string> lines;
  std::size_t start = 0;
  while (start < text.size()) {
    std::size_t end = text.find('\n', start);
    if (end == std::string::npos) end = text.size();
    lines.push_back(text.substr(start, end - start));
    start = end + 1;
  }
  return lines;
}

inline bool starts_with(const std::string& s, const std::string& prefix) {
  return s.compare(0, prefix.size(), prefix) == 0;
}

struct FencedBlock {
  std::string info;   // the word after the opening fence: "sh", "text", ""
  int open_line = 0;  // 1-based line numbers of the two fences
  int close_line = 0;
  std::vector<std::string> lines;  // the lines between them
};

// Every fenced block, in order. An unclosed fence runs to the end of the file.
inline std::vector<FencedBlock> fenced_blocks(const std::vector<std::string>& lines) {
  std::vector<FencedBlock> blocks;
  FencedBlock* open = nullptr;
  for (std::size_t i = 0; i < lines.size(); ++i) {
    const std::string& line = lines[i];
    const int number = static_cast<int>(i) + 1;
    if (!starts_with(line, "```")) {
      if (open) open->lines.push_back(line);
      continue;
    }
    if (open) {
      open->close_line = number;
      open = nullptr;
      continue;
    }
    FencedBlock block;
    block.info = line.substr(3, line.find_first_of(" \t", 3) - 3);
    block.open_line = number;
    blocks.push_back(block);
    open = &blocks.back();
  }
  if (open) open->close_line = static_cast<int>(lines.size()) + 1;
  return blocks;
}

// The contents of the `...` spans of a line, in order.
inline std::vector<std::string> backticked(const std::string& line) {
  std::vector<std::string> spans;
  std::size_t at = line.find('`');
  while (at != std::string::npos) {
    const std::size_t end = line.find('`', at + 1);
    if (end == std::string::npos) break;
    spans.push_back(line.substr(at + 1, end - at - 1));
    at = line.find('`', end + 1);
  }
  return spans;
}

}  // namespace boxgen::test
