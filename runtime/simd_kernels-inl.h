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
#include <cstring>
#include <string_view>
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

// The stage profile of docs/performance.md: compiled with -DBOXGEN_PROFILE_STAGES, the stages of
// evaluate_lanes (lattice_lanes, locate_pack, lane_stencil, gather_orbit, orbit_polynomial) stay
// out of line, so that callgrind counts each apart. Only for that measurement (it is slower).
#ifndef BOXGEN_STAGE
#ifdef BOXGEN_PROFILE_STAGES
#define BOXGEN_STAGE [[gnu::noinline, gnu::flatten]]
#else
#define BOXGEN_STAGE
#endif
#endif

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

// Integers held exactly in T (|v| < 2^51 in double) to the signed integers of T's width and back.
// In double by the bits of v + 1.5 * 2^52, two instructions: AVX2 has no conversion between double
// and int64, which Highway emulates in about twenty. In float by the vector unit's own.
inline constexpr double kExactIntegerBias = 6755399441055744.0;  // 1.5 * 2^52
template <class D>
HWY_ATTR hn::Vec<hn::RebindToSigned<D>> to_index(D d, hn::Vec<D> v) {
  const hn::RebindToSigned<D> di;
  if constexpr (sizeof(hn::TFromD<D>) == 4) {
    return hn::ConvertTo(di, v);
  } else {
    const auto bias = hn::Set(d, kExactIntegerBias);
    return hn::Sub(hn::BitCast(di, hn::Add(v, bias)), hn::BitCast(di, bias));
  }
}
template <class D>
HWY_ATTR hn::Vec<D> from_index(D d, hn::Vec<hn::RebindToSigned<D>> i) {
  if constexpr (sizeof(hn::TFromD<D>) == 4) {
    return hn::ConvertTo(d, i);
  } else {
    const auto bias = hn::Set(d, kExactIntegerBias);
    const hn::RebindToSigned<D> di;
    return hn::Sub(hn::BitCast(d, hn::Add(i, hn::BitCast(di, bias))), bias);
  }
}

// v >> bits for v >= 0, shifting in zeros (AVX2 has no arithmetic shift of int64).
template <class V>
HWY_ATTR V shift_right_zeros(V v, int bits) {
  const hn::DFromV<V> di;
  const hn::RebindToUnsigned<decltype(di)> du;
  return hn::BitCast(di, hn::ShiftRightSame(hn::BitCast(du, v), bits));
}

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

// The tables locate() reads per lane, so that a gather fetches them: the cell of (cube, knot
// key), as numbers of type T (small integers: exact), and per cell its orbit and its map onto the
// orbit's reference region x_ref_i = sign_i x_perm_i + ... + a_i, packed into one integer of
// GatherIndex<T> (kMapBits per axis: perm, sign > 0, a + kMapBias), so that one gather fetches
// a lane's whole map; bit kFirstParityBit holds the parity of the cell's first stencil offset
// along x (evaluate_lanes: whether the first sample changes the corner's coset).
inline constexpr int kMapBits = 10, kMapBias = 64, kFirstParityBit = 30;

// Not constexpr: reaching it while the tables are built at compile time stops the build.
void map_beyond_packed_range();

template <class Tr, class T>
struct LocateTables {
  T lookup[Tr::kCubeCount * Tr::kLookupSize];
  T orbit[Tr::kCellCount];
  GatherIndex<T> map[Tr::kCellCount];
};

template <class Tr, class T>
constexpr LocateTables<Tr, T> locate_tables() {
  static_assert(Tr::kDimension * kMapBits <= kFirstParityBit, "three axes");
  LocateTables<Tr, T> t{};
  for (int c = 0; c < Tr::kCubeCount; ++c)
    for (int k = 0; k < Tr::kLookupSize; ++k)
      t.lookup[c * Tr::kLookupSize + k] = static_cast<T>(Tr::kLookup[c][k]);
  for (int c = 0; c < Tr::kCellCount; ++c) {
    const auto& cell = Tr::kCells[c];
    t.orbit[c] = static_cast<T>(cell.orbit);
    GatherIndex<T> word = (Tr::kOffsets[c][0][0] & 1) << kFirstParityBit;
    for (int i = 0; i < Tr::kDimension; ++i) {
      // a translation within the reference cube: |a| is 0 or 1 for every filter (kScale 1)
      if (cell.a[i] < -kMapBias || cell.a[i] >= kMapBias) map_beyond_packed_range();
      const int field = cell.perm[i] | (cell.sign[i] > 0 ? 4 : 0) | ((cell.a[i] + kMapBias) << 3);
      word |= static_cast<GatherIndex<T>>(field) << (kMapBits * i);
    }
    t.map[c] = word;
  }
  return t;
}

template <class Tr, class T>
inline constexpr LocateTables<Tr, T> kLocateTables = locate_tables<Tr, T>();

// The packed map of each lane's cell (LocateTables::map), axis i's field of it, and the parts of
// that field.
template <class Tr, class T, class V>
HWY_ATTR V map_word(V cell) {
  return hn::GatherIndex(hn::DFromV<V>(), kLocateTables<Tr, T>.map, cell);
}
template <class V>
HWY_ATTR V map_field(V word, int i) {
  const hn::DFromV<V> di;
  return hn::And(shift_right_zeros(word, kMapBits * i),
                 hn::Set(di, static_cast<hn::TFromD<decltype(di)>>((1 << kMapBits) - 1)));
}
template <class V>
HWY_ATTR V field_perm(V field) {
  return hn::And(field, hn::Set(hn::DFromV<V>(), 3));
}
template <class V>
HWY_ATTR auto field_positive(V field) {
  const hn::DFromV<V> di;
  return hn::Ne(hn::And(field, hn::Set(di, 4)), hn::Zero(di));
}

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
  // b is a constant of the tables (a Hermite diagonal): for a power of two, a / b is a * (1 / b)
  // exactly, and the multiplication keeps the divider, the slowest vector unit, free.
  HWY_ATTR static Whole floor_div(Whole a, std::int64_t b) {
    if (b == 1) return a;
    if ((b & (b - 1)) == 0)
      return Whole(
          hn::Floor(hn::Mul(a.v, hn::Set(D(), static_cast<T>(1.0 / static_cast<double>(b))))));
    return Whole(hn::Floor(hn::Div(a.v, hn::Set(D(), static_cast<T>(b)))));
  }
  HWY_ATTR static Whole at_least(Real s, T c) {
    return Whole(hn::IfThenElseZero(hn::Ge(s.v, hn::Set(D(), c)), hn::Set(D(), T(1))));
  }
  // Any valid index for the lanes without a cell: their gathers are not used.
  HWY_ATTR static auto index(Whole cell) { return to_index(D(), hn::Max(cell.v, hn::Zero(D()))); }
  template <class Tr>
  HWY_ATTR static Whole cell_of(Whole cube, Whole key, const Real* /*r*/) {
    const Whole entry = cube * constant(Tr::kLookupSize) + key;
    return Whole(hn::GatherIndex(D(), kLocateTables<Tr, T>.lookup, to_index(D(), entry.v)));
  }
  // One gather of the packed map per lane for all axes (the compiler does not merge repeated
  // gathers of one table).
  template <class Tr>
  HWY_ATTR static void cell_maps(Whole cell, support::CellMap<Whole, Real>* g) {
    const D d;
    const hn::RebindToSigned<D> di;
    const auto word = map_word<Tr, T>(index(cell));
    for (int i = 0; i < Tr::kDimension; ++i) {
      const auto field = map_field(word, i);
      const auto a = hn::Sub(shift_right_zeros(field, 3), hn::Set(di, kMapBias));
      g[i] = {Whole(from_index(d, field_perm(field))),
              Real(hn::IfThenElse(hn::RebindMask(d, field_positive(field)), hn::Set(d, T(1)),
                                  hn::Set(d, T(-1)))),
              Real(from_index(d, a))};
    }
  }
  template <int N>
  HWY_ATTR static Pack<T> pick(Whole p, const Pack<T>* xs) {
    hn::Vec<D> r = xs[N - 1].v;
    for (int q = N - 2; q >= 0; --q)
      r = hn::IfThenElse(hn::Eq(p.v, hn::Set(D(), static_cast<T>(q))), xs[q].v, r);
    return Pack<T>(r);
  }
};

// Whether 1 / h is exact and h and 1 / h are normal: h = +-2^k, |k| < 1022 (its mantissa bits
// zero, its exponent field away from both ends).
inline bool exact_inverse(double h) {
  std::uint64_t bits = 0;
  std::memcpy(&bits, &h, sizeof bits);
  const std::uint64_t exponent = (bits >> 52) & 0x7FF;
  return (bits & ((std::uint64_t{1} << 52) - 1)) == 0 && exponent > 1 && exponent < 2045;
}

// World to lattice coordinates in double, as LatticeVolume::to_lattice, rounded to T as the scalar
// path rounds them; x[i * kRow + lane] and near[lane] (1 or 0). points[3 * lane + i]: the chunk's
// world coordinates, point after point. Lanes that are not near get x = 0, so that nothing below
// converts a huge or non-finite number to an integer. Where every spacing h is a power of two,
// the division by h is a multiplication by 1 / h: the same bits, without the vector divisions
// (the slowest operation here).
template <class T>
BOXGEN_STAGE HWY_ATTR void lattice_lanes(const double* points, const Frame& frame, T* x, T* near) {
  const hn::ScalableTag<double> dd;
  using V = hn::Vec<decltype(dd)>;
  const hn::Rebind<T, decltype(dd)> dt;
  const auto to_t = [&](V v) HWY_ATTR {
    if constexpr (std::is_same_v<T, double>) {
      static_cast<void>(dt);
      return v;
    } else {
      return hn::DemoteTo(dt, v);
    }
  };
  // The frame as vectors, once: the stores to x do not make the compiler read it again.
  const bool exact =
      exact_inverse(frame.h[0]) && exact_inverse(frame.h[1]) && exact_inverse(frame.h[2]);
  V origin[3], scale[3], upper[3];
  for (int i = 0; i < 3; ++i) {
    origin[i] = hn::Set(dd, frame.origin[i]);
    scale[i] = hn::Set(dd, exact ? 1.0 / frame.h[i] : frame.h[i]);
    upper[i] = hn::Set(dd, frame.upper[i]);
  }
  const V lower = hn::Set(dd, frame.lower);
  const int width = static_cast<int>(hn::Lanes(dd));
  const auto convert = [&](auto multiply) HWY_ATTR {
    for (int at = 0; at < kChunk; at += width) {
      V lattice[3];
      hn::LoadInterleaved3(dd, points + std::ptrdiff_t{3} * at, lattice[0], lattice[1], lattice[2]);
      auto ok = hn::Eq(hn::Zero(dd), hn::Zero(dd));
      for (int i = 0; i < 3; ++i) {
        const V shifted = hn::Sub(lattice[i], origin[i]);
        if constexpr (decltype(multiply)::value)
          lattice[i] = hn::Mul(shifted, scale[i]);
        else
          lattice[i] = hn::Div(shifted, scale[i]);
        ok = hn::And(ok, hn::And(hn::Gt(lattice[i], lower), hn::Lt(lattice[i], upper[i])));
      }
      for (int i = 0; i < 3; ++i)
        hn::StoreU(to_t(hn::IfThenElseZero(ok, lattice[i])), dt, x + i * kRow + at);
      hn::StoreU(to_t(hn::IfThenElseZero(ok, hn::Set(dd, 1.0))), dt, near + at);
    }
  };
  if (exact)
    convert(std::true_type{});
  else
    convert(std::false_type{});
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
BOXGEN_STAGE HWY_ATTR LocatedPack<Tr, T> locate_pack(const T* x, const T* near, int at,
                                                     const Frame& frame) {
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

// Where each lane's stencil lies in a linear volume: its first sample's index, the index changes
// of a unit step along each reference axis (sign_i stride[perm_i], from the cell's map), and of a
// step that changes the coset; and the lane's cell, as an index.
template <class V>
struct LaneStencil {
  V first, axis[3], flip, cell;
};

template <class Tr, class T>
BOXGEN_STAGE HWY_ATTR auto lane_stencil(const LocatedPack<Tr, T>& l,
                                        const LinearVolume<T>& volume) {
  constexpr int n = Tr::kDimension;
  using A = PackArith<T>;
  const typename A::D d;
  const hn::RebindToSigned<decltype(d)> di;
  using V = hn::Vec<decltype(di)>;
  using I = hn::TFromD<decltype(di)>;
  LaneStencil<V> st;
  st.cell = A::index(l.cell);
  // The first sample: volume.rows by the corner's parity and the cell.
  const V one = hn::Set(di, I{1});
  const V parity = hn::And(to_index(d, l.corner[0].v), one);
  const V row =
      hn::Add(st.cell, hn::IfThenElseZero(hn::Eq(parity, one), hn::Set(di, I{Tr::kCellCount})));
  // corner . stride: exact in T's integer lanes for float (the caller keeps every index in
  // int32), in double arithmetic (exact below 2^53) for double.
  V base;
  if constexpr (sizeof(T) == 4) {
    base = hn::Zero(di);
    for (int i = 0; i < n; ++i)
      base = hn::Add(
          base, hn::Mul(to_index(d, l.corner[i].v), hn::Set(di, static_cast<I>(volume.stride[i]))));
  } else {
    auto sum = hn::Zero(d);
    for (int i = 0; i < n; ++i)
      sum = hn::Add(sum, hn::Mul(l.corner[i].v, hn::Set(d, static_cast<T>(volume.stride[i]))));
    base = to_index(d, sum);
  }
  st.first = hn::Add(base, hn::GatherIndex(di, volume.rows, row));
  // The storage strides of the reference axes from the cell's map (one gather per lane, not one
  // per axis: fewer cycles on AVX-512, a few more instructions; docs/performance.md).
  const V word = map_word<Tr, T>(st.cell);
  for (int i = 0; i < n; ++i) {
    const V field = map_field(word, i);
    const V perm = field_perm(field);
    const V stride = hn::IfThenElse(
        hn::Eq(perm, hn::Zero(di)), hn::Set(di, static_cast<I>(volume.stride[0])),
        hn::IfThenElse(hn::Eq(perm, one), hn::Set(di, static_cast<I>(volume.stride[1])),
                       hn::Set(di, static_cast<I>(volume.stride[2]))));
    st.axis[i] = hn::IfThenElse(field_positive(field), stride, hn::Neg(stride));
  }
  // An odd step moves to the other coset: out of the odd one (+coset_shift: sample j sits at
  // j . stride - (j_x & 1) coset_shift) or into it (-coset_shift).
  const V first_odd = hn::Xor(parity, hn::And(shift_right_zeros(word, kFirstParityBit), one));
  const V shift = hn::Set(di, static_cast<I>(volume.coset_shift));
  st.flip = hn::IfThenElse(hn::Eq(first_odd, one), shift, hn::Neg(shift));
  return st;
}

// The orbit polynomial of orbit O on one point per lane (a function of its own only for the stage
// profile).
template <class Tr, int Order, int O, class T>
BOXGEN_STAGE HWY_ATTR Pack<T> orbit_polynomial(const Pack<T>* pv, const Pack<T>* ref, Pack<T>* pd) {
  return Tr::template orbit<Order>(O, pv, ref, pd);
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
BOXGEN_STAGE HWY_ATTR void gather_orbit(const T* samples, V first, const V* axis, V flip,
                                        Pack<T>* pv, std::integer_sequence<int, K...> /*samples*/) {
  const typename Pack<T>::D d;
  ((pv[K] = Pack<T>(hn::GatherIndex(d, samples, sample_index<Tr, O, K>(first, axis, flip)))), ...);
}

#if HWY_TARGET != HWY_SCALAR  // one lane has nothing to transpose
// Vector m of a run's load (load_runs): the loads of all lanes one after the other, L samples
// each from samples + base[lane], cut into vectors of d (m counts vectors).
template <int L, class D, class T, class I>
HWY_ATTR hn::Vec<D> run_vector(D d, const T* samples, const I* base, std::ptrdiff_t m) {
  constexpr int kLanes = static_cast<int>(hn::MaxLanes(d));
  if constexpr (kLanes <= L) {
    constexpr int kParts = L / kLanes;
    return hn::LoadU(d, samples + base[m / kParts] + (m % kParts) * kLanes);
  } else {
    const hn::Half<D> dh;
    constexpr int kHalf = kLanes / 2 / L;  // loads per half
    return hn::Combine(d, run_vector<L>(dh, samples, base + (2 * m + 1) * kHalf, 0),
                       run_vector<L>(dh, samples, base + 2 * m * kHalf, 0));
  }
}

// Splits the N vectors v (a sequence of values, vector after vector) by the value's position mod
// N: out[c] holds the values at positions c, c + N, c + 2 N, ... in order.
template <int N, class D>
HWY_ATTR void deinterleave(D d, const hn::Vec<D>* v, hn::Vec<D>* out) {
  if constexpr (N == 1) {
    out[0] = v[0];
  } else {
    hn::Vec<D> even[N / 2], odd[N / 2], split[2][N / 2];
    for (std::ptrdiff_t q = 0; q < N / 2; ++q) {
      even[q] = hn::ConcatEven(d, v[2 * q + 1], v[2 * q]);
      odd[q] = hn::ConcatOdd(d, v[2 * q + 1], v[2 * q]);
    }
    deinterleave<N / 2>(d, even, split[0]);
    deinterleave<N / 2>(d, odd, split[1]);
    for (std::ptrdiff_t c = 0; c < N / 2; ++c) {
      out[2 * c] = split[0][c];
      out[2 * c + 1] = split[1][c];
    }
  }
}

// The stencil of orbit O loaded by runs (StencilSteps::run_axis): each lane loads the kRun
// samples of a run with one load of L = kRun u consecutive samples (u = run_step; storage axis 0
// has stride 1), and the loads are transposed into one vector per sample (what the unneeded
// positions would give is never computed). A lane whose cell reverses the run's axis finds the
// run's samples in the reverse order. The caller makes sure that no load reaches beyond the
// volume's samples (with u = 2 a load takes one sample after its run).
template <class Tr, int O, class T, class V, int... G>
BOXGEN_STAGE HWY_ATTR void load_runs(const T* samples, V first, const V* axis, V flip, Pack<T>* pv,
                                     std::integer_sequence<int, G...> /*runs*/) {
  constexpr auto& steps = kStencilSteps<Tr>;
  constexpr int kRun = StencilSteps<Tr>::kRun, r = steps.run_axis[O], u = steps.run_step[O];
  constexpr int L = kRun * u;
  const typename Pack<T>::D d;
  const hn::DFromV<V> di;
  using I = hn::TFromD<decltype(di)>;
  const auto reversed = hn::Lt(axis[r], hn::Zero(di));
  // A reversed run starts (kRun - 1) u samples below its first sample.
  constexpr int kBack = -(kRun - 1) * u;
  const V back = hn::IfThenElseZero(reversed, hn::Set(di, static_cast<I>(kBack)));
  alignas(64) I base[sizeof...(G)][hn::MaxLanes(di)];
  ((hn::Store(hn::Add(sample_index<Tr, O, kRun * G>(first, axis, flip), back), di, base[G])), ...);
  const auto flipped = hn::RebindMask(d, reversed);
  (
      [&]() HWY_ATTR {
        hn::Vec<decltype(d)> v[L], at[L];
        for (int m = 0; m < L; ++m) v[m] = run_vector<L>(d, samples, base[G], m);
        deinterleave<L>(d, v, at);
        for (int j = 0; j < kRun; ++j)
          pv[kRun * G + j] = Pack<T>(hn::IfThenElse(flipped, at[(kRun - 1 - j) * u], at[j * u]));
      }(),
      ...);
}

// Whether the stencils of the lanes of `lanes` may be loaded by runs: a volume whose storage axis
// 0 has stride 1, and (where a load takes a sample after its run) no lane whose stencil box holds
// the volume's last sample, the lattice point at the limit of every axis (then the extra sample
// would lie beyond it). Else the caller gathers.
template <class Tr, int O, class T, class M>
HWY_ATTR bool runs_fit(const LinearVolume<T>& volume, const LocatedPack<Tr, T>& l, M lanes,
                       const Frame& frame) {
  constexpr auto& steps = kStencilSteps<Tr>;
  const typename Pack<T>::D d;
  if (volume.stride[0] != 1 || hn::AllFalse(d, lanes)) return false;
  if constexpr (steps.run_step[O] == 1) return true;
  auto at_end = lanes;
  for (int i = 0; i < Tr::kDimension; ++i)
    at_end = hn::And(
        at_end,
        hn::Ge(l.corner[i].v, hn::Set(d, static_cast<T>(frame.limit[i] - Tr::kStencilReachHi[i]))));
  return hn::AllFalse(d, at_end);
}
#endif

// evaluate_chunk (simd_batch.h) for one orbit O: the lanes of `lanes` (the others gather sample 0
// and their results are not used) take the orbit's polynomial.
template <class Tr, int Order, int O, class T, class V, class M>
HWY_ATTR void evaluate_orbit(const LinearVolume<T>& volume, const Frame& frame,
                             const LocatedPack<Tr, T>& l, M lanes, const LaneStencil<V>& st,
                             Pack<T>& value, Pack<T>* derivatives) {
  constexpr int n = Tr::kDimension;
  constexpr int kDerivatives =
      Order == support::kValue ? 0
                               : (Order == support::kGradient ? n : n + support::hessian_size(n));
  constexpr int size = Tr::kOrbitStencilSize[O];
  const hn::DFromV<V> di;
  const auto m = hn::RebindMask(di, lanes);
  V axis_in[n];
  for (int i = 0; i < n; ++i) axis_in[i] = hn::IfThenElseZero(m, st.axis[i]);
  static_cast<void>(frame);  // used where the orbit has runs
  Pack<T> pv[Tr::kStencilSize];
  const V first = hn::IfThenElseZero(m, st.first), flip = hn::IfThenElseZero(m, st.flip);
  bool loaded = false;
#if HWY_TARGET != HWY_SCALAR
  // In double, runs whose loads also carry unused samples (run_step 2) were slower than the
  // gathers on a cache-resident volume (docs/performance.md), so they gather.
  constexpr int u = kStencilSteps<Tr>.run_step[O];
  if constexpr (kStencilSteps<Tr>.run_axis[O] >= 0 && (sizeof(T) == 4 || u == 1)) {
    if (runs_fit<Tr, O>(volume, l, lanes, frame)) {
      load_runs<Tr, O>(volume.samples, first, axis_in, flip, pv,
                       std::make_integer_sequence<int, size / StencilSteps<Tr>::kRun>{});
      loaded = true;
    }
  }
#endif
  if (!loaded)
    gather_orbit<Tr, O>(volume.samples, first, axis_in, flip, pv,
                        std::make_integer_sequence<int, size>{});
  for (int k = size; k < Tr::kStencilSize; ++k) pv[k] = Pack<T>(0.0);
  Pack<T>
      pd[kDerivatives + 1];  // the orbit function fills d[0, kDerivatives); zeroed for the compiler
  for (Pack<T>& e : pd) e = Pack<T>(0.0);
  const Pack<T> v = orbit_polynomial<Tr, Order, O>(pv, l.ref, pd);
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
  constexpr int kDerivatives =
      Order == support::kValue ? 0
                               : (Order == support::kGradient ? n : n + support::hessian_size(n));
  using P = Pack<T>;
  const typename P::D d;
  const hn::RebindToSigned<decltype(d)> di;
  using V = hn::Vec<decltype(di)>;
  alignas(64) T x[n * kRow];
  alignas(64) T near[kChunk];
  lattice_lanes(points, frame, x, near);
  const int width = static_cast<int>(hn::Lanes(d));
  for (int at = 0; at < kChunk; at += width) {
    const LocatedPack<Tr, T> l = locate_pack<Tr>(x, near, at, frame);
    const LaneStencil<V> st = lane_stencil<Tr>(l, volume);
    P value(0.0);
    P derivatives[kDerivatives + 1];
    for (P& e : derivatives) e = P(0.0);
    if constexpr (sizeof...(O) == 1) {
      evaluate_orbit<Tr, Order, 0>(volume, frame, l, l.ok, st, value, derivatives);
    } else {
      const P orbit(hn::GatherIndex(d, kLocateTables<Tr, T>.orbit, st.cell));
      (
          [&]() HWY_ATTR {
            const auto lanes = hn::And(l.ok, hn::Eq(orbit.v, hn::Set(d, static_cast<T>(O))));
            if (!hn::AllFalse(d, lanes))
              evaluate_orbit<Tr, Order, O>(volume, frame, l, lanes, st, value, derivatives);
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
// Whether the chunk kernels can ever serve Tr's volumes: they need consistent stencil steps and
// samples in one linear layout (runtime/stencils.h), which BCC's parity tables give and the
// general lattice tables give only on a lattice of period 1 (det G = 1). On FCC and every other
// lattice of period > 1 simd_block (the orbit kernels) serves every batch, so the chunk kernels
// are not instantiated there: they were the largest part of a compiled filter's compile.
template <class Tr>
constexpr bool chunks_can_serve() {
  if (!kStencilSteps<Tr>.consistent) return false;
  if (std::string_view(Tr::kLattice) == "bcc") return true;
  std::int64_t det = 1;
  for (int i = 0; i < Tr::kDimension; ++i) det *= Tr::kHermite[i][i];
  return det == 1;
}

// One precision's kernels of Tr into `k` (a compiled filter fills each in its own translation
// unit: loader/filter_loader.cpp); chunk kernels only where chunks_can_serve<Tr>().
template <class Tr, class T>
void set_kernels_for(Kernels& k) {
  constexpr bool kChunks = chunks_can_serve<Tr>();
  if constexpr (std::is_same_v<T, float>) {
    k.locate_float = &locate_for<Tr, float>;
    k.orbit_float = &orbit_for<Tr, float>;
    k.chunk_float = nullptr;
    if constexpr (kChunks) k.chunk_float = &chunk_for<Tr, float>;
  } else {
    k.locate_double = &locate_for<Tr, double>;
    k.orbit_double = &orbit_for<Tr, double>;
    k.chunk_double = nullptr;
    if constexpr (kChunks) k.chunk_double = &chunk_for<Tr, double>;
  }
}
template <class Tr>
Kernels kernels_for() {
  Kernels k{};
  set_kernels_for<Tr, float>(k);
  set_kernels_for<Tr, double>(k);
  return k;
}

}  // namespace boxgen::runtime::simd::HWY_NAMESPACE
HWY_AFTER_NAMESPACE();

#endif  // BOXGEN_RUNTIME_SIMD_KERNELS_INL_H_
