// The system's C++ compiler, and the runtime engine a filter's shared object is compiled against
// (docs/runtime.md "Filters from any SPEC").
#pragma once
#include <cstddef>
#include <filesystem>
#include <functional>
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
  // A folder holding runtime/compiled_filter.h precompiled by the build for this compiler and
  // these flags, searched first; empty when there is none (an installed tree, another compiler).
  // Not part of the identity: the object compiled is the same with it or without.
  std::filesystem::path precompiled_dir;
  // What the cache key needs to know about all this: compiler, version, flags, and the engine
  // (the archive's size and modification time: a rebuilt runtime is a new engine).
  std::string identity() const;
};

// The compiler (CompileOptions::compiler, else BOXGEN_CXX, else the one this build used, else
// c++ or g++ on PATH) and the engine beside the library that holds this code. Throws LoadError
// (one line) when there is no compiler, naming what to install, or no engine, or when the
// compiler's `--version` does not answer within the time limit.
Toolchain find_toolchain(const CompileOptions& options);

// The limits of a compile: the seconds it may take (CompileOptions::compile_seconds, else
// BOXGEN_COMPILE_TIMEOUT, else 600; `--version` gets at most 30 of them) and the bytes of the
// compiler's messages that are kept in the log (the rest is counted and dropped).
double compile_time_limit(const CompileOptions& options);
inline constexpr std::size_t kMaxLogBytes = 64 * 1024;

// Compiles `sources` (C++) into the shared object `output` within `seconds`: one source in one
// step, several each into an object at the same time (the machine's cores share the work), then
// linked. Each compiler runs in a process group of its own that is killed when the time is up,
// when this process is stopped by SIGINT, SIGTERM or SIGHUP (support::handle_signals) or when
// `check` throws (it is called every 0.1 s on the calling thread; the compilers are killed before
// the exception goes on). On failure throws LoadError naming `what` and the log `log`, written
// with the compiler's first kMaxLogBytes of messages; on success the log is removed. An exit
// status of 0 with no ELF object written is a failure too.
void compile_shared_object(const Toolchain& toolchain,
                           const std::vector<std::filesystem::path>& sources,
                           const std::filesystem::path& output, const std::filesystem::path& log,
                           const std::string& what, double seconds,
                           const std::function<void()>& check = {});

}  // namespace boxgen::loader
