#include "runtime/points_file.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <fmt/format.h>

#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstring>
#include <stdexcept>

namespace boxgen::runtime {

namespace {

// Text from the user's file made fit for a one-line message.
std::string printable(std::string_view text, std::size_t limit = 60) {
  std::string out;
  for (char ch : text.substr(0, limit))
    out += (static_cast<unsigned char>(ch) < 0x20 || ch == 0x7f) ? '?' : ch;
  if (text.size() > limit) out += "...";
  return out;
}

bool is_blank(char ch) { return ch == ' ' || ch == '\t' || ch == '\r' || ch == '\v' || ch == '\f'; }

// The next whitespace-separated token of `line` (empty at the end).
std::string_view next_token(std::string_view& line) {
  std::size_t start = 0;
  while (start < line.size() && is_blank(line[start])) ++start;
  std::size_t end = start;
  while (end < line.size() && !is_blank(line[end])) ++end;
  const std::string_view token = line.substr(start, end - start);
  line.remove_prefix(end);
  return token;
}

bool parse_number(std::string_view token, double& value) {
  if (token.starts_with('+')) token.remove_prefix(1);
  std::chars_format format = std::chars_format::general;
  std::string_view digits = token;
  const bool negative = digits.starts_with('-');
  if (negative) digits.remove_prefix(1);
  if (digits.starts_with("0x") ||
      digits.starts_with("0X")) {  // from_chars takes hex without its prefix
    format = std::chars_format::hex;
    digits.remove_prefix(2);
    if (digits.starts_with('-')) return false;
  }
  const auto [end, error] =
      std::from_chars(digits.data(), digits.data() + digits.size(), value, format);
  if (error != std::errc() || end != digits.data() + digits.size()) return false;
  if (negative) value = -value;
  return true;
}

}  // namespace

std::vector<Vec3> parse_points(std::string_view text, std::string_view name) {
  if (text.starts_with("\xEF\xBB\xBF")) text.remove_prefix(3);  // UTF-8 byte order mark
  std::vector<Vec3> points;
  std::size_t number = 0;
  while (!text.empty()) {
    ++number;
    const std::size_t newline = text.find('\n');
    std::string_view line = text.substr(0, newline);
    text.remove_prefix(newline == std::string_view::npos ? text.size() : newline + 1);
    if (const std::size_t hash = line.find('#'); hash != std::string_view::npos)
      line = line.substr(0, hash);
    auto fail = [&](const std::string& why) {
      throw std::invalid_argument(fmt::format("{}:{}: {}", printable(name, 200), number, why));
    };
    if (line.find('\0') != std::string_view::npos)
      fail("expected three numbers 'x y z', found a NUL byte (is it a text file?)");
    Vec3 p{};
    std::string_view rest = line;
    int found = 0;
    for (std::string_view token = next_token(rest); !token.empty(); token = next_token(rest)) {
      if (found == 3)
        fail(fmt::format("expected three numbers 'x y z', found more ('{}')", printable(token)));
      double value = 0;
      if (!parse_number(token, value))
        fail(fmt::format("expected three numbers 'x y z', '{}' is not a number", printable(token)));
      if (!std::isfinite(value))
        fail(fmt::format("the coordinate '{}' is not finite", printable(token)));
      p[found++] = value;
    }
    if (found == 0) continue;  // a blank or comment line
    if (found < 3) fail(fmt::format("expected three numbers 'x y z', found {}", found));
    points.push_back(p);
  }
  return points;
}

std::vector<Vec3> read_points_file(const std::string& path) {
  const bool from_stdin = path == "-";
  const std::string name = from_stdin ? std::string("<stdin>") : path;
  auto fail = [&](const std::string& why) {
    throw std::invalid_argument(
        fmt::format("cannot read points file '{}': {}", printable(name, 200), why));
  };
  const int fd = from_stdin ? STDIN_FILENO : ::open(path.c_str(), O_RDONLY | O_CLOEXEC);
  if (fd < 0) fail(errno == ENOENT ? "no such file" : std::strerror(errno));
  struct Closer {
    int fd;
    bool owned;
    ~Closer() {
      if (owned) ::close(fd);
    }
  } closer{fd, !from_stdin};
  struct stat info {};
  if (::fstat(fd, &info) != 0) fail(std::strerror(errno));
  if (S_ISDIR(info.st_mode)) fail("it is a directory");
  std::string text;
  char buffer[65536];
  for (;;) {
    const ssize_t got = ::read(fd, buffer, sizeof buffer);
    if (got < 0 && errno == EINTR) continue;
    if (got < 0) fail(std::strerror(errno));
    if (got == 0) break;
    text.append(buffer, static_cast<std::size_t>(got));
  }
  return parse_points(text, name);
}

}  // namespace boxgen::runtime
