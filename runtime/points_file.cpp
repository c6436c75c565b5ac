#include "runtime/points_file.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <fmt/format.h>

#include <algorithm>
#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstring>
#include <stdexcept>

#include "support/available_memory.h"

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

// Lines are parsed as they arrive, so that memory follows the points kept, and a file that is
// not a points file (/dev/zero, an endless stream) is refused once a line or the point count
// passes its bound, instead of filling memory.
class PointsParser {
 public:
  explicit PointsParser(std::string_view name) : name_(name) {}

  void feed(std::string_view chunk) {
    while (!chunk.empty()) {
      const std::size_t newline = chunk.find('\n');
      const std::string_view piece = chunk.substr(0, newline);
      if (pending_.size() + piece.size() > kMaxPointsLineBytes)
        fail(number_ + 1, fmt::format("a line longer than {} bytes (is it a points file?)",
                                      kMaxPointsLineBytes));
      if (newline == std::string_view::npos) {
        pending_.append(piece);
        return;
      }
      if (pending_.empty()) {
        line(piece);
      } else {
        pending_.append(piece);
        line(pending_);
        pending_.clear();
      }
      chunk.remove_prefix(newline + 1);
    }
  }
  std::vector<Vec3> finish() && {
    if (!pending_.empty()) line(pending_);
    return std::move(points_);
  }

 private:
  [[noreturn]] void fail(std::size_t number, const std::string& why) const {
    throw std::invalid_argument(fmt::format("{}:{}: {}", printable(name_, 200), number, why));
  }

  void line(std::string_view text) {
    const std::size_t number = ++number_;
    if (number == 1 && text.starts_with("\xEF\xBB\xBF")) text.remove_prefix(3);  // UTF-8 BOM
    if (const std::size_t hash = text.find('#'); hash != std::string_view::npos)
      text = text.substr(0, hash);
    if (text.find('\0') != std::string_view::npos)
      fail(number, "expected three numbers 'x y z', found a NUL byte (is it a text file?)");
    Vec3 p{};
    std::string_view rest = text;
    int found = 0;
    for (std::string_view token = next_token(rest); !token.empty(); token = next_token(rest)) {
      if (found == 3)
        fail(number,
             fmt::format("expected three numbers 'x y z', found more ('{}')", printable(token)));
      double value = 0;
      if (!parse_number(token, value))
        fail(number,
             fmt::format("expected three numbers 'x y z', '{}' is not a number", printable(token)));
      if (!std::isfinite(value))
        fail(number, fmt::format("the coordinate '{}' is not finite", printable(token)));
      p[found++] = value;
    }
    if (found == 0) return;  // a blank or comment line
    if (found < 3) fail(number, fmt::format("expected three numbers 'x y z', found {}", found));
    if (points_.size() == limit_)
      fail(number, limit_ == kMaxPoints
                       ? fmt::format("more than {} points; split the file", kMaxPoints)
                       : fmt::format("more than {} points, the most whose {} bytes each fit in the "
                                     "memory this process may still take; split the file",
                                     limit_, kBytesPerPoint));
    points_.push_back(p);
  }

  std::string name_;
  std::size_t limit_ = max_points();
  std::string pending_;
  std::vector<Vec3> points_;
  std::size_t number_ = 0;
};

}  // namespace

std::size_t max_points() {
  const double available = support::available_memory_bytes();
  if (available <= 0) return kMaxPoints;
  return static_cast<std::size_t>(
      std::min(static_cast<double>(kMaxPoints), available / static_cast<double>(kBytesPerPoint)));
}

std::vector<Vec3> parse_points(std::string_view text, std::string_view name) {
  PointsParser parser(name);
  parser.feed(text);
  return std::move(parser).finish();
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
  return read_points_stream(fd, name);
}

std::vector<Vec3> read_points_stream(int fd, std::string_view name) {
  PointsParser parser(name);
  char buffer[65536];
  for (;;) {
    const ssize_t got = ::read(fd, buffer, sizeof buffer);
    if (got < 0 && errno == EINTR) continue;
    if (got < 0)
      throw std::invalid_argument(fmt::format("cannot read points file '{}': {}",
                                              printable(name, 200), std::strerror(errno)));
    if (got == 0) break;
    parser.feed(std::string_view(buffer, static_cast<std::size_t>(got)));
  }
  return std::move(parser).finish();
}

}  // namespace boxgen::runtime
