// Exactness on the GPU targets without a GPU (label gpu, docs/gpu.md): every registry filter and
// a 2-D matrix of this folder's own, emitted at build time for GLSL and CUDA; the values,
// gradients and Hessians of every entry point at the points of tests/emitted (half of them near
// knot planes), against the exact rational values, in float and double. The exact values are
// computed once per filter and serve all four runs: GLSL in a compute shader on llvmpipe
// (glsl_runner.cpp) and the CUDA header built for the host (cuda_host_runner.cpp).
#include <gtest/gtest.h>

#include "tests/gpu/gpu_test_support.h"

namespace boxgen::generator::gpu_test {
namespace {

class GpuTargets : public ::testing::TestWithParam<Filter> {};

TEST_P(GpuTargets, GlslAndCudaAreExactToTolerance) {
  const Filter& f = GetParam();
  const ExactCase c(f);
  const std::string name = f.name;
  {
    Evaluations e;
    evaluate_glsl<float>(f, c, &e);
    if (!HasFatalFailure()) compare(c.ref, c.exact, e, kFloatTolerance, name + ".glsl (float)");
  }
  {
    Evaluations e;
    evaluate_glsl<double>(f, c, &e);
    if (!HasFatalFailure()) compare(c.ref, c.exact, e, kDoubleTolerance, name + ".glsl (double)");
  }
  compare(c.ref, c.exact, evaluate_cuda_host<float>(f, c), kFloatTolerance, name + ".cuh (float)");
  compare(c.ref, c.exact, evaluate_cuda_host<double>(f, c), kDoubleTolerance,
          name + ".cuh (double)");
}

// examples/gpu/m7_volume.comp, with the emitted m7.glsl where it says, compiles and links (its
// CUDA twin is the test CudaExampleCompilesToPtx): the example cannot rot.
TEST(GpuExamples, ComputeShaderCompilesWithTheEmittedEvaluator) {
  std::string source = read_text(BOXGEN_GPU_EXAMPLE_SHADER);
  const std::string marker = "// ---- the text of m7.glsl goes here ----";
  const std::size_t at = source.find(marker);
  ASSERT_NE(at, std::string::npos) << BOXGEN_GPU_EXAMPLE_SHADER << " lost its marker line";
  source.replace(at, marker.size(), read_text(std::string(BOXGEN_GPU_EMITTED_DIR) + "/m7.glsl"));
  EXPECT_NE(compute_program(source, BOXGEN_GPU_EXAMPLE_SHADER), 0u);
}

INSTANTIATE_TEST_SUITE_P(Filters, GpuTargets, ::testing::ValuesIn(kFilters),
                         [](const auto& p) { return std::string(p.param.name); });

}  // namespace
}  // namespace boxgen::generator::gpu_test
