// Emission (docs/design.md §11): the generator's tables and polynomial code, filled into the
// fmt templates of templates/ to make a self-contained C++ evaluator header for one spline.
#pragma once
#include <string>

#include "boxgen/version.h"
#include "generator/analysis.h"
#include "generator/polynomial_code.h"

namespace boxgen {

inline constexpr const char* kGeneratorVersion = kVersionBanner;  // boxgen/version.h (CMake)


struct EmittedFile {
  std::string filename;
  std::string text;
};

struct EmissionRequest {
  std::string name;     // C++ identifier: the namespace boxgen::generated::<name>
  std::string command;  // the command that reproduces the file, for its header
  EmissionStrategy strategy = EmissionStrategy::Horner;  // see generator/polynomial_code.h
};

// <name>.hpp (evaluator) and <name>_prefilters.hpp (Q^I on shells 0,1 and Q^II on 0,1,2 where
// they exist). Throws InputError for a name that is not a C++ identifier.
std::vector<EmittedFile> emit(const Analysis& analysis, const EmissionRequest& request);

// Writes the files into `directory` (each through a temporary file and a rename).
void write_files(const std::vector<EmittedFile>& files, const std::string& directory);

}  // namespace boxgen
