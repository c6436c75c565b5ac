// The GLSL evaluators of the registry's filters as this build emitted them (float and double),
// with what the GL device needs beside the text as data: registry_glsl.cpp is written at build
// time by boxgen_embed_glsl (generator/codegen/tools/embed_glsl.cpp) from the generator's Emission.
#pragma once

namespace boxgen::runtime::gl {

struct RegistryGlsl {
  const char* name;
  int stencil_size;
  const char* float_text;  // NAME.glsl: its tables `const` arrays
  const char* double_text;
  // The same with the run-time-indexed tables in a storage block
  // (generator/codegen/targets/glsl_evaluator.h), and the block's contents (the same in both
  // precisions).
  const char* float_buffered;
  const char* double_buffered;
  const int* block;
  int block_size;
};

extern const RegistryGlsl kRegistryGlsl[];
extern const int kRegistryGlslCount;

}  // namespace boxgen::runtime::gl
