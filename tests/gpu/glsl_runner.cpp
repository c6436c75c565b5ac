// The GLSL target on the CPU: the emitted evaluator (boxgen emit --target glsl, float or double)
// in an OpenGL 4.5 compute shader on Mesa's llvmpipe through EGL with no display, one invocation
// per point calling the three entry points, in the GL device's context (runtime/gl). Without
// EGL the run fails, naming the packages to install.
#define GL_GLEXT_PROTOTYPES
#include <GL/glcorearb.h>
#include <fmt/format.h>
#include <gtest/gtest.h>

#include <fstream>
#include <sstream>

#include "runtime/gl/gl_context.h"
#include "tests/gpu/gpu_test_support.h"

namespace boxgen::generator::gpu_test {
namespace {

// The compute shader: one point per invocation, the emitted file between the application's
// fetch (from a box of samples in an SSBO) and main.
std::string shader(const std::string& name, const std::string& glsl, int n, bool dbl) {
  const std::string real = dbl ? "double" : "float";
  const std::string vec = fmt::format("{}vec{}", dbl ? "d" : "", n);
  const std::string mat = fmt::format("{}mat{}", dbl ? "d" : "", n);
  const std::string ivec = fmt::format("ivec{}", n);
  std::string out = fmt::format(R"(#version 430
layout(local_size_x = 64) in;
layout(std430, binding = 0) readonly buffer Points {{ {0} points[]; }};
layout(std430, binding = 1) writeonly buffer Results {{ {0} results[]; }};
layout(std430, binding = 2) readonly buffer Samples {{ {0} samples[]; }};
uniform int count;
uniform int lo;
uniform int side;
{0} {1}_fetch({2} j) {{
  int k = 0;
  for (int i = {3} - 1; i >= 0; --i) k = k * side + (j[i] - lo);
  return samples[k];
}}
)",
                                real, name, ivec, n);
  out += glsl;
  const int stride = 3 + 2 * n + n * n;
  // x built whole: NVIDIA's compiler (580) fails to link a write to a dvec at a run-time index
  // ("can't find __setVectorIndex function in stdlib").
  std::string coordinates;
  for (int i = 0; i < n; ++i)
    coordinates += fmt::format("{}points[p * {} + {}]", i ? ", " : "", n, i);
  out += fmt::format(R"(
void main() {{
  int p = int(gl_GlobalInvocationID.x);
  if (p >= count) return;
  {0} x = {0}({5});
  {0} g1, g2;
  {2} h;
  int at = p * {3};
  results[at] = {4}_value(x);
  results[at + 1] = {4}_value_gradient(x, g1);
  results[at + 2] = {4}_value_gradient_hessian(x, g2, h);
  for (int i = 0; i < {1}; ++i) {{
    results[at + 3 + i] = g1[i];
    results[at + 3 + {1} + i] = g2[i];
    for (int j = 0; j < {1}; ++j) results[at + 3 + 2 * {1} + i * {1} + j] = h[j][i];
  }}
}}
)",
                     vec, n, mat, stride, name, coordinates);
  return out;
}

GLuint buffer(GLuint binding, const void* data, std::size_t bytes) {
  GLuint b = 0;
  glGenBuffers(1, &b);
  glBindBuffer(GL_SHADER_STORAGE_BUFFER, b);
  glBufferData(GL_SHADER_STORAGE_BUFFER, static_cast<GLsizeiptr>(bytes), data, GL_DYNAMIC_COPY);
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, binding, b);
  return b;
}

}  // namespace

std::string read_text(const std::string& path) {
  std::ifstream in(path);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

GLuint compute_program(const std::string& source, const std::string& what) {
  try {
    return runtime::gl::compile_compute(source, what);
  } catch (const runtime::gl::GlError& e) {  // no context, or the driver's log
    ADD_FAILURE() << e.what();
    return 0;
  }
}

template <class Real>
void evaluate_glsl(const Filter& f, const ExactCase& c, Evaluations* e) {
  try {
    (void)runtime::gl::device();  // the GL device's context (runtime/gl/gl_context.h)
  } catch (const runtime::gl::GlError& error) {
    FAIL() << error.what();
  }
  constexpr bool dbl = sizeof(Real) == 8;
  const int n = c.ref.dimension();
  const auto& points = c.points;
  // Samples on a box of integer points around the test points (|x| < 4, reach <= 6).
  const int lo = -12, side = 24;
  std::vector<Real> samples(static_cast<std::size_t>(std::pow(side, n)));
  for (std::size_t k = 0; k < samples.size(); ++k) {
    IntVec j(n);
    std::size_t rest = k;
    for (int i = 0; i < n; ++i, rest /= side) j[i] = static_cast<std::int64_t>(rest % side) + lo;
    samples[k] = static_cast<Real>(exact_reference::data_value(j));
  }
  std::vector<Real> xs;
  for (const auto& x : points)
    for (const auto& xi : x) xs.push_back(static_cast<Real>(to_double(xi)));
  const std::string file =
      fmt::format("{}/{}{}.glsl", BOXGEN_GPU_EMITTED_DIR, f.name, dbl ? "_double" : "");
  const std::string source = shader(f.name, read_text(file), n, dbl);
  const GLuint program = compute_program(source, file);
  ASSERT_NE(program, 0u);
  glUseProgram(program);
  const int count = static_cast<int>(points.size());
  glUniform1i(glGetUniformLocation(program, "count"), count);
  glUniform1i(glGetUniformLocation(program, "lo"), lo);
  glUniform1i(glGetUniformLocation(program, "side"), side);
  const std::size_t stride = 3 + 2 * n + n * n;
  std::vector<Real> results(stride * points.size());
  const GLuint buffers[] = {buffer(0, xs.data(), xs.size() * sizeof(Real)),
                            buffer(1, nullptr, results.size() * sizeof(Real)),
                            buffer(2, samples.data(), samples.size() * sizeof(Real))};
  glDispatchCompute(static_cast<GLuint>((count + 63) / 64), 1, 1);
  glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
  glBindBuffer(GL_SHADER_STORAGE_BUFFER, buffers[1]);
  glGetBufferSubData(GL_SHADER_STORAGE_BUFFER, 0,
                     static_cast<GLsizeiptr>(results.size() * sizeof(Real)), results.data());
  ASSERT_EQ(glGetError(), static_cast<GLenum>(GL_NO_ERROR));
  glDeleteBuffers(3, buffers);
  glDeleteProgram(program);
  for (std::size_t p = 0; p < points.size(); ++p) {
    const Real* r = &results[p * stride];
    e->value0.push_back(r[0]);
    e->value1.push_back(r[1]);
    e->value2.push_back(r[2]);
    for (int i = 0; i < n; ++i) {
      e->gradient1.push_back(r[3 + i]);
      e->gradient2.push_back(r[3 + n + i]);
      for (int j = 0; j < n; ++j) e->hessian.push_back(r[3 + 2 * n + i * n + j]);
    }
  }
}

template void evaluate_glsl<float>(const Filter&, const ExactCase&, Evaluations*);
template void evaluate_glsl<double>(const Filter&, const ExactCase&, Evaluations*);

}  // namespace boxgen::generator::gpu_test
