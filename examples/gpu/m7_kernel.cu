// Reconstructs a BCC volume with M7 at a batch of points on an NVIDIA GPU, with the header from
//   boxgen emit m7 --name m7 --target cuda --out .
// and boxgen's headers (the glue m7.cuh includes, support/cell_glue.h) under PREFIX/include/boxgen.
// Build with nvcc (nvcc -std=c++17 -I PREFIX/include/boxgen -c m7_kernel.cu) or, without the
// CUDA SDK, to PTX with clang:
//   clang++ -x cuda --cuda-device-only --cuda-gpu-arch=sm_70 -nocudainc -nocudalib -std=c++17 \
//       -I PREFIX/include/boxgen -O3 -S m7_kernel.cu
// The same header builds as plain C++17 for the host (g++ -std=c++17), which the tests use.
#include "m7.cuh"

// Samples on a box of integer points [lo, lo + side)^3, clamped at its faces.
struct Volume {
  const float* samples;
  int lo[3];
  int side;
  BOXGEN_HOST_DEVICE float operator()(int j0, int j1, int j2) const {
    const int j[3] = {j0, j1, j2};
    int k[3];
    for (int i = 0; i < 3; ++i) {
      const int t = j[i] - lo[i];
      k[i] = t < 0 ? 0 : (t >= side ? side - 1 : t);
    }
    return samples[k[0] + side * (k[1] + side * k[2])];
  }
};

// One thread per point: value, gradient (3) and Hessian (xx xy xz yy yz zz) into out[10 p..].
#if defined(__CUDA__) || defined(__CUDACC__)
__attribute__((global)) void reconstruct(Volume volume, const float* points, int count,
                                         float* out) {
#if defined(__CUDACC__) && !defined(__clang__)
  const int p = blockIdx.x * blockDim.x + threadIdx.x;
#else
  const int p = __nvvm_read_ptx_sreg_ctaid_x() * __nvvm_read_ptx_sreg_ntid_x() +
                __nvvm_read_ptx_sreg_tid_x();
#endif
  if (p >= count) return;
  float* o = out + 10 * p;
  o[0] = boxgen::generated::m7::cuda::evaluate(points + 3 * p, volume, o + 1, o + 4);
}
#endif
