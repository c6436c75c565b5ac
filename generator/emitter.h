// Emission (design.md 7, issue 4): the generator's tables and polynomial code, filled into the
// fmt templates of templates/ to make a self-contained C++ evaluator header for one spline.
#pragma once
#include <string>

#include "generator/analysis.h"

namespace boxgen {

inline constexpr const char* kGeneratorVersion = "boxgen 0.1.0";

// How the reference polynomials are written out. `monomial`: per-monomial linear combinations
// of the stencil values, then a sum over powers (the only strategy so far; the switch exists so
// the performance work can add Horner/CSE and BB forms behind the same interface).
enum class EmissionStrategy { Monomial };

struct EmittedFile {
  std::string filename;
  std::string text;
};

struct EmissionRequest {
  std::string name;     // C++ identifier: the namespace boxgen::generated::<name>
  std::string command;  // the command that reproduces the file, for its header
  EmissionStrategy strategy = EmissionStrategy::Monomial;
};

// <name>.hpp (evaluator) and <name>_prefilters.hpp (Q^I on shells 0,1 and Q^II on 0,1,2 where
// they exist). Throws InputError for a name that is not a C++ identifier.
std::vector<EmittedFile> emit(const Analysis& analysis, const EmissionRequest& request);

// Writes the files into `directory` (each through a temporary file and a rename).
void write_files(const std::vector<EmittedFile>& files, const std::string& directory);

}  // namespace boxgen
