// Emission (docs/design.md §11): the generator's tables and polynomial code, filled into the
// fmt templates of templates/ to make a self-contained C++ evaluator header for one spline.
#pragma once
#include <optional>
#include <string>
#include <vector>

#include "boxgen/version.h"
#include "generator/codegen/strategies/polynomial_code.h"
#include "generator/derivation.h"
#include "generator/prefilter.h"

namespace boxgen::generator {

inline constexpr const char* kGeneratorVersion = kVersionBanner;  // boxgen/version.h (CMake)

struct EmittedFile {
  std::string filename;
  std::string text;
  // C++ headers of an evaluator: the same text without its include guard, for a translation unit
  // that holds the header in its own text (the loader's shared object); empty otherwise.
  std::string pasted = {};
};

// The language of the evaluator: C++ (<name>.hpp and <name>_prefilters.hpp), GLSL 4.30
// (<name>.glsl) or CUDA (<name>.cuh), all printed from the same scheduled expression graphs.
enum class EmissionTarget { Cpp, Glsl, Cuda };

// q1opt or q2opt (docs/design.md §19) for NAME_prefilters.hpp: the caller computes them, since
// their free parameters come from a numerical optimisation (analysis/) that the generator does
// not link. `exact`: no free parameter, the weights are exact rationals (printed beside the
// table); otherwise their nearest doubles are the data.
struct OptimisedPrefilterTable {
  Prefilter prefilter;
  bool exact = false;
};

struct EmissionRequest {
  std::string name;     // C++ identifier: the namespace boxgen::generated::<name>
  std::string command;  // the command that reproduces the file, for its header
  // See generator/codegen/strategies/polynomial_code.h.
  EmissionStrategy strategy = EmissionStrategy::Auto;
  EmissionTarget target = EmissionTarget::Cpp;
  bool double_precision = false;  // GLSL: double, dvec3, dmat3 instead of float, vec3, mat3
  // The shells of q1 (q2: these and the next shell); empty: the smallest on which a prefilter of
  // full order exists (quasi_interpolation_shells, generator/prefilter.h).
  std::vector<int> shells{};
  // C++: the tables q1opt and q2opt (on the shells of q1 and q2); none: the header says that
  // this emission has none.
  std::optional<OptimisedPrefilterTable> q1opt{}, q2opt{};
};

// What the emitted evaluator costs: the strategy of each orbit and its operation counts (value;
// value + gradient; value + gradient + Hessian), as recorded in the header.
struct OrbitReport {
  std::string strategy;
  OperationCount value, gradient, hessian;
  std::string form;                      // e.g. the origin of the shifted form: "about (1,1,1)"
  std::vector<StrategyCost> considered;  // auto: every applicable strategy's counts
};
struct EmissionReport {
  std::string strategy;  // of the whole evaluator ("mixed: ..." when orbits differ)
  std::vector<OrbitReport> orbits;
  OperationCount value, gradient, hessian;  // the costliest orbit's
};

// What an emission is, as data beside its text: consumers (the loader, the CLI, the tests) read
// these and never search or parse the text.
struct Emission {
  // C++: <name>.hpp (evaluator) and <name>_prefilters.hpp; GLSL: <name>.glsl; CUDA: <name>.cuh.
  std::vector<EmittedFile> files;
  EmissionReport report;
  int stencil_size = 0;       // the largest stencil, kStencilSize of every target
  IntVec reach_lo, reach_hi;  // kStencilReachLo/Hi: offsets j - floor(x + c) over every cell
  // C++: the quasi-interpolation prefilters q1 and q2 that <name>_prefilters.hpp holds (on the
  // request's shells); none where no prefilter of full order exists there (the header says why).
  std::optional<Prefilter> q1, q2;
  // C++: the request's q1opt and q2opt, which the header holds where given.
  std::optional<Prefilter> q1opt, q2opt;
  // GLSL: the evaluator with its run-time-indexed tables in a storage block, and the block's
  // contents (generator/codegen/targets/glsl_evaluator.h); the file is the variant whose tables are
  // `const`.
  std::string glsl_buffered;
  std::vector<int> glsl_block;
};

// The evaluator of `analysis` for the request's target. Throws InputError for a name that is not
// a C++ identifier.
Emission emit(const Derivation& analysis, const EmissionRequest& request);

// registry.hpp: boxgen::generated::with_filter over the named filters (each with its evaluator and
// both prefilters in the same directory), in the order given; the last one is the switch's default.
EmittedFile emit_registry(const std::vector<std::string>& names, const std::string& command);

}  // namespace boxgen::generator
