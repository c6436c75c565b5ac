// --device cpu|gl of eval, resample, render and bench: the CPU runtime, or the GL device
// (runtime/gl, docs/gpu.md "The GL device"), which evaluates the registry's filters with their
// emitted GLSL in OpenGL compute shaders.
#pragma once
#include <CLI/CLI.hpp>

#include <string>

namespace boxgen::app {

enum class Device { Cpu, Gl };

// "cpu" or "gl"; anything else is std::invalid_argument (one line).
Device parse_device(const std::string& text);

// Adds --device to a command, and --verbose (the GL renderer on stderr) unless it has one.
void add_device_option(CLI::App* command, std::string& device, bool* verbose);

// "GL device: RENDERER (PLATFORM)", with "CPU emulation" for llvmpipe; opens the context (throws
// runtime::gl::GlError without one).
std::string gl_device_line();

}  // namespace boxgen::app
