// Where the GL device keeps an emitted evaluator's tables (docs/gpu.md "Tables on the device").
// The emitted GLSL declares every table as a `const` array, so the file stands alone. The tables
// indexed by the point's cell (and, with several orbits, by its orbit) are indexed at run time, a
// different entry in each invocation; a `const` array indexed that way may be copied into each
// invocation's local memory by a GPU's compiler (the suspect in the H200's rates, performance.md).
// The generator therefore also prints the evaluator with those tables as members of one
// read-only storage block (generator/codegen/targets/glsl_evaluator.h), and gives the block's
// contents as numbers: the device uploads them once. Both come as data with the text
// (GlslEvaluator, gl_spline.h); nothing searches or rewrites the text.
#pragma once

namespace boxgen::runtime::gl {

enum class TableStorage {
  constant,  // the emitted text as it is
  buffer,    // the run-time-indexed tables in a storage buffer, where the evaluator carries them
};

}  // namespace boxgen::runtime::gl
