// A filter from any SPEC at run time (docs/runtime.md "Filters from any SPEC"): a registry name
// (m7, fcc6, ...) gives the registry's filter; anything else boxgen accepts (a preset on another
// lattice, or the columns "1,1,1; 1,-1,-1; ...", with a lattice) is derived and emitted by the
// generator, compiled once by the system's C++ compiler into a shared object against the
// runtime's engine, and cached; later uses load the cached object. The result is a SplineFilter
// like any other: Reconstructor, resample and render take it.
#pragma once
#include <filesystem>
#include <functional>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "runtime/spline_filter.h"

namespace boxgen::loader {

// A SPEC that cannot become a filter, or a compile that failed: one line (boxrecon exits 1).
struct LoadError : std::invalid_argument {
  using std::invalid_argument::invalid_argument;
};

struct CompileOptions {
  // Where compiled filters live; empty: BOXGEN_CACHE_DIR, else $XDG_CACHE_HOME/boxgen, else
  // ~/.cache/boxgen (cache_directory()).
  std::filesystem::path cache_dir;
  // The C++ compiler; empty: BOXGEN_CXX, else the compiler this build was made with, else c++
  // or g++ on PATH.
  std::string compiler;
  // Progress of a first use (derive, emit, compile) on stderr; boxrecon passes
  // isatty(stderr) && !--quiet. Never printed for registry filters or cached ones.
  bool progress = false;
  // Seconds and bytes the derivation may take before it is refused (0: the generator's limits).
  double max_seconds = 0;
  double max_bytes = 0;
  // Seconds a compile may take before it is stopped (0: BOXGEN_COMPILE_TIMEOUT, else 600).
  double compile_seconds = 0;
  // Called every 0.1 s while a compile runs; an exception it throws stops the compile (the
  // compiler's process group is killed) and goes on to the caller. Python raises
  // KeyboardInterrupt through it.
  std::function<void()> check_interrupt;
};

// The filter of `spec_or_name` on `lattice` (bcc | fcc | cartesian | the rows of G, as boxgen
// takes them; none: the preset's lattice). A registry name without a lattice, or with its own
// lattice, is the registry's filter; a registry name with another lattice is refused (give its
// directions instead). Throws LoadError (one line) for a SPEC boxgen refuses, a 2-D SPEC, no
// compiler ("install g++ (Debian: apt-get install g++)") or a failed compile. A SPEC's filter
// carries its GLSL evaluators for the GL device (FilterSource::glsl, float and double: prefix
// spec_KEY, the text, and the evaluator with its run-time-indexed tables in a storage block with
// the block's contents), emitted into the cache entry with the shared object and read with it,
// checked against the entry's record.
runtime::SplineFilter load_filter(const std::string& spec_or_name,
                                  std::optional<std::string> lattice = std::nullopt,
                                  const CompileOptions& options = {});

// The directions of a SPEC as its cache key hashes them: each with its first nonzero entry
// positive, sorted. The centred spline is the same for any order and sign of its directions, so
// every such spelling loads one entry. Throws LoadError for a SPEC boxgen refuses.
std::string cache_key_directions(const std::string& spec, const std::string& lattice = {});

// The cache directory the options name (not created).
std::filesystem::path cache_directory(const CompileOptions& options = {});

// A compiled filter in the cache.
struct CachedFilter {
  std::string spec;     // the directions "a,b,c; ..." as derived
  std::string lattice;  // its lattice's name (bcc, fcc, cartesian or custom)
  std::string rows;     // the rows of G
  std::string key;      // the file stem in the cache
  std::filesystem::path library;
};

// Every cached filter whose shared object is present, by SPEC.
std::vector<CachedFilter> cached_filters(const CompileOptions& options = {});

}  // namespace boxgen::loader
