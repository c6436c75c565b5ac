// libFuzzer target for points files (runtime/points_file.h): the bytes are parsed whole
// (parse_points) and read from a pipe in pieces of the first byte's size (read_points_stream, the
// path of `eval --points -`). Both must agree: the same points, or both an
// std::invalid_argument of one line. A crash, a sanitizer report or a disagreement is a bug.
#include <fcntl.h>
#include <unistd.h>

#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <stdexcept>
#include <string>
#include <string_view>
#include <thread>
#include <vector>

#include "runtime/points_file.h"

namespace {

using boxgen::runtime::Vec3;

void require(bool condition, const char* what) {
  if (condition) return;
  std::fprintf(stderr, "fuzz_points: invariant violated: %s\n", what);
  std::abort();
}

// The points, or the error message (marked by a leading '!').
template <class Read>
std::pair<std::vector<Vec3>, std::string> outcome(Read read) {
  try {
    return {read(), ""};
  } catch (const std::invalid_argument& e) {
    const std::string message = e.what();
    require(message.find('\n') == std::string::npos, "an error message of more than one line");
    return {{}, "!" + message};
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  const auto whole = outcome([&] { return boxgen::runtime::parse_points(text, "<fuzz>"); });
  int ends[2];
  require(::pipe(ends) == 0, "pipe");
  const std::size_t piece = size == 0 ? 1 : 1 + data[0] % 64;
  std::thread writer([&] {
    for (std::size_t at = 0; at < size; at += piece)
      (void)!::write(ends[1], data + at, std::min(piece, size - at));
    ::close(ends[1]);
  });
  const auto streamed =
      outcome([&] { return boxgen::runtime::read_points_stream(ends[0], "<fuzz>"); });
  writer.join();
  ::close(ends[0]);
  require(whole.second == streamed.second, "parse_points and read_points_stream disagree (error)");
  require(whole.first == streamed.first, "parse_points and read_points_stream disagree (points)");
  return 0;
}
