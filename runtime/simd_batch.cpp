// Compiled once per Highway target: foreach_target.h re-includes this file with HWY_TARGET set to
// each instruction set (SSE4, AVX2, AVX-512 and the portable fallback), and HWY_EXPORT /
// HWY_DYNAMIC_DISPATCH call the best one the CPU supports.
#include "runtime/simd_batch.h"

// SSSE3 adds nothing over SSE4 here and costs one more compilation of every orbit polynomial.
// The sanitizer and fuzz builds define BOXGEN_SIMD_TWO_TARGETS and keep only the portable fallback
// and AVX2: the kernels are not instrumented there, so more targets would cost compile time and
// check nothing. The release build compiles them all and tests the one the CPU dispatches to.
#ifndef HWY_DISABLED_TARGETS
#ifdef BOXGEN_SIMD_TWO_TARGETS
#define HWY_DISABLED_TARGETS (HWY_SSSE3 | HWY_SSE4 | HWY_AVX3 | HWY_AVX3_DL)
#else
#define HWY_DISABLED_TARGETS HWY_SSSE3
#endif
#endif

#undef HWY_TARGET_INCLUDE
#define HWY_TARGET_INCLUDE "runtime/simd_batch.cpp"
#include <hwy/foreach_target.h>  // IWYU pragma: keep
// clang-format off: foreach_target.h must come first
#include <hwy/highway.h>
// clang-format on

#include <array>
#include <cstddef>
#include <cstdlib>
#include <cstring>
#include <utility>

#include "generated/registry.hpp"
#include "runtime/simd_kernels-inl.h"
#include "runtime/stencil_steps.h"

HWY_BEFORE_NAMESPACE();
namespace boxgen::runtime::simd::HWY_NAMESPACE {
namespace hn = hwy::HWY_NAMESPACE;
namespace support = boxgen::generated::support;

template <class T>
void LocateChunk(int filter, const double* points, const Frame& frame, T* out) {
  generated::with_filter(filter, [&](auto entry) {
    locate_lanes<typename decltype(entry)::Traits>(points, frame, out);
  });
}

void LocateChunkFloat(int filter, const double* points, const Frame& frame, float* out) {
  LocateChunk(filter, points, frame, out);
}
void LocateChunkDouble(int filter, const double* points, const Frame& frame, double* out) {
  LocateChunk(filter, points, frame, out);
}

template <class T>
void OrbitChunk(int filter, int orbit, int order, const T* v, const T* x, T* out, int lanes) {
  generated::with_filter(filter, [&](auto entry) {
    using Tr = typename decltype(entry)::Traits;
    if (order == support::kValue) return run<Tr, support::kValue>(orbit, v, x, out, lanes);
    if (order == support::kGradient) return run<Tr, support::kGradient>(orbit, v, x, out, lanes);
    run<Tr, support::kHessian>(orbit, v, x, out, lanes);
  });
}

void OrbitChunkFloat(int filter, int orbit, int order, const float* v, const float* x, float* out,
                     int lanes) {
  OrbitChunk(filter, orbit, order, v, x, out, lanes);
}
void OrbitChunkDouble(int filter, int orbit, int order, const double* v, const double* x,
                      double* out, int lanes) {
  OrbitChunk(filter, orbit, order, v, x, out, lanes);
}
template <class T>
void EvaluateChunk(int filter, int order, const double* points, const Frame& frame,
                   const LinearVolume<T>& volume, T* out) {
  generated::with_filter(filter, [&](auto entry) {
    using Tr = typename decltype(entry)::Traits;
    if constexpr (kStencilSteps<Tr>.consistent) chunk_for<Tr>(order, points, frame, volume, out);
  });
}

void EvaluateChunkFloat(int filter, int order, const double* points, const Frame& frame,
                        const LinearVolume<float>& volume, float* out) {
  EvaluateChunk(filter, order, points, frame, volume, out);
}
void EvaluateChunkDouble(int filter, int order, const double* points, const Frame& frame,
                         const LinearVolume<double>& volume, double* out) {
  EvaluateChunk(filter, order, points, frame, volume, out);
}
const char* TargetName() { return hwy::TargetName(HWY_TARGET); }
bool IsVector() { return HWY_TARGET != HWY_EMU128 && HWY_TARGET != HWY_SCALAR; }

}  // namespace boxgen::runtime::simd::HWY_NAMESPACE
HWY_AFTER_NAMESPACE();

#if HWY_ONCE
namespace boxgen::runtime::simd {

HWY_EXPORT(OrbitChunkFloat);
HWY_EXPORT(OrbitChunkDouble);
HWY_EXPORT(TargetName);
HWY_EXPORT(IsVector);
HWY_EXPORT(LocateChunkFloat);
HWY_EXPORT(LocateChunkDouble);
HWY_EXPORT(EvaluateChunkFloat);
HWY_EXPORT(EvaluateChunkDouble);

void locate_chunk(int filter, const double* points, const Frame& frame, float* out) {
  HWY_DYNAMIC_DISPATCH(LocateChunkFloat)(filter, points, frame, out);
}
void locate_chunk(int filter, const double* points, const Frame& frame, double* out) {
  HWY_DYNAMIC_DISPATCH(LocateChunkDouble)(filter, points, frame, out);
}

void evaluate_chunk(int filter, int order, const double* points, const Frame& frame,
                    const LinearVolume<float>& volume, float* out) {
  HWY_DYNAMIC_DISPATCH(EvaluateChunkFloat)(filter, order, points, frame, volume, out);
}
void evaluate_chunk(int filter, int order, const double* points, const Frame& frame,
                    const LinearVolume<double>& volume, double* out) {
  HWY_DYNAMIC_DISPATCH(EvaluateChunkDouble)(filter, order, points, frame, volume, out);
}

bool has_evaluate_chunk(int filter) {
  bool has = false;
  generated::with_filter(filter, [&](auto entry) {
    has = kStencilSteps<typename decltype(entry)::Traits>.consistent;
  });
  return has;
}

const char* target_name() { return HWY_DYNAMIC_DISPATCH(TargetName)(); }

bool enabled() {
  static const bool vector = HWY_DYNAMIC_DISPATCH(IsVector)();
  if (!vector) return false;
  const char* env = std::getenv("BOXGEN_SIMD");
  return !(env && (std::strcmp(env, "0") == 0 || std::strcmp(env, "off") == 0));
}

void orbit_chunk(int filter, int orbit, int order, const float* v, const float* x, float* out,
                 int lanes) {
  HWY_DYNAMIC_DISPATCH(OrbitChunkFloat)(filter, orbit, order, v, x, out, lanes);
}
void orbit_chunk(int filter, int orbit, int order, const double* v, const double* x, double* out,
                 int lanes) {
  HWY_DYNAMIC_DISPATCH(OrbitChunkDouble)(filter, orbit, order, v, x, out, lanes);
}

namespace {

// The registry's kernels as simd::Kernels: registry filter I through the dispatch above.
template <int I, class T>
void registry_locate(const double* points, const Frame& frame, T* out) {
  locate_chunk(I, points, frame, out);
}
template <int I, class T>
void registry_orbit(int orbit, int order, const T* v, const T* x, T* out, int lanes) {
  orbit_chunk(I, orbit, order, v, x, out, lanes);
}
template <int I, class T>
void registry_chunk(int order, const double* points, const Frame& frame,
                    const LinearVolume<T>& volume, T* out) {
  evaluate_chunk(I, order, points, frame, volume, out);
}
template <std::size_t... I>
std::array<Kernels, sizeof...(I)> registry_table(std::index_sequence<I...> /*filters*/) {
  return {Kernels{&registry_locate<I, float>, &registry_locate<I, double>,
                  &registry_orbit<I, float>, &registry_orbit<I, double>,
                  has_evaluate_chunk(I) ? &registry_chunk<I, float> : nullptr,
                  has_evaluate_chunk(I) ? &registry_chunk<I, double> : nullptr}...};
}

}  // namespace

const Kernels* registry_kernels(int index) {
  static const auto table = registry_table(std::make_index_sequence<generated::kFilterCount>{});
  if (index < 0 || index >= generated::kFilterCount) return nullptr;
  return &table[static_cast<std::size_t>(index)];
}

}  // namespace boxgen::runtime::simd
#endif  // HWY_ONCE
