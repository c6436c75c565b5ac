// Where the GL device keeps an emitted evaluator's tables (docs/gpu.md "Tables on the device").
// The emitted GLSL declares every table as a `const` array, so the file stands alone. The tables
// indexed by the point's cell (and, with several orbits, by its orbit) are indexed at run time, a
// different entry in each invocation; a `const` array indexed that way may be copied into each
// invocation's local memory by a GPU's compiler (the suspect in the H200's rates, performance.md).
// tables_in_buffer declares those tables instead as members of one read-only storage block whose
// contents the device uploads once: the rest of the text reads them by the same names.
#pragma once
#include <string>
#include <vector>

namespace boxgen::runtime::gl {

enum class TableStorage {
  constant,  // the emitted text as it is
  buffer,    // the run-time-indexed tables in a storage buffer
};

struct BufferedTables {
  std::string text;        // the evaluator, its run-time-indexed tables declared in the block
  std::vector<int> block;  // the block's contents (std430: int arrays, tightly packed, in order)
};

// The evaluator `text` (prefix `name`, as emitted by `boxgen emit --target glsl`) with its
// run-time-indexed int tables in a storage block at `binding`. GlError when a table is missing
// or malformed (the text is not an emitted evaluator).
BufferedTables tables_in_buffer(const std::string& text, const std::string& name, int binding);

}  // namespace boxgen::runtime::gl
