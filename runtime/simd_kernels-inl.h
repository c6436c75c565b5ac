// The SIMD kernels of the runtime's batch path for one emitted evaluator (its Traits Tr):
// locate_lanes (support::locate_in for kChunk points at once) and run (the orbit polynomial, one
// point per lane). A Highway per-target header: include it after hwy/highway.h (once per target
// under foreach_target.h, or once for the static target), inside nothing. simd_batch.cpp
// instantiates it for the registry's filters; a filter compiled at run time (loader/) for its own.
// clang-format off: the toggle of a per-target header comes first
#if defined(BOXGEN_RUNTIME_SIMD_KERNELS_INL_H_) == defined(HWY_TARGET_TOGGLE)
#ifdef BOXGEN_RUNTIME_SIMD_KERNELS_INL_H_
#undef BOXGEN_RUNTIME_SIMD_KERNELS_INL_H_
#else
#define BOXGEN_RUNTIME_SIMD_KERNELS_INL_H_
#endif
// clang-format on

#include <hwy/highway.h>

#include <cstddef>
#include <cstdint>
#include <type_traits>
#include <utility>

#include "runtime/simd_batch.h"
#include "runtime/stencil_steps.h"
#include "support/evaluator_support.hpp"

HWY_BEFORE_NAMESPACE();
namespace boxgen::runtime::simd::HWY_NAMESPACE {
namespace hn = hwy::HWY_NAMESPACE;
namespace support = boxgen::generated::support;

// Buffers are rows of kChunk values: row r starts at r * kRow.
constexpr std::ptrdiff_t kRow = kChunk;

// The number type the generated polynomial code is instantiated with: one point per lane. It has
// exactly what that code uses: T(constant), +, -, * and unary minus.
template <class T>
struct Pack {
  using D = hn::ScalableTag<T>;
  hn::Vec<D> v;

  // HWY_ATTR on every member: they are instantiated from the generated code, which lies outside
  // this target's region, and must still be compiled for this target.
  HWY_ATTR Pack() = default;
  HWY_ATTR explicit Pack(hn::Vec<D> w) : v(w) {}
  // T(c) in the generated code: the constant rounded to T, as in the scalar code.
  HWY_ATTR explicit Pack(double c) : v(hn::Set(D(), static_cast<T>(c))) {}

  HWY_ATTR friend Pack operator+(Pack a, Pack b) { return Pack(hn::Add(a.v, b.v)); }
  HWY_ATTR friend Pack operator-(Pack a, Pack b) { return Pack(hn::Sub(a.v, b.v)); }
  HWY_ATTR friend Pack operator*(Pack a, Pack b) { return Pack(hn::Mul(a.v, b.v)); }
  HWY_ATTR Pack operator-() const { return Pack(hn::Neg(v)); }
};

// flatten: the generated code is a template defined outside this target's region; inlining all of
// it here compiles it for this target's instruction set.
template <class Tr, int Order, class T>
[[gnu::flatten]] HWY_ATTR void run(int orbit, const T* v, const T* x, T* out, int lanes) {
  using P = Pack<T>;
  constexpr int n = Tr::kDimension;
  constexpr int kDerivatives =
      Order == support::kValue ? 0
                               : (Order == support::kGradient ? n : n + support::hessian_size(n));
  const typename P::D d;
  const int width = static_cast<int>(hn::Lanes(d));
  const int size = Tr::kOrbitStencilSize[orbit];
  for (int at = 0; at < lanes; at += width) {
    P pv[Tr::kStencilSize];
    for (int k = 0; k < Tr::kStencilSize; ++k)
      pv[k] = k < size ? P(hn::LoadU(d, v + k * kRow + at)) : P(0.0);
    P px[n];
    for (int i = 0; i < n; ++i) px[i] = P(hn::LoadU(d, x + i * kRow + at));
    P pd[kDerivatives + 1];  // the orbit function fills d[0, kDerivatives); zeroed for the compiler
    for (P& e : pd) e = P(0.0);
    const P value = Tr::template orbit<Order>(orbit, pv, px, pd);
    hn::StoreU(value.v, d, out + at);
    for (int j = 0; j < kDerivatives; ++j) hn::StoreU(pd[j].v, d, out + (j + 1) * kRow + at);
  }
}

// The tables locate() reads per lane, as numbers of type T (small integers: exact), so that a
// gather fetches them: the cell of (cube, knot key), and per cell its orbit and its map onto the
// orbit's reference region.
template <class Tr, class T>
struct LocateTables {
  T lookup[Tr::kCubeCount * Tr::kLookupSize];
  T orbit[Tr::kCellCount];
  T perm[Tr::kDimension][Tr::kCellCount];
  T sign[Tr::kDimension][Tr::kCellCount];
  T a[Tr::kDimension][Tr::kCellCount];
};

template <class Tr, class T>
constexpr LocateTables<Tr, T> locate_tables() {
  LocateTables<Tr, T> t{};
  for (int c = 0; c < Tr::kCubeCount; ++c)
    for (int k = 0; k < Tr::kLookupSize; ++k)
      t.lookup[c * Tr::kLookupSize + k] = static_cast<T>(Tr::kLookup[c][k]);
  for (int c = 0; c < Tr::kCellCount; ++c) {
    t.orbit[c] = static_cast<T>(Tr::kCells[c].orbit);
    for (int i = 0; i < Tr::kDimension; ++i) {
      t.perm[i][c] = static_cast<T>(Tr::kCells[c].perm[i]);
      t.sign[i][c] = static_cast<T>(Tr::kCells[c].sign[i]);
      t.a[i][c] = static_cast<T>(Tr::kCells[c].a[i]);
    }
  }
  return t;
}

template <class Tr, class T>
inline constexpr LocateTables<Tr, T> kLocateTables = locate_tables<Tr, T>();

// The arithmetic of support::locate_in() on one point per lane (support/evaluator_support.hpp
// lists what it must provide): integers are carried as T (exact, as the caller keeps |x| below
// 2^23), table lookups are gathers, and a missing cell stays -1 for the caller (it takes the
// scalar path, which settles it).
template <class T>
struct PackArith {
  using Scalar = T;
  using Real = Pack<T>;
  using Whole = Pack<T>;
  using D = typename Pack<T>::D;

  HWY_ATTR static Real floor(Real s) { return Real(hn::Floor(s.v)); }
  HWY_ATTR static Real real(Whole w) { return w; }
  HWY_ATTR static Whole whole(Real f) { return f; }
  HWY_ATTR static Whole constant(std::int64_t c) { return Whole(static_cast<double>(c)); }
  HWY_ATTR static Real constant_real(T c) { return Real(static_cast<double>(c)); }
  HWY_ATTR static Whole floor_div(Whole a, std::int64_t b) {
    return b == 1 ? a : Whole(hn::Floor(hn::Div(a.v, hn::Set(D(), static_cast<T>(b)))));
  }
  HWY_ATTR static Whole at_least(Real s, T c) {
    return Whole(hn::IfThenElseZero(hn::Ge(s.v, hn::Set(D(), c)), hn::Set(D(), T(1))));
  }
  // Any valid index for the lanes without a cell: their gathers are not used.
  HWY_ATTR static auto index(Whole cell) {
    return hn::ConvertTo(hn::RebindToSigned<D>(), hn::Max(cell.v, hn::Zero(D())));
  }
  template <class Tr>
  HWY_ATTR static Whole cell_of(Whole cube, Whole key, const Real* /*r*/) {
    const Whole entry = cube * constant(Tr::kLookupSize) + key;
    return Whole(hn::GatherIndex(D(), kLocateTables<Tr, T>.lookup,
                                 hn::ConvertTo(hn::RebindToSigned<D>(), entry.v)));
  }
  template <class Tr>
  HWY_ATTR static support::CellMap<Whole, Real> cell_map(Whole cell, int i) {
    const auto at = index(cell);
    const auto& t = kLocateTables<Tr, T>;
    return {Whole(hn::GatherIndex(D(), t.perm[i], at)), Real(hn::GatherIndex(D(), t.sign[i], at)),
            Real(hn::GatherIndex(D(), t.a[i], at))};
  }
  template <int N>
  HWY_ATTR static Pack<T> pick(Whole p, const Pack<T>* xs) {
    hn::Vec<D> r = xs[N - 1].v;
    for (int q = N - 2; q >= 0; --q)
      r = hn::IfThenElse(hn::Eq(p.v, hn::Set(D(), static_cast<T>(q))), xs[q].v, r);
    return Pack<T>(r);
  }
};

// World to lattice coordinates in double, as BccVolume::to_lattice, rounded to T as the scalar
// path rounds them; x[i * kRow + lane] and near[lane] (1 or 0). points[3 * lane + i]: the chunk's
// world coordinates, point after point. Lanes that are not near get x = 0, so that nothing below
// converts a huge or non-finite number to an integer.
template <class T>
HWY_ATTR void lattice_lanes(const double* points, const Frame& frame, T* x, T* near) {
  const hn::ScalableTag<double> dd;
  const hn::Rebind<T, decltype(dd)> dt;
  const auto to_t = [&](hn::Vec<decltype(dd)> v) HWY_ATTR {
    if constexpr (std::is_same_v<T, double>) {
      static_cast<void>(dt);
      return v;
    } else {
      return hn::DemoteTo(dt, v);
    }
  };
  const int width = static_cast<int>(hn::Lanes(dd));
  for (int at = 0; at < kChunk; at += width) {
    hn::Vec<decltype(dd)> lattice[3];
    hn::LoadInterleaved3(dd, points + std::ptrdiff_t{3} * at, lattice[0], lattice[1], lattice[2]);
    auto ok = hn::Eq(hn::Zero(dd), hn::Zero(dd));
    for (int i = 0; i < 3; ++i) {
      lattice[i] =
          hn::Div(hn::Sub(lattice[i], hn::Set(dd, frame.origin[i])), hn::Set(dd, frame.h[i]));
      ok = hn::And(ok, hn::And(hn::Gt(lattice[i], hn::Set(dd, frame.lower)),
                               hn::Lt(lattice[i], hn::Set(dd, frame.upper[i]))));
    }
    for (int i = 0; i < 3; ++i)
      hn::StoreU(to_t(hn::IfThenElseZero(ok, lattice[i])), dt, x + i * kRow + at);
    hn::StoreU(to_t(hn::IfThenElseZero(ok, hn::Set(dd, 1.0))), dt, near + at);
  }
}

// One vector of located points: support::locate_in()'s corner, cell and reference coordinates,
// and `ok` where the point is near, has a cell and its stencil box lies inside the volume.
template <class Tr, class T>
struct LocatedPack {
  Pack<T> corner[Tr::kDimension], cell, ref[Tr::kDimension];
  hn::Mask<typename Pack<T>::D> ok;
};

// support::locate_in() for the vector of lanes at `at` of lattice_lanes' output (the same
// operations in the same order, so the same cells and the same reference coordinates, bit for
// bit), and the stencil box check of the runtime.
template <class Tr, class T>
HWY_ATTR LocatedPack<Tr, T> locate_pack(const T* x, const T* near, int at, const Frame& frame) {
  constexpr int n = Tr::kDimension;
  using A = PackArith<T>;
  using P = Pack<T>;
  const typename A::D d;
  LocatedPack<Tr, T> l;
  P xs[n];
  for (int i = 0; i < n; ++i) xs[i] = P(hn::LoadU(d, x + i * kRow + at));
  support::locate_in<Tr, A>(xs, l.corner, l.cell, l.ref);
  auto ok = hn::And(hn::Ge(l.cell.v, hn::Zero(d)), hn::Gt(hn::LoadU(d, near + at), hn::Zero(d)));
  for (int i = 0; i < n; ++i) {
    const auto lo = hn::Add(l.corner[i].v, hn::Set(d, static_cast<T>(Tr::kStencilReachLo[i])));
    const auto hi = hn::Add(l.corner[i].v, hn::Set(d, static_cast<T>(Tr::kStencilReachHi[i])));
    ok = hn::And(ok, hn::And(hn::Ge(lo, hn::Zero(d)),
                             hn::Le(hi, hn::Set(d, static_cast<T>(frame.limit[i])))));
  }
  l.ok = ok;
  return l;
}

// support::locate_in() for kChunk points at once and the stencil box check (locate_chunk).
template <class Tr, class T>
[[gnu::flatten]] HWY_ATTR void locate_lanes(const double* points, const Frame& frame, T* out) {
  constexpr int n = Tr::kDimension;
  static_assert(n == 3 && Tr::kScale == 1, "3-D filters, not scaled pairs");
  using A = PackArith<T>;
  const typename A::D d;
  alignas(64) T x[n * kRow];
  alignas(64) T near[kChunk];
  lattice_lanes(points, frame, x, near);
  const int width = static_cast<int>(hn::Lanes(d));
  for (int at = 0; at < kChunk; at += width) {
    const LocatedPack<Tr, T> l = locate_pack<Tr>(x, near, at, frame);
    hn::StoreU(l.cell.v, d, out + n * kRow + at);
    hn::StoreU(hn::IfThenElseZero(l.ok, hn::Set(d, T(1))), d, out + (2 * n + 2) * kRow + at);
    hn::StoreU(hn::GatherIndex(d, kLocateTables<Tr, T>.orbit, A::index(l.cell)), d,
               out + (2 * n + 1) * kRow + at);
    for (int i = 0; i < n; ++i) {
      hn::StoreU(l.corner[i].v, d, out + i * kRow + at);
      hn::StoreU(l.ref[i].v, d, out + (n + 1 + i) * kRow + at);
    }
  }
}

// m * s for a small constant m >= 0, by shifts and additions (no vector multiplication of 64-bit
// integers on AVX2; fewer cycles than one of 32-bit integers).
template <int M, class V>
HWY_ATTR V times(V s) {
  if constexpr (M == 0) {
    return hn::Zero(hn::DFromV<V>());
  } else if constexpr (M == 1) {
    return s;
  } else if constexpr (M % 2 == 0) {
    return hn::ShiftLeft<1>(times<M / 2>(s));
  } else {
    return hn::Add(times<M - 1>(s), s);
  }
}

// index + m s for a constant m (of either sign).
template <int M, class V>
HWY_ATTR V add_times(V index, V s) {
  if constexpr (M > 0) return hn::Add(index, times<M>(s));
  if constexpr (M < 0) return hn::Sub(index, times<-M>(s));
  return index;
}

// The storage index of sample K of orbit O: the first sample's, plus the step of stencil_steps.h
// through the lane's axis strides, plus the coset flip where the step is odd.
template <class Tr, int O, int K, class V>
HWY_ATTR V sample_index(V first, const V* axis, V flip) {
  constexpr auto& steps = kStencilSteps<Tr>;
  V index = add_times<steps.step[O][K][0]>(first, axis[0]);
  index = add_times<steps.step[O][K][1]>(index, axis[1]);
  index = add_times<steps.step[O][K][2]>(index, axis[2]);
  if constexpr ((steps.step[O][K][0] & 1) != 0) index = hn::Add(index, flip);
  return index;
}

// The stencil of orbit O gathered: pv[k] for k below the orbit's stencil size.
template <class Tr, int O, class T, class V, int... K>
HWY_ATTR void gather_orbit(const T* samples, V first, const V* axis, V flip, Pack<T>* pv,
                           std::integer_sequence<int, K...> /*samples*/) {
  const typename Pack<T>::D d;
  ((pv[K] = Pack<T>(hn::GatherIndex(d, samples, sample_index<Tr, O, K>(first, axis, flip)))), ...);
}

// evaluate_chunk (simd_batch.h) for one orbit O: the lanes of `lanes` (the others gather sample 0
// and their results are not used) take the orbit's polynomial.
template <class Tr, int Order, int O, class T, class V, class M>
HWY_ATTR void evaluate_orbit(const LinearVolume<T>& volume, const LocatedPack<Tr, T>& l, M lanes,
                             V first, const V* axis, V flip, Pack<T>& value, Pack<T>* derivatives) {
  constexpr int n = Tr::kDimension;
  constexpr int kDerivatives =
      Order == support::kValue ? 0
                               : (Order == support::kGradient ? n : n + support::hessian_size(n));
  constexpr int size = Tr::kOrbitStencilSize[O];
  const hn::DFromV<V> di;
  const auto m = hn::RebindMask(di, lanes);
  V axis_in[n];
  for (int i = 0; i < n; ++i) axis_in[i] = hn::IfThenElseZero(m, axis[i]);
  Pack<T> pv[Tr::kStencilSize];
  gather_orbit<Tr, O>(volume.samples, hn::IfThenElseZero(m, first), axis_in,
                      hn::IfThenElseZero(m, flip), pv, std::make_integer_sequence<int, size>{});
  for (int k = size; k < Tr::kStencilSize; ++k) pv[k] = Pack<T>(0.0);
  Pack<T>
      pd[kDerivatives + 1];  // the orbit function fills d[0, kDerivatives); zeroed for the compiler
  for (Pack<T>& e : pd) e = Pack<T>(0.0);
  const Pack<T> v = Tr::template orbit<Order>(O, pv, l.ref, pd);
  value = Pack<T>(hn::IfThenElse(lanes, v.v, value.v));
  for (int j = 0; j < kDerivatives; ++j)
    derivatives[j] = Pack<T>(hn::IfThenElse(lanes, pd[j].v, derivatives[j].v));
}

// evaluate_chunk (simd_batch.h) for Tr on this target.
template <class Tr, int Order, class T, int... O>
[[gnu::flatten]] HWY_ATTR void evaluate_lanes(const double* points, const Frame& frame,
                                              const LinearVolume<T>& volume, T* out,
                                              std::integer_sequence<int, O...> /*orbits*/) {
  constexpr int n = Tr::kDimension;
  static_assert(n == 3 && Tr::kScale == 1, "3-D filters, not scaled pairs");
  constexpr int kDerivatives =
      Order == support::kValue ? 0
                               : (Order == support::kGradient ? n : n + support::hessian_size(n));
  using A = PackArith<T>;
  using P = Pack<T>;
  const typename A::D d;
  const hn::RebindToSigned<decltype(d)> di;
  using V = hn::Vec<decltype(di)>;
  alignas(64) T x[n * kRow];
  alignas(64) T near[kChunk];
  lattice_lanes(points, frame, x, near);
  const int width = static_cast<int>(hn::Lanes(d));
  for (int at = 0; at < kChunk; at += width) {
    const LocatedPack<Tr, T> l = locate_pack<Tr>(x, near, at, frame);
    // The lane's row of volume.rows: its corner's parity and its cell.
    const V cell = A::index(l.cell);
    using I = hn::TFromD<decltype(di)>;
    const V parity = hn::And(hn::ConvertTo(di, l.corner[0].v), hn::Set(di, I{1}));
    const V row = hn::Add(cell, hn::IfThenElseZero(hn::Eq(parity, hn::Set(di, I{1})),
                                                   hn::Set(di, I{Tr::kCellCount})));
    const V field = hn::Add(hn::ShiftLeft<2>(row), row);  // row * kLinearFields
    static_assert(kLinearFields == 5, "field = 4 row + row");
    const auto read = [&](int f) HWY_ATTR {
      return hn::GatherIndex(di, volume.rows, hn::Add(field, hn::Set(di, static_cast<I>(f))));
    };
    // corner . stride: exact in T's integer lanes for float (the caller keeps every index in
    // int32), in double arithmetic (exact below 2^53) for double.
    V base;
    if constexpr (sizeof(T) == 4) {
      base = hn::Zero(di);
      for (int i = 0; i < n; ++i)
        base = hn::Add(base, hn::Mul(hn::ConvertTo(di, l.corner[i].v),
                                     hn::Set(di, static_cast<std::int32_t>(volume.stride[i]))));
    } else {
      auto sum = hn::Zero(d);
      for (int i = 0; i < n; ++i)
        sum = hn::Add(sum, hn::Mul(l.corner[i].v, hn::Set(d, static_cast<T>(volume.stride[i]))));
      base = hn::ConvertTo(di, sum);
    }
    const V first = hn::Add(base, read(0));
    const V axis[3] = {read(1), read(2), read(3)};
    const V flip = read(4);
    P value(0.0);
    P derivatives[kDerivatives + 1];
    for (P& e : derivatives) e = P(0.0);
    if constexpr (sizeof...(O) == 1) {
      evaluate_orbit<Tr, Order, 0>(volume, l, l.ok, first, axis, flip, value, derivatives);
    } else {
      const P orbit(hn::GatherIndex(d, kLocateTables<Tr, T>.orbit, cell));
      (
          [&]() HWY_ATTR {
            const auto lanes = hn::And(l.ok, hn::Eq(orbit.v, hn::Set(d, static_cast<T>(O))));
            if (!hn::AllFalse(d, lanes))
              evaluate_orbit<Tr, Order, O>(volume, l, lanes, first, axis, flip, value, derivatives);
          }(),
          ...);
    }
    hn::StoreU(value.v, d, out + at);
    for (int j = 0; j < kDerivatives; ++j)
      hn::StoreU(derivatives[j].v, d, out + (j + 1) * kRow + at);
    hn::StoreU(l.cell.v, d, out + kChunkCellRow * kRow + at);
    hn::StoreU(hn::IfThenElseZero(l.ok, hn::Set(d, T(1))), d, out + kChunkOkRow * kRow + at);
  }
}

template <class Tr, class T>
void chunk_for(int order, const double* points, const Frame& frame, const LinearVolume<T>& volume,
               T* out) {
  constexpr auto orbits = std::make_integer_sequence<int, StencilSteps<Tr>::kOrbits>{};
  if (order == support::kValue)
    return evaluate_lanes<Tr, support::kValue>(points, frame, volume, out, orbits);
  if (order == support::kGradient)
    return evaluate_lanes<Tr, support::kGradient>(points, frame, volume, out, orbits);
  evaluate_lanes<Tr, support::kHessian>(points, frame, volume, out, orbits);
}

// The kernels of Tr for this target, as the function pointers of simd::Kernels.
template <class Tr, class T>
void locate_for(const double* points, const Frame& frame, T* out) {
  locate_lanes<Tr>(points, frame, out);
}
template <class Tr, class T>
void orbit_for(int orbit, int order, const T* v, const T* x, T* out, int lanes) {
  if (order == support::kValue) return run<Tr, support::kValue>(orbit, v, x, out, lanes);
  if (order == support::kGradient) return run<Tr, support::kGradient>(orbit, v, x, out, lanes);
  run<Tr, support::kHessian>(orbit, v, x, out, lanes);
}
template <class Tr>
Kernels kernels_for() {
  constexpr bool kChunks = kStencilSteps<Tr>.consistent;
  return {&locate_for<Tr, float>,
          &locate_for<Tr, double>,
          &orbit_for<Tr, float>,
          &orbit_for<Tr, double>,
          kChunks ? &chunk_for<Tr, float> : nullptr,
          kChunks ? &chunk_for<Tr, double> : nullptr};
}

}  // namespace boxgen::runtime::simd::HWY_NAMESPACE
HWY_AFTER_NAMESPACE();

#endif  // BOXGEN_RUNTIME_SIMD_KERNELS_INL_H_
