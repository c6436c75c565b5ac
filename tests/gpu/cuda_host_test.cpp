// The emitted CUDA headers (boxgen emit --target cuda) built as plain C++17 by the host compiler,
// as a CPU caller of the device code would use them: every registry filter and this folder's own
// 2-D matrix, float and double, values, gradients and Hessians against the exact rational
// values (the same points and tolerances as the GLSL test). The PTX compile of the same headers
// is the test CudaHeadersCompileToPtx (tests/gpu/CMakeLists.txt).
#include <gtest/gtest.h>

#include "cart7.cuh"
#include "fcc6.cuh"
#include "five.cuh"
#include "m12.cuh"
#include "m7.cuh"
#include "m8.cuh"
#include "tests/gpu/gpu_test_support.h"
#include "tricubic.cuh"

namespace boxgen::generator::gpu_test {
namespace {

template <class Real, int N, class Evaluate>
void check(const Filter& f, Evaluate evaluate) {
  const Reference ref(f.spec, f.lattice);
  ASSERT_EQ(ref.dimension(), N);
  const auto points = exact_reference::test_points(ref, BOXGEN_GPU_POINTS);
  std::vector<Exact> exact;
  Evaluations e;
  const auto fetch = [](int j0, auto... rest) {
    return static_cast<Real>(exact_reference::data_value(IntVec{j0, rest...}));
  };
  for (const auto& point : points) {
    exact.push_back(ref.at(point));
    Real x[N], g1[N], g2[N], h[N * (N + 1) / 2];
    for (int i = 0; i < N; ++i) x[i] = static_cast<Real>(to_double(point[i]));
    e.value0.push_back(evaluate(x, fetch, nullptr, nullptr));
    e.value1.push_back(evaluate(x, fetch, g1, nullptr));
    e.value2.push_back(evaluate(x, fetch, g2, h));
    for (int i = 0; i < N; ++i) {
      e.gradient1.push_back(g1[i]);
      e.gradient2.push_back(g2[i]);
      for (int j = 0; j < N; ++j) {
        const int a = std::min(i, j), b = std::max(i, j);
        e.hessian.push_back(h[a * N - a * (a - 1) / 2 + (b - a)]);
      }
    }
  }
  compare(ref, exact, e, sizeof(Real) == 8 ? 1e-13 : 2e-6, std::string(f.name) + ".cuh");
}

const Filter& filter(const std::string& name) {
  for (const auto& f : kFilters)
    if (name == f.name) return f;
  throw std::invalid_argument(name);
}

#define BOXGEN_CUDA_HOST_TEST(NS, N)                                                             \
  TEST(CudaHost, NS##Float) {                                                                    \
    check<float, N>(filter(#NS), [](const float* x, const auto& fetch, float* g, float* h) {     \
      return generated::NS::cuda::evaluate(x, fetch, g, h);                                      \
    });                                                                                          \
  }                                                                                              \
  TEST(CudaHost, NS##Double) {                                                                   \
    check<double, N>(filter(#NS), [](const double* x, const auto& fetch, double* g, double* h) { \
      return generated::NS::cuda::evaluate(x, fetch, g, h);                                      \
    });                                                                                          \
  }

BOXGEN_CUDA_HOST_TEST(m7, 3)
BOXGEN_CUDA_HOST_TEST(m8, 3)
BOXGEN_CUDA_HOST_TEST(m12, 3)
BOXGEN_CUDA_HOST_TEST(fcc6, 3)
BOXGEN_CUDA_HOST_TEST(tricubic, 3)
BOXGEN_CUDA_HOST_TEST(cart7, 3)
BOXGEN_CUDA_HOST_TEST(five, 2)

}  // namespace
}  // namespace boxgen::generator::gpu_test
