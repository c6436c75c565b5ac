// Error types of the generator. An InputError is a user's mistake (bad SPEC, lattice, point,
// argument): the CLI prints its message as one line and exits non-zero. Anything else that
// escapes is an internal failure (a broken invariant), reported differently.
#pragma once
#include <stdexcept>
#include <string>

namespace boxgen::generator {

struct InputError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

// A derivation or check that must hold mathematically did not: a bug, never user error.
struct InternalError : std::logic_error {
  using std::logic_error::logic_error;
};

[[noreturn]] void fail_input(const std::string& message);
[[noreturn]] void fail_internal(const std::string& message);

}  // namespace boxgen::generator
