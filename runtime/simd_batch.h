// The SIMD batch path of the runtime (Reconstructor evaluates through
// runtime/emitted_spline.h): the generated orbit polynomial of a filter
// (generated/registry.hpp) evaluated for many points at once, one point per SIMD lane. The
// polynomial code is the generated one, instantiated with a vector type instead of T (it uses
// only constants, +, -, * and unary minus); the glue that locates points and gathers their
// stencils stays scalar (emitted_spline.h). Google Highway picks the instruction set at run
// time (dynamic dispatch: SSE4, AVX2 or AVX-512 where present), so one binary runs on any
// x86-64 and no -march flag is needed.
#pragma once

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
// for bit the same), and the runtime's stencil box check. In: world[i * kChunk + lane]. Out, rows
// of kChunk: the corner floor(x + c) (n rows), the cell (-1: none), the reference coordinates (n
// rows), the cell's orbit, and 1 where the point is near (see Frame), its cell exists and its
// whole published reach is inside [0, limit], else 0 (the caller then takes the scalar path, which
// decides and reports). Integers are carried as T: callers keep upper[i] below 2^22.
void locate_chunk(int filter, const double* world, const Frame& frame, float* out);
void locate_chunk(int filter, const double* world, const Frame& frame, double* out);

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

// The kernels of one filter, as the engine calls them (emitted_spline.h): locate_chunk and
// orbit_chunk above bound to a registry filter (registry_kernels), or a filter's own, compiled
// with it (runtime/simd_kernels-inl.h: kernels_for<Traits>(), as a filter compiled at run time
// by loader/ does).
struct Kernels {
  void (*locate_float)(const double* world, const Frame& frame, float* out);
  void (*locate_double)(const double* world, const Frame& frame, double* out);
  void (*orbit_float)(int orbit, int order, const float* v, const float* x, float* out, int lanes);
  void (*orbit_double)(int orbit, int order, const double* v, const double* x, double* out,
                       int lanes);

  void locate(const double* world, const Frame& frame, float* out) const {
    locate_float(world, frame, out);
  }
  void locate(const double* world, const Frame& frame, double* out) const {
    locate_double(world, frame, out);
  }
  void orbit(int o, int order, const float* v, const float* x, float* out, int lanes) const {
    orbit_float(o, order, v, x, out, lanes);
  }
  void orbit(int o, int order, const double* v, const double* x, double* out, int lanes) const {
    orbit_double(o, order, v, x, out, lanes);
  }
};

// The kernels of registry filter `index` (generated/registry.hpp), or null outside the registry.
const Kernels* registry_kernels(int index);

}  // namespace boxgen::runtime::simd
