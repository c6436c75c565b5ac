#include "runtime/gl/gl_context.h"

#define EGL_EGLEXT_PROTOTYPES
#define GL_GLEXT_PROTOTYPES
#include <EGL/egl.h>
#include <EGL/eglext.h>
#include <GL/glcorearb.h>
#include <fmt/format.h>

#include <algorithm>
#include <cctype>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <string>
#include <system_error>

#include "runtime/nrrd_checks.h"
#include "support/output_file.h"

namespace boxgen::runtime::gl {

namespace {

const char* const kInstall =
    "install libegl1, libopengl0 and libgl1-mesa-dri (Debian; scripts/install-deps.sh) or a GPU "
    "driver with EGL";

std::int64_t storage_override = 0;

// With BOXGEN_GL_DUMP set to a folder: the program's source, the driver's link log and the
// program's binary (glGetProgramBinary, in the driver's own format) as DIR/LABEL.comp, .log and
// .bin (written as support/output_file.h writes a set), LABEL made of `what`'s letters and
// digits. For reading what a GPU's compiler made of a kernel (docs/gpu.md, "A kernel's
// compile").
void dump_program(GLuint program, const std::string& source, const std::string& what,
                  const std::string& log) {
  const char* folder = std::getenv("BOXGEN_GL_DUMP");
  if (!folder || !*folder) return;
  // An existing folder only: a mistyped path is an error, never a tree of folders made for it.
  std::error_code error;
  if (!std::filesystem::is_directory(folder, error))
    throw GlError(fmt::format("BOXGEN_GL_DUMP: '{}' is not an existing folder",
                              runtime::nrrd_checks::printable(folder)));
  std::string label;
  for (char c : what) {
    const bool word = std::isalnum(static_cast<unsigned char>(c)) != 0;
    if (word)
      label += static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    else if (!label.empty() && label.back() != '_')
      label += '_';
  }
  while (!label.empty() && label.back() == '_') label.pop_back();
  GLint length = 0;
  glGetProgramiv(program, GL_PROGRAM_BINARY_LENGTH, &length);
  std::string binary(static_cast<std::size_t>(std::max(length, 0)), '\0');
  GLenum format = 0;
  if (length > 0) glGetProgramBinary(program, length, &length, &format, binary.data());
  binary.resize(static_cast<std::size_t>(std::max(length, 0)));
  const support::NamedText files[] = {
      {label + ".comp", source}, {label + ".log", log}, {label + ".bin", binary}};
  try {
    support::write_file_set(folder, files);
  } catch (const support::OutputFileError& e) {
    throw GlError(fmt::format("BOXGEN_GL_DUMP: {}", e.what()));
  }
}

// A 4.3 core context on `display`, current with no surface; false (display terminated) if not.
// No-config contexts (EGL_KHR_no_config_context) first, then a pbuffer-capable config.
bool make_current(EGLDisplay display) {
  EGLint major = 0, minor = 0;
  if (display == EGL_NO_DISPLAY || !eglInitialize(display, &major, &minor)) return false;
  if (!eglBindAPI(EGL_OPENGL_API)) {
    eglTerminate(display);
    return false;
  }
  const EGLint attributes[] = {EGL_CONTEXT_MAJOR_VERSION,
                               4,
                               EGL_CONTEXT_MINOR_VERSION,
                               3,
                               EGL_CONTEXT_OPENGL_PROFILE_MASK,
                               EGL_CONTEXT_OPENGL_CORE_PROFILE_BIT,
                               EGL_NONE};
  EGLConfig config = EGL_NO_CONFIG_KHR;
  EGLContext context = eglCreateContext(display, config, EGL_NO_CONTEXT, attributes);
  if (context == EGL_NO_CONTEXT) {
    const EGLint wanted[] = {EGL_RENDERABLE_TYPE, EGL_OPENGL_BIT, EGL_SURFACE_TYPE, EGL_PBUFFER_BIT,
                             EGL_NONE};
    EGLint found = 0;
    if (eglChooseConfig(display, wanted, &config, 1, &found) && found == 1)
      context = eglCreateContext(display, config, EGL_NO_CONTEXT, attributes);
  }
  if (context == EGL_NO_CONTEXT ||
      !eglMakeCurrent(display, EGL_NO_SURFACE, EGL_NO_SURFACE, context)) {
    if (context != EGL_NO_CONTEXT) eglDestroyContext(display, context);
    eglTerminate(display);
    return false;
  }
  return true;
}

// The first hardware device EGL enumerates with a 4.3 context (software devices, Mesa's
// EGL_MESA_device_software, are left to the surfaceless fallback).
bool make_device_current() {
  const auto query_devices =
      reinterpret_cast<PFNEGLQUERYDEVICESEXTPROC>(eglGetProcAddress("eglQueryDevicesEXT"));
  const auto device_string = reinterpret_cast<PFNEGLQUERYDEVICESTRINGEXTPROC>(
      eglGetProcAddress("eglQueryDeviceStringEXT"));
  if (!query_devices || !device_string) return false;
  EGLDeviceEXT devices[16];
  EGLint count = 0;
  if (!query_devices(16, devices, &count)) return false;
  for (EGLint i = 0; i < count; ++i) {
    const char* extensions = device_string(devices[i], EGL_EXTENSIONS);
    if (extensions && std::strstr(extensions, "EGL_MESA_device_software")) continue;
    if (make_current(eglGetPlatformDisplay(EGL_PLATFORM_DEVICE_EXT, devices[i], nullptr)))
      return true;
  }
  return false;
}

std::string gl_string(GLenum name) {
  const auto* s = reinterpret_cast<const char*>(glGetString(name));
  return s ? s : "";
}

DeviceInfo open_device() {
  DeviceInfo info;
  // BOXGEN_GL_PLATFORM=surfaceless skips the device enumeration (Mesa, e.g. llvmpipe, even on a
  // machine with a GPU).
  const char* platform = std::getenv("BOXGEN_GL_PLATFORM");
  const bool surfaceless_only = platform && std::string(platform) == "surfaceless";
  if (platform && *platform && !surfaceless_only)
    throw GlError(fmt::format("BOXGEN_GL_PLATFORM must be 'surfaceless' or unset, got '{}'",
                              runtime::nrrd_checks::printable(platform)));
  if (!surfaceless_only && make_device_current()) {
    info.platform = "EGL device";
  } else if (make_current(eglGetPlatformDisplay(EGL_PLATFORM_SURFACELESS_MESA, EGL_DEFAULT_DISPLAY,
                                                nullptr))) {
    info.platform = "EGL surfaceless (Mesa)";
  } else {
    throw GlError(
        fmt::format("no OpenGL 4.3 context through EGL (no GPU device and no Mesa "
                    "surfaceless platform): {}",
                    kInstall));
  }
  info.renderer = gl_string(GL_RENDERER);
  info.vendor = gl_string(GL_VENDOR);
  info.version = gl_string(GL_VERSION);
  info.software = info.renderer.find("llvmpipe") != std::string::npos ||
                  info.renderer.find("softpipe") != std::string::npos;
  GLint major = 0, minor = 0;
  glGetIntegerv(GL_MAJOR_VERSION, &major);
  glGetIntegerv(GL_MINOR_VERSION, &minor);
  if (major * 10 + minor < 43)
    throw GlError(fmt::format("the OpenGL context is version {}.{} ({}), compute shaders need 4.3",
                              major, minor, info.renderer));
  info.fp64 = true;  // core since 4.0
  GLint64 block = 0;
  glGetInteger64v(GL_MAX_SHADER_STORAGE_BLOCK_SIZE, &block);
  info.max_storage_block_bytes = block;
  check_gl("the context's limits");
  return info;
}

}  // namespace

const DeviceInfo& device() {
  static const DeviceInfo info = open_device();
  return info;
}

std::int64_t storage_limit() {
  const std::int64_t driver = device().max_storage_block_bytes;
  return storage_override > 0 && storage_override < driver ? storage_override : driver;
}

void set_storage_limit_for_testing(std::int64_t bytes) { storage_override = bytes; }

void check_gl(const char* what) {
  const GLenum reset = glGetGraphicsResetStatus();
  if (reset != GL_NO_ERROR)
    throw GlError(fmt::format("the GPU was reset during {} (status 0x{:x}): no result is trusted",
                              what, reset));
  const GLenum error = glGetError();
  if (error != GL_NO_ERROR)
    throw GlError(fmt::format("OpenGL error 0x{:x} during {}", error, what));
}

unsigned compile_compute(const std::string& source, const std::string& what) {
  (void)device();
  const char* text = source.c_str();
  const GLuint shader = glCreateShader(GL_COMPUTE_SHADER);
  glShaderSource(shader, 1, &text, nullptr);
  glCompileShader(shader);
  GLint ok = 0;
  glGetShaderiv(shader, GL_COMPILE_STATUS, &ok);
  const auto log_of = [](GLuint object, bool is_shader) {
    GLint length = 0;
    (is_shader ? glGetShaderiv : glGetProgramiv)(object, GL_INFO_LOG_LENGTH, &length);
    std::string log(static_cast<std::size_t>(length > 0 ? length : 1), '\0');
    (is_shader ? glGetShaderInfoLog : glGetProgramInfoLog)(object, static_cast<GLsizei>(log.size()),
                                                           nullptr, log.data());
    log.resize(std::strlen(log.c_str()));
    for (char& c : log)  // one line: the driver's log joined
      if (c == '\n') c = ' ';
    return log;
  };
  if (!ok) {
    const std::string log = log_of(shader, true);
    glDeleteShader(shader);
    throw GlError(fmt::format("{} does not compile on {}: {}", what, device().renderer, log));
  }
  const GLuint program = glCreateProgram();
  glAttachShader(program, shader);
  glProgramParameteri(program, GL_PROGRAM_BINARY_RETRIEVABLE_HINT, GL_TRUE);
  glLinkProgram(program);
  glDeleteShader(shader);  // the program keeps it
  glGetProgramiv(program, GL_LINK_STATUS, &ok);
  if (!ok) {
    const std::string log = log_of(program, false);
    glDeleteProgram(program);
    throw GlError(fmt::format("{} does not link on {}: {}", what, device().renderer, log));
  }
  check_gl("the shader's compile");
  dump_program(program, source, what, log_of(program, false));
  return program;
}

}  // namespace boxgen::runtime::gl
