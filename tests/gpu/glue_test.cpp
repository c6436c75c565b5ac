// The cell-locating glue on all three targets against the same cases (docs/gpu.md): nearest_cell
// and floor_div of support/cell_glue.h, the one definition the C++ and CUDA evaluators share, as
// the C++ header calls it (support::nearest_cell<Traits> of support/evaluator_support.hpp) and as
// the CUDA header calls it, on the CUDA header's own tables built for the host (the PTX compile
// is CudaHeadersCompileToPtx), and the GLSL evaluator's port, NAME_nearest_cell and
// NAME_floor_div, in a compute shader on llvmpipe, in float and double, for every filter of
// gpu_test_support.h.
//
// nearest_cell's cases: every cube of the period and every r in {0, 1/4, 1/2, 3/4}^n, most of them
// on knot planes, where cells tie. Their sums are exact in every precision (small integers times
// quarters), so every target must pick exactly the cell that integer arithmetic picks from the
// tables: the first of the least violation. (Off such points every target sums in the evaluator's
// precision; where GLSL's rounding breaks a tie differently, either cell is right, the spline
// being continuous there.)
#define GL_GLEXT_PROTOTYPES
#include <GL/glcorearb.h>
#include <fmt/format.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <set>
#include <string>
#include <vector>

#include "cart7.cuh"
#include "cpp/cart7.hpp"
#include "cpp/fcc6.hpp"
#include "cpp/five.hpp"
#include "cpp/m12.hpp"
#include "cpp/m7.hpp"
#include "cpp/m8.hpp"
#include "cpp/tricubic.hpp"
#include "fcc6.cuh"
#include "five.cuh"
#include "m12.cuh"
#include "m7.cuh"
#include "m8.cuh"
#include "runtime/gl/gl_context.h"
#include "tests/gpu/gpu_test_support.h"
#include "tricubic.cuh"

namespace boxgen::generator::gpu_test {
namespace {

constexpr int kQuarters = 4;  // r's coordinates are m / 4, m in [0, 4)

// One nearest_cell case: a cube and r = m / 4.
struct CellCase {
  int cube;
  std::vector<int> m;
};

// One floor_div case: floor(a / b), b > 0 as the glue calls it.
struct DivCase {
  int a, b;
};

// What the cases need of a filter's tables, read from its C++ header, and each target's glue.
struct Glue {
  int dimension = 0, cube_count = 0;
  std::vector<int> cell_cube;               // per cell
  std::vector<std::vector<int>> cell_keys;  // per cell, per normal
  std::vector<std::vector<int>> normals;    // per normal (the axes excluded), its components
  int (*cpp_float)(int, const float*) = nullptr;
  int (*cpp_double)(int, const double*) = nullptr;
  int (*cuda_float)(int, const float*) = nullptr;
  int (*cuda_double)(int, const double*) = nullptr;
};

template <class Tr>
Glue tables_of() {
  Glue g;
  g.dimension = Tr::kDimension;
  g.cube_count = Tr::kCubeCount;
  for (const auto& c : Tr::kCells) {
    g.cell_cube.push_back(c.cube);
    g.cell_keys.emplace_back(c.keys, c.keys + Tr::kNormalCount);
  }
  for (int k = 0; k < Tr::kNormalCount; ++k)
    g.normals.emplace_back(Tr::kNormals[k], Tr::kNormals[k] + Tr::kDimension);
  return g;
}

#define BOXGEN_GLUE(NS)                                                              \
  if (name == #NS) {                                                                 \
    Glue g = tables_of<generated::NS::Traits>();                                     \
    g.cpp_float = &generated::support::nearest_cell<generated::NS::Traits, float>;   \
    g.cpp_double = &generated::support::nearest_cell<generated::NS::Traits, double>; \
    g.cuda_float = +[](int cube, const float* r) {                                   \
      return ::boxgen::support::nearest_cell(cube, r, generated::NS::cuda::kCells,   \
                                             generated::NS::cuda::kNormals);         \
    };                                                                               \
    g.cuda_double = +[](int cube, const double* r) {                                 \
      return ::boxgen::support::nearest_cell(cube, r, generated::NS::cuda::kCells,   \
                                             generated::NS::cuda::kNormals);         \
    };                                                                               \
    return g;                                                                        \
  }

Glue glue_of(const std::string& name) {
  BOXGEN_GLUE(m7)
  BOXGEN_GLUE(m8)
  BOXGEN_GLUE(m12)
  BOXGEN_GLUE(fcc6)
  BOXGEN_GLUE(tricubic)
  BOXGEN_GLUE(cart7)
  BOXGEN_GLUE(five)
  ADD_FAILURE() << "no glue for " << name;
  return {};
}

std::vector<CellCase> cell_cases(const Glue& g) {
  std::vector<CellCase> out;
  int points = 1;
  for (int i = 0; i < g.dimension; ++i) points *= kQuarters;
  for (int cube = 0; cube < g.cube_count; ++cube)
    for (int p = 0; p < points; ++p) {
      CellCase c{cube, {}};
      for (int i = 0, rest = p; i < g.dimension; ++i, rest /= kQuarters)
        c.m.push_back(rest % kQuarters);
      out.push_back(c);
    }
  return out;
}

std::vector<DivCase> div_cases() {
  std::vector<DivCase> out;
  for (int b = 1; b <= 5; ++b)
    for (int a = -23; a <= 23; ++a) out.push_back({a, b});
  return out;
}

// The cell of the cube whose slabs [key, key + 1] the products nu . r violate least, the first of
// several: in integers, four times every product.
int exact_nearest_cell(const Glue& g, const CellCase& c) {
  int best = -1;
  long best_violation = 0;
  for (std::size_t cell = 0; cell < g.cell_cube.size(); ++cell) {
    if (g.cell_cube[cell] != c.cube) continue;
    long violation = 0;
    for (std::size_t k = 0; k < g.normals.size(); ++k) {
      long s = 0;
      for (int i = 0; i < g.dimension; ++i) s += static_cast<long>(g.normals[k][i]) * c.m[i];
      const long lo = kQuarters * static_cast<long>(g.cell_keys[cell][k]);
      violation += std::max(0L, lo - s) + std::max(0L, s - (lo + kQuarters));
    }
    if (best < 0 || violation < best_violation) {
      best = static_cast<int>(cell);
      best_violation = violation;
    }
  }
  return best;
}

template <class Real>
std::vector<int> run_host(int (*nearest)(int, const Real*), const std::vector<CellCase>& cases) {
  std::vector<int> out;
  for (const CellCase& c : cases) {
    std::vector<Real> r;
    for (int m : c.m) r.push_back(static_cast<Real>(m) / kQuarters);
    out.push_back(nearest(c.cube, r.data()));
  }
  return out;
}

GLuint buffer(GLuint binding, const void* data, std::size_t bytes) {
  GLuint b = 0;
  glGenBuffers(1, &b);
  glBindBuffer(GL_SHADER_STORAGE_BUFFER, b);
  glBufferData(GL_SHADER_STORAGE_BUFFER, static_cast<GLsizeiptr>(std::max<std::size_t>(bytes, 4)),
               data, GL_DYNAMIC_COPY);
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, binding, b);
  return b;
}

// The GLSL glue of NAME.glsl (or NAME_double.glsl) on the cases: per invocation one nearest_cell
// case (the normals' products with r formed as the evaluator forms them, in its precision) and
// one floor_div case. The results: the cells, then the quotients.
std::vector<int> run_glsl(const std::string& name, bool dbl, const Glue& g,
                          const std::vector<CellCase>& cells, const std::vector<DivCase>& divs) {
  try {
    (void)runtime::gl::device();  // the GL device's context (runtime/gl/gl_context.h)
  } catch (const runtime::gl::GlError& error) {
    ADD_FAILURE() << error.what();
    return {};
  }
  const int n = g.dimension;
  const int normals = static_cast<int>(g.normals.size());
  const std::string real = dbl ? "double" : "float";
  const std::string file =
      fmt::format("{}/{}{}.glsl", BOXGEN_GPU_EMITTED_DIR, name, dbl ? "_double" : "");
  std::string source = fmt::format(R"(#version 430
layout(local_size_x = 64) in;
layout(std430, binding = 0) readonly buffer Cells {{ int cells[]; }};
layout(std430, binding = 1) readonly buffer Divs {{ int divs[]; }};
layout(std430, binding = 2) readonly buffer Normals {{ int normals[]; }};
layout(std430, binding = 3) writeonly buffer Results {{ int results[]; }};
uniform int cell_count;
uniform int div_count;
{0} {1}_fetch(ivec{2} j) {{ return {0}(0); }}
)",
                                   real, name, n);
  source += read_text(file);
  source += fmt::format(R"(
void main() {{
  int p = int(gl_GlobalInvocationID.x);
  if (p < cell_count) {{
    int at = p * ({2} + 1);
    {0} key[{3} + 1];
    for (int k = 0; k <= {3}; ++k) key[k] = {0}(0);
    for (int k = 0; k < {3}; ++k)
      for (int i = 0; i < {2}; ++i)
        key[k] += {0}(normals[k * {2} + i]) * ({0}(cells[at + 1 + i]) / {0}({4}));
    results[p] = {1}_nearest_cell(cells[at], key);
  }}
  if (p < div_count) results[cell_count + p] = {1}_floor_div(divs[2 * p], divs[2 * p + 1]);
}}
)",
                        real, name, n, normals, kQuarters);
  const GLuint program = compute_program(source, file);
  if (program == 0) return {};
  std::vector<int> cell_data, div_data, normal_data;
  for (const CellCase& c : cells) {
    cell_data.push_back(c.cube);
    cell_data.insert(cell_data.end(), c.m.begin(), c.m.end());
  }
  for (const DivCase& d : divs) div_data.insert(div_data.end(), {d.a, d.b});
  for (const auto& nu : g.normals) normal_data.insert(normal_data.end(), nu.begin(), nu.end());
  glUseProgram(program);
  const int cell_count = static_cast<int>(cells.size()), div_count = static_cast<int>(divs.size());
  glUniform1i(glGetUniformLocation(program, "cell_count"), cell_count);
  glUniform1i(glGetUniformLocation(program, "div_count"), div_count);
  std::vector<int> results(cells.size() + divs.size());
  const GLuint buffers[] = {buffer(0, cell_data.data(), cell_data.size() * sizeof(int)),
                            buffer(1, div_data.data(), div_data.size() * sizeof(int)),
                            buffer(2, normal_data.data(), normal_data.size() * sizeof(int)),
                            buffer(3, nullptr, results.size() * sizeof(int))};
  const int invocations = std::max(cell_count, div_count);
  glDispatchCompute(static_cast<GLuint>((invocations + 63) / 64), 1, 1);
  glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
  glBindBuffer(GL_SHADER_STORAGE_BUFFER, buffers[3]);
  glGetBufferSubData(GL_SHADER_STORAGE_BUFFER, 0,
                     static_cast<GLsizeiptr>(results.size() * sizeof(int)), results.data());
  EXPECT_EQ(glGetError(), static_cast<GLenum>(GL_NO_ERROR));
  glDeleteBuffers(4, buffers);
  glDeleteProgram(program);
  return results;
}

class CellLocatingGlue : public ::testing::TestWithParam<Filter> {};

TEST_P(CellLocatingGlue, NearestCellAndFloorDivAgreeOnEveryTarget) {
  const std::string name = GetParam().name;
  const Glue g = glue_of(name);
  ASSERT_GT(g.dimension, 0);
  const std::vector<CellCase> cells = cell_cases(g);
  const std::vector<DivCase> divs = div_cases();
  std::vector<int> expected_cells, expected_quotients;
  for (const CellCase& c : cells) expected_cells.push_back(exact_nearest_cell(g, c));
  for (const DivCase& d : divs)
    expected_quotients.push_back(static_cast<int>(std::floor(static_cast<double>(d.a) / d.b)));
  // Every case has a cell, and where the period has several, the cases are not all of one.
  EXPECT_EQ(std::count(expected_cells.begin(), expected_cells.end(), -1), 0);
  if (g.cell_cube.size() > 1) {
    EXPECT_GT(std::set<int>(expected_cells.begin(), expected_cells.end()).size(), 1u);
  }

  EXPECT_EQ(run_host(g.cpp_float, cells), expected_cells) << name << ".hpp (float)";
  EXPECT_EQ(run_host(g.cpp_double, cells), expected_cells) << name << ".hpp (double)";
  EXPECT_EQ(run_host(g.cuda_float, cells), expected_cells) << name << ".cuh (float)";
  EXPECT_EQ(run_host(g.cuda_double, cells), expected_cells) << name << ".cuh (double)";
  std::vector<int> quotients;  // the C++ and CUDA headers' one floor_div (support/integer_math.h)
  for (const DivCase& d : divs)
    quotients.push_back(static_cast<int>(::boxgen::support::floor_div(d.a, d.b)));
  EXPECT_EQ(quotients, expected_quotients) << "support::floor_div";

  std::vector<int> expected = expected_cells;
  expected.insert(expected.end(), expected_quotients.begin(), expected_quotients.end());
  for (const bool dbl : {false, true})
    EXPECT_EQ(run_glsl(name, dbl, g, cells, divs), expected)
        << name << (dbl ? "_double" : "") << ".glsl";
}

INSTANTIATE_TEST_SUITE_P(Filters, CellLocatingGlue, ::testing::ValuesIn(kFilters),
                         [](const auto& p) { return std::string(p.param.name); });

}  // namespace
}  // namespace boxgen::generator::gpu_test
