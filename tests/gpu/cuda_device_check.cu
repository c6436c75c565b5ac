// The emitted CUDA evaluators run on an NVIDIA GPU, built with nvcc: a GPU-only check, not in CI
// (CI has no GPU and no nvcc). scripts/gpu_check.sh builds and runs it where a GPU is lent:
//   nvcc -std=c++17 -O3 -arch=native -I EMITTED -I . tests/gpu/cuda_device_check.cu -o check
// in the source tree (-I . finds support/cell_glue.h, which the headers include), with EMITTED
// the folder of the headers that `boxgen emit NAME --target cuda` writes (the build emits them
// into build/tests/gpu/emitted/), then ./check. For every registry filter, 100000 random points
// are evaluated on the device (value only; value, gradient and Hessian) and by the same header's
// host build, with the samples of tests/emitted/exact_reference.h's data_value. In CI the host
// build is checked against the exact rational values within kFloatTolerance (2e-6 of max|V|,
// Hessians 4x; tests/gpu/gpu_test_support.h); the device may round differently (contractions
// into FMA), so it must agree with the host within twice that. Exit 1 on any disagreement.
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <vector>

#include "cart7.cuh"
#include "fcc6.cuh"
#include "m12.cuh"
#include "m7.cuh"
#include "m8.cuh"
#include "tricubic.cuh"

namespace {

constexpr double kMaxV = 1000;
constexpr double kFloatTolerance = 2e-6;
constexpr int kPoints = 100000;

// data_value of tests/emitted/exact_reference.h, for host and device.
struct HashFetch {
  __host__ __device__ float operator()(int j0, int j1, int j2) const {
    std::uint64_t h = 1469598103934665603ull;
    const int j[3] = {j0, j1, j2};
    for (int v : j) h = (h ^ static_cast<std::uint64_t>(v + 4096)) * 1099511628211ull;
    return static_cast<float>(static_cast<double>(h % 2001) - kMaxV);
  }
};

// One filter's evaluate<float, HashFetch> as a type, for the kernel's template argument.
#define BOXGEN_FILTER(NS)                                                                   \
  struct NS {                                                                               \
    __host__ __device__ static float evaluate(const float* x, float* gradient, float* hessian) { \
      return boxgen::generated::NS::cuda::evaluate<float, HashFetch>(x, HashFetch{}, gradient, \
                                                                     hessian);              \
    }                                                                                       \
  };
BOXGEN_FILTER(m7)
BOXGEN_FILTER(m8)
BOXGEN_FILTER(m12)
BOXGEN_FILTER(fcc6)
BOXGEN_FILTER(tricubic)
BOXGEN_FILTER(cart7)
#undef BOXGEN_FILTER

// out[11 p ..]: value only, then value, gradient (3) and Hessian (6) of the full path.
template <class F>
__global__ void evaluate_points(const float* points, int count, float* out) {
  const int p = blockIdx.x * blockDim.x + threadIdx.x;
  if (p >= count) return;
  float* o = out + 11 * p;
  o[0] = F::evaluate(points + 3 * p, nullptr, nullptr);
  o[1] = F::evaluate(points + 3 * p, o + 2, o + 5);
}

template <class F>
void evaluate_host(const std::vector<float>& points, std::vector<float>& out) {
  for (int p = 0; p < kPoints; ++p) {
    float* o = out.data() + 11 * p;
    o[0] = F::evaluate(points.data() + 3 * p, nullptr, nullptr);
    o[1] = F::evaluate(points.data() + 3 * p, o + 2, o + 5);
  }
}

bool cuda_ok(cudaError_t e, const char* what) {
  if (e == cudaSuccess) return true;
  std::fprintf(stderr, "cuda_device_check: %s: %s\n", what, cudaGetErrorString(e));
  return false;
}

// Device against host for one filter; false on any disagreement or CUDA error.
template <class F>
bool check(const char* name, const std::vector<float>& points) {
  std::vector<float> host(11 * kPoints), device(11 * kPoints);
  evaluate_host<F>(points, host);
  float *d_points = nullptr, *d_out = nullptr;
  if (!cuda_ok(cudaMalloc(&d_points, points.size() * sizeof(float)), "cudaMalloc") ||
      !cuda_ok(cudaMalloc(&d_out, device.size() * sizeof(float)), "cudaMalloc"))
    return false;
  cudaMemcpy(d_points, points.data(), points.size() * sizeof(float), cudaMemcpyHostToDevice);
  evaluate_points<F><<<(kPoints + 127) / 128, 128>>>(d_points, kPoints, d_out);
  const bool ran = cuda_ok(cudaGetLastError(), "launch") &&
                   cuda_ok(cudaDeviceSynchronize(), "kernel") &&
                   cuda_ok(cudaMemcpy(device.data(), d_out, device.size() * sizeof(float),
                                      cudaMemcpyDeviceToHost),
                           "copy back");
  cudaFree(d_points);
  cudaFree(d_out);
  if (!ran) return false;
  double worst[3] = {0, 0, 0};  // values, gradients, Hessians, relative to max|V|
  for (int p = 0; p < kPoints; ++p)
    for (int k = 0; k < 11; ++k) {
      const double d = std::abs(double(host[11 * p + k]) - double(device[11 * p + k])) / kMaxV;
      const int kind = k < 2 ? 0 : (k < 5 ? 1 : 2);
      if (!(d <= worst[kind])) worst[kind] = d;  // NaN counts as worst
    }
  const bool ok = worst[0] <= 2 * kFloatTolerance && worst[1] <= 2 * kFloatTolerance &&
                  worst[2] <= 8 * kFloatTolerance;
  std::printf("%-9s device vs host, worst / max|V|: value %.2e, gradient %.2e, Hessian %.2e  %s\n",
              name, worst[0], worst[1], worst[2], ok ? "ok" : "FAILED");
  return ok;
}

}  // namespace

int main() {
  cudaDeviceProp prop{};
  if (!cuda_ok(cudaGetDeviceProperties(&prop, 0), "no CUDA device")) return 1;
  std::printf("device: %s\n", prop.name);
  std::vector<float> points(3 * kPoints);
  std::uint64_t s = 12345;
  for (float& x : points) {  // lattice coordinates in [0, 64), on a 2^-16 grid
    s = s * 6364136223846793005ull + 1442695040888963407ull;
    x = static_cast<float>((s >> 40) % (64u << 16)) / 65536.0f;
  }
  bool ok = true;
  ok &= check<m7>("m7", points);
  ok &= check<m8>("m8", points);
  ok &= check<m12>("m12", points);
  ok &= check<fcc6>("fcc6", points);
  ok &= check<tricubic>("tricubic", points);
  ok &= check<cart7>("cart7", points);
  std::printf("%s\n", ok ? "all filters agree" : "DISAGREEMENT");
  return ok ? 0 : 1;
}
