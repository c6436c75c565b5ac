// The CUDA target on the CPU: the emitted headers (boxgen emit --target cuda) built as plain C++17
// by the host compiler, as a CPU caller of the device code would use them, each path once per
// point. The PTX compile of the same headers is the test CudaHeadersCompileToPtx
// (tests/gpu/CMakeLists.txt).
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

// The sample V(j) of the exact reference at lattice point j, as the evaluators' fetch.
template <class Real>
struct HashFetch {
  template <class... J>
  Real operator()(J... j) const {
    return static_cast<Real>(exact_reference::data_value(IntVec{j...}));
  }
};

template <class Real>
using Evaluate = Real (*)(const Real*, const HashFetch<Real>&, Real*, Real*);

template <class Real, int N>
Evaluations run(Evaluate<Real> evaluate, const std::vector<RatVec>& points) {
  Evaluations e;
  const HashFetch<Real> fetch;
  for (const auto& point : points) {
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
  return e;
}

}  // namespace

template <class Real>
Evaluations evaluate_cuda_host(const Filter& f, const ExactCase& c) {
#define BOXGEN_CUDA_FILTER(NS, N) \
  if (std::string(f.name) == #NS) \
    return run<Real, N>(&generated::NS::cuda::evaluate<Real, HashFetch<Real>>, c.points);
  BOXGEN_CUDA_FILTER(m7, 3)
  BOXGEN_CUDA_FILTER(m8, 3)
  BOXGEN_CUDA_FILTER(m12, 3)
  BOXGEN_CUDA_FILTER(fcc6, 3)
  BOXGEN_CUDA_FILTER(tricubic, 3)
  BOXGEN_CUDA_FILTER(cart7, 3)
  BOXGEN_CUDA_FILTER(five, 2)
#undef BOXGEN_CUDA_FILTER
  ADD_FAILURE() << "no CUDA header for " << f.name;
  return {};
}

template Evaluations evaluate_cuda_host<float>(const Filter&, const ExactCase&);
template Evaluations evaluate_cuda_host<double>(const Filter&, const ExactCase&);

}  // namespace boxgen::generator::gpu_test
