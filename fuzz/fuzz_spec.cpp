// libFuzzer target for the SPEC and lattice parsers (generator/spec.h). Every input must either
// parse into a valid spec or raise an InputError with a one-line message; a crash, a sanitizer
// report, any other exception or a spec that breaks its invariants is a bug.
// Input convention: the whole input is tried as a SPEC and as lattice text; if it contains '|',
// the part before is also tried as a SPEC with the part after as its --lattice.
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <string>
#include <string_view>

#include "generator/error.h"
#include "generator/spec.h"

namespace {

using namespace boxgen::generator;

void require(bool condition, const char* what) {
  if (condition) return;
  std::fprintf(stderr, "fuzz_spec: invariant violated: %s\n", what);
  std::abort();
}

template <class Parse>
void valid_or_input_error(Parse parse) {
  try {
    parse();
  } catch (const InputError& e) {
    const std::string_view message = e.what();
    require(!message.empty(), "InputError message is empty");
    require(message.find('\n') == std::string_view::npos &&
                message.find('\r') == std::string_view::npos,
            "InputError message spans more than one line");
  } catch (const std::exception& e) {
    std::fprintf(stderr, "fuzz_spec: unexpected exception: %s\n", e.what());
    std::abort();
  }
}

std::string rows_text(const IntColumns& rows) {
  std::string out;
  for (const auto& row : rows) {
    if (!out.empty()) out += ';';
    for (auto v : row) out += std::to_string(v) + ' ';
  }
  return out;
}

// What parse_spec promises about anything it accepts.
void check_spec(const BoxSplineSpec& spec) {
  const int n = spec.dimension();
  require(n == 2 || n == 3, "dimension is 2 or 3");
  require(spec.count() >= n && spec.count() <= kMaxDirections, "direction count within [n, 32]");
  require(spec.lattice.det_abs() > 0, "lattice is nonsingular");
  for (const auto& xi : spec.directions) {
    require(static_cast<int>(xi.size()) == n, "direction has n components");
    bool nonzero = false;
    for (auto v : xi) {
      require(v >= -64 && v <= 64, "components at most 64 in magnitude");
      nonzero = nonzero || v != 0;
    }
    require(nonzero, "no zero direction");
    require(spec.lattice.contains(xi), "direction lies in the lattice");
  }
  require(rank(spec.directions, n) == n, "directions span R^n");
  // The canonical text reproduces the spec.
  const BoxSplineSpec again =
      parse_spec(spec.directions_text(), rows_text(spec.lattice.generator_rows()));
  require(again.directions == spec.directions, "directions_text round trip");
  require(again.lattice.generator() == spec.lattice.generator(), "lattice rows round trip");
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  valid_or_input_error([&] { check_spec(parse_spec(text)); });
  if (const auto bar = text.find('|'); bar != std::string::npos)
    valid_or_input_error(
        [&] { check_spec(parse_spec(text.substr(0, bar), text.substr(bar + 1))); });
  for (int n : {2, 3})
    valid_or_input_error([&] {
      const Lattice lattice = parse_lattice(text, n);
      require(lattice.dimension() == n && lattice.det_abs() > 0,
              "parsed lattice has the requested dimension");
    });
  return 0;
}
