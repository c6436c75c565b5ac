#include "apps/boxrecon/device_choice.h"

#include <fmt/format.h>

#include <stdexcept>

#include "runtime/gl/gl_context.h"

namespace boxgen::app {

Device parse_device(const std::string& text) {
  if (text == "cpu") return Device::Cpu;
  if (text == "gl") return Device::Gl;
  throw std::invalid_argument("--device must be cpu or gl, got '" + text.substr(0, 40) + "'");
}

void add_device_option(CLI::App* command, std::string& device, bool* verbose) {
  command->add_option("--device", device,
                      "cpu (default) | gl: OpenGL compute through EGL (a GPU, else Mesa's "
                      "llvmpipe), float unless --precision double");
  if (verbose) command->add_flag("--verbose", *verbose, "name the GL device's renderer on stderr");
}

std::string gl_device_line() {
  const runtime::gl::DeviceInfo& d = runtime::gl::device();
  return fmt::format("GL device: {} ({}, {}){}", d.renderer, d.platform, d.version,
                     d.software ? ": a software renderer, CPU emulation of a GPU" : "");
}

}  // namespace boxgen::app
