// The system's C++ compiler, and the runtime engine a filter's shared object is compiled against
// (docs/runtime.md "Filters from any SPEC").
#pragma once
#include <filesystem>
#include <string>
#include <vector>

namespace boxgen::loader {

struct CompileOptions;

struct Toolchain {
  std::string compiler;            // absolute path
  std::string version;             // the first line of `compiler --version`
  std::vector<std::string> flags;  // every argument before the source
  std::filesystem::path
      include_dir;  // holds runtime/, support/ (the build tree or <prefix>/include/boxgen)
  std::filesystem::path archive;       // the runtime's static library the object links
  std::vector<std::string> libraries;  // after the archive
  // What the cache key needs to know about all this: compiler, version, flags, and the engine
  // (the archive's size and modification time: a rebuilt runtime is a new engine).
  std::string identity() const;
};

// The compiler (CompileOptions::compiler, else BOXGEN_CXX, else the one this build used, else
// c++ or g++ on PATH) and the engine beside the library that holds this code. Throws LoadError
// (one line) when there is no compiler, naming what to install, or no engine.
Toolchain find_toolchain(const CompileOptions& options);

// Compiles `source` (C++) into the shared object `output`. On failure throws LoadError naming
// `what` and the log file, where the compiler's messages stay; on success the log is removed.
void compile_shared_object(const Toolchain& toolchain, const std::filesystem::path& source,
                           const std::filesystem::path& output, const std::filesystem::path& log,
                           const std::string& what);

}  // namespace boxgen::loader
