// The name of an emitted evaluator (`boxgen emit --name`, EmissionRequest::name): it becomes the
// namespace boxgen::generated::NAME, the files NAME.hpp and NAME_prefilters.hpp, and the prefix
// of the GLSL and CUDA functions, so it must compile wherever the evaluator is included beside
// the usual C and C++ headers. Checked before anything is derived (docs/cli.md, `--name`).
#pragma once
#include <string>

namespace boxgen::generator {

inline constexpr std::size_t kMaxEvaluatorName = 64;

// Throws InputError, one line naming the rule, unless `name` is: a C++ identifier of at most
// kMaxEvaluatorName characters; not a keyword, not reserved in C++ ('__', '_' and a capital) or
// GLSL ('gl_'); not a name the emitted code itself declares or refers to (Traits, kLattice,
// locate, std, ...: read from the templates); not in capitals only (the names of macros, which
// the C and C++ headers define by the hundred: FLT_MAX, BUFSIZ, RAND_MAX, MAXFLOAT); not one of
// the lowercase macros of those headers (errno, assert, stdin, si_pid, ...).
void check_evaluator_name(const std::string& name);

}  // namespace boxgen::generator
