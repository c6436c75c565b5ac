// The GLSL evaluators of the registry's filters as this build emitted them (float and double):
// registry_glsl.cpp is written at build time by EmbedGlsl.cmake from `boxgen emit --target glsl`.
#pragma once

namespace boxgen::runtime::gl {

struct RegistryGlsl {
  const char* name;
  const char* float_text;
  const char* double_text;
};

extern const RegistryGlsl kRegistryGlsl[];
extern const int kRegistryGlslCount;

}  // namespace boxgen::runtime::gl
