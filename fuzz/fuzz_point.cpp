// libFuzzer target for the number and point parsers (generator/rational.h): parse_rational and
// parse_point for n = 2 and 3. Every input must either parse or raise an InputError; a crash, a
// sanitizer report, any other exception or a value that does not survive a round trip is a bug.
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <string>
#include <string_view>

#include "generator/error.h"
#include "generator/rational.h"

namespace {

using namespace boxgen::generator;

void require(bool condition, const char* what) {
  if (condition) return;
  std::fprintf(stderr, "fuzz_point: invariant violated: %s\n", what);
  std::abort();
}

// The parsers repeat the user's text in their messages, so a message may only contain a line
// break the input brought in; one the parser adds itself is a bug.
template <class Parse>
void valid_or_input_error(std::string_view input, Parse parse) {
  try {
    parse();
  } catch (const InputError& e) {
    const std::string_view message = e.what();
    require(!message.empty(), "InputError message is empty");
    if (input.find_first_of("\r\n") == std::string_view::npos)
      require(message.find_first_of("\r\n") == std::string_view::npos,
              "InputError message spans several lines");
  } catch (const std::exception& e) {
    std::fprintf(stderr, "fuzz_point: unexpected exception: %s\n", e.what());
    std::abort();
  }
}

void check_round_trip(const Rational& r) {
  require(parse_rational(to_string(r)) == r, "to_string / parse_rational round trip");
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  valid_or_input_error(text, [&] { check_round_trip(parse_rational(text)); });
  for (int n : {2, 3})
    valid_or_input_error(text, [&] {
      const RatVec point = parse_point(text, n);
      require(static_cast<int>(point.size()) == n, "point has n coordinates");
      for (const auto& x : point) check_round_trip(x);
    });
  return 0;
}
