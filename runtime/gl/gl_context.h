// The process's one headless OpenGL context (docs/gpu.md "The GL device"): EGL with no display,
// a GPU's driver where EGL device enumeration finds one (EGL_EXT_device_enumeration,
// EGL_PLATFORM_DEVICE_EXT), else Mesa's surfaceless platform (llvmpipe on a machine without a
// GPU). Core profile 4.3 or later: compute shaders and shader storage buffers. No GL type appears
// here; gl_context.cpp and the GL device's sources include the GL headers.
#pragma once
#include <cstdint>
#include <stdexcept>
#include <string>

namespace boxgen::runtime::gl {

// What the GL device cannot do: no EGL or no GL 4.3 context, a shader that does not compile (the
// driver's log in the message), a volume beyond the device's limits, a GL error or a lost
// context. One line; boxrecon exits 1.
struct GlError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

struct DeviceInfo {
  std::string renderer;   // GL_RENDERER, e.g. "llvmpipe (LLVM 15.0.6, 256 bits)"
  std::string vendor;     // GL_VENDOR
  std::string version;    // GL_VERSION
  std::string platform;   // "EGL device" (a GPU's driver) or "EGL surfaceless (Mesa)"
  bool software = false;  // llvmpipe or softpipe: the numbers measure CPU emulation
  bool fp64 = false;      // double precision in shaders (core since GL 4.0: always true)
  std::int64_t max_storage_block_bytes = 0;  // GL_MAX_SHADER_STORAGE_BLOCK_SIZE
};

// Makes the context current on first use (in the calling thread; the GL device is used from one
// thread) and describes it. Throws GlError, one line naming what is missing.
const DeviceInfo& device();

// The largest shader storage block the device path allocates: the driver's
// GL_MAX_SHADER_STORAGE_BLOCK_SIZE, or less after set_storage_limit_for_testing.
std::int64_t storage_limit();
// A test hook: pretend the device holds at most `bytes` per storage block (0: the driver's).
void set_storage_limit_for_testing(std::int64_t bytes);

// Throws GlError naming `what` when the GL reports an error or a lost context (a GPU hang or
// reset): a result read after either is not trusted.
void check_gl(const char* what);

// A compute program from the source (a full shader with its #version line). Throws GlError with
// the driver's log when it does not compile or link. The program id (a GLuint).
unsigned compile_compute(const std::string& source, const std::string& what);

}  // namespace boxgen::runtime::gl
