// The SIMD batch path of the runtime (Reconstructor evaluates through
// runtime/emitted_spline.h): the generated orbit polynomial of a filter
// (generated/registry.hpp) evaluated for many points at once, one point per SIMD lane. The
// polynomial code is the generated one, instantiated with a vector type instead of T (it uses
// only constants, +, -, * and unary minus); the glue that locates points and gathers their
// stencils stays scalar (emitted_spline.h). Google Highway picks the instruction set at run
// time (dynamic dispatch: SSE4, AVX2 or AVX-512 where present), so one binary runs on any
// x86-64 and no -march flag is needed.
#pragma once
#include <cstdint>
#include <type_traits>

namespace boxgen::runtime::simd {

// Points per kernel call: a multiple of every target's lane count (AVX-512: 16 floats, 8 doubles).
inline constexpr int kChunk = 16;

// Highway's name of the instruction set the kernels dispatch to on this machine ("AVX2",
// "AVX3" for AVX-512, "SSE4", "EMU128" when no vector unit is usable).
const char* target_name();

// Whether Reconstructor::evaluate takes the SIMD path: the dispatched target is a vector one and
// the environment variable BOXGEN_SIMD is not "0" or "off" (a switch for measuring and checking
// the scalar path, which stays the reference).
bool enabled();

// Rows of locate_chunk's output for a filter of dimension n (kChunk values each).
constexpr int locate_rows(int n) { return 2 * n + 3; }

// A volume's frame for locate_chunk: lattice = (world - origin) / h (per axis), as to_lattice
// computes it; a point goes on only when every lattice coordinate i lies in (lower, upper[i])
// (also false for NaN and infinities); limit[i] is the largest lattice coordinate of the volume.
struct Frame {
  double origin[3];
  double h[3];
  double lower;
  double upper[3];
  double limit[3];
};

// For kChunk points of registry filter `filter` at once: the lattice coordinates, then
// support/evaluator_support.hpp's locate_in() on packs of T (the scalar path's own code, so bit
// for bit the same), and the runtime's stencil box check. In: points[3 * lane + i], the world
// coordinates point after point. Out, rows of kChunk: the corner floor(x + c) (n rows), the cell
// (-1: none), the reference coordinates (n rows), the cell's orbit, and 1 where the point is near
// (see Frame), its cell exists and its whole published reach is inside [0, limit], else 0 (the
// caller then takes the scalar path, which decides and reports). Integers are carried as T: callers
// keep upper[i] below 2^22.
void locate_chunk(int filter, const double* points, const Frame& frame, float* out);
void locate_chunk(int filter, const double* points, const Frame& frame, double* out);

// The orbit polynomial `orbit` of registry filter `filter` at `lanes` (<= kChunk) points, with
// derivatives up to `order` (support::kValue, kGradient, kHessian), in the orbit's reference frame.
// Transposed, lane-minor buffers: v[k * kChunk + lane] the stencil values (k below the orbit's
// stencil size), x[i * kChunk + lane] the reference coordinates, out[j * kChunk + lane] the value
// (j = 0) then the orbit function's d[j - 1]. Lanes from `lanes` up to the next multiple of the
// vector width are computed too, so callers fill them (with any finite data).
void orbit_chunk(int filter, int orbit, int order, const float* v, const float* x, float* out,
                 int lanes);
void orbit_chunk(int filter, int orbit, int order, const double* v, const double* x, double* out,
                 int lanes);

// The integer type of the vector unit's gather indices for samples of type T.
template <class T>
using GatherIndex = std::conditional_t<sizeof(T) == 4, std::int32_t, std::int64_t>;

// A volume whose storage is linear up to the coset parity (stencils.h, LinearLayout), as
// evaluate_chunk reads it: lattice point j lies at samples[j . stride - (j_0 & 1) coset_shift].
// rows[p * kCellCount + c] (corner parity p = corner_0 & 1, cell c): the index of the cell's
// first stencil sample relative to corner . stride. Every index fits GatherIndex<T> (the caller
// checks).
template <class T>
struct LinearVolume {
  const T* samples;
  const GatherIndex<T>* rows;
  std::int64_t stride[3];
  std::int64_t coset_shift;
};

// Rows of evaluate_chunk's output (kChunk values each): the value, the derivatives in the reference
// frame of each lane's cell (as orbit_chunk's, up to 3 + 6), the lane's cell, and 1 where the lane
// was evaluated (else 0: the point is not near, has no cell or its stencil box is not inside, and
// the caller takes the scalar path).
inline constexpr int kChunkCellRow = 10, kChunkOkRow = 11, kChunkRows = 12;

// For kChunk points of registry filter `filter` on a linear volume, in one call: located as
// locate_chunk does, each lane's stencil gathered by the vector unit's own gathers (its indices
// from the lane's first sample and the steps of stencil_steps.h), the orbit polynomial evaluated
// with derivatives up to `order`. points[3 * lane + i]: the world coordinates, point after point.
void evaluate_chunk(int filter, int order, const double* points, const Frame& frame,
                    const LinearVolume<float>& volume, float* out);
void evaluate_chunk(int filter, int order, const double* points, const Frame& frame,
                    const LinearVolume<double>& volume, double* out);
// Whether registry filter `filter` has evaluate_chunk: its tables have the structure of
// stencil_steps.h.
bool has_evaluate_chunk(int filter);

// The kernels of one filter, as the engine calls them (emitted_spline.h): locate_chunk and
// orbit_chunk above bound to a registry filter (registry_kernels), or a filter's own, compiled
// with it (runtime/simd_kernels-inl.h: kernels_for<Traits>(), as a filter compiled at run time
// by loader/ does).
struct Kernels {
  void (*locate_float)(const double* points, const Frame& frame, float* out);
  void (*locate_double)(const double* points, const Frame& frame, double* out);
  void (*orbit_float)(int orbit, int order, const float* v, const float* x, float* out, int lanes);
  void (*orbit_double)(int orbit, int order, const double* v, const double* x, double* out,
                       int lanes);
  // evaluate_chunk above, or null where the filter's tables lack its structure.
  void (*chunk_float)(int order, const double* points, const Frame& frame,
                      const LinearVolume<float>& volume, float* out);
  void (*chunk_double)(int order, const double* points, const Frame& frame,
                       const LinearVolume<double>& volume, double* out);

  void locate(const double* points, const Frame& frame, float* out) const {
    locate_float(points, frame, out);
  }
  void locate(const double* points, const Frame& frame, double* out) const {
    locate_double(points, frame, out);
  }
  void orbit(int o, int order, const float* v, const float* x, float* out, int lanes) const {
    orbit_float(o, order, v, x, out, lanes);
  }
  void orbit(int o, int order, const double* v, const double* x, double* out, int lanes) const {
    orbit_double(o, order, v, x, out, lanes);
  }
  bool has_chunk() const { return chunk_float != nullptr && chunk_double != nullptr; }
  void chunk(int order, const double* points, const Frame& frame, const LinearVolume<float>& volume,
             float* out) const {
    chunk_float(order, points, frame, volume, out);
  }
  void chunk(int order, const double* points, const Frame& frame,
             const LinearVolume<double>& volume, double* out) const {
    chunk_double(order, points, frame, volume, out);
  }
};

// The kernels of registry filter `index` (generated/registry.hpp), or null outside the registry.
const Kernels* registry_kernels(int index);

}  // namespace boxgen::runtime::simd
