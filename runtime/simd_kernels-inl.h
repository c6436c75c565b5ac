// The SIMD kernels of the runtime's batch path for one emitted evaluator (its Traits Tr):
// locate_lanes (support::locate for kChunk points at once) and run (the orbit polynomial, one
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
#include <type_traits>

#include "runtime/simd_batch.h"
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

// World to lattice coordinates in double, as BccVolume::to_lattice, rounded to T as the scalar
// path rounds them; x[i * kRow + lane] and near[lane] (1 or 0). Lanes that are not near get
// x = 0, so that nothing below converts a huge or non-finite number to an integer.
template <class T>
HWY_ATTR void lattice_lanes(int n, const double* world, const Frame& frame, T* x, T* near) {
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
    auto ok = hn::Eq(hn::Zero(dd), hn::Zero(dd));
    for (int i = 0; i < n; ++i) {
      lattice[i] =
          hn::Div(hn::Sub(hn::LoadU(dd, world + i * kRow + at), hn::Set(dd, frame.origin[i])),
                  hn::Set(dd, frame.h[i]));
      ok = hn::And(ok, hn::And(hn::Gt(lattice[i], hn::Set(dd, frame.lower)),
                               hn::Lt(lattice[i], hn::Set(dd, frame.upper[i]))));
    }
    for (int i = 0; i < n; ++i)
      hn::StoreU(to_t(hn::IfThenElseZero(ok, lattice[i])), dt, x + i * kRow + at);
    hn::StoreU(to_t(hn::IfThenElseZero(ok, hn::Set(dd, 1.0))), dt, near + at);
  }
}

// support::locate() for kChunk points at once, with the same operations in the same order (so the
// same cells and the same reference coordinates, bit for bit), and the stencil box check of the
// runtime. Integers are carried as T (exact: the caller keeps |x| below 2^23).
template <class Tr, class T>
[[gnu::flatten]] HWY_ATTR void locate_lanes(const double* world, const Frame& frame, T* out) {
  constexpr int n = Tr::kDimension;
  static_assert(Tr::kScale == 1, "the registry's filters are not scaled pairs");
  static constexpr LocateTables<Tr, T> kTables = locate_tables<Tr, T>();
  const hn::ScalableTag<T> d;
  const hn::RebindToSigned<decltype(d)> di;
  using V = hn::Vec<decltype(d)>;
  alignas(64) T x[n * kRow];
  alignas(64) T near[kChunk];
  lattice_lanes(n, world, frame, x, near);
  const int width = static_cast<int>(hn::Lanes(d));
  for (int at = 0; at < kChunk; at += width) {
    V xs[n], r[n], corner[n], rep[n];
    for (int i = 0; i < n; ++i) {
      xs[i] = hn::LoadU(d, x + i * kRow + at);
      const V u = hn::Add(xs[i], hn::Set(d, static_cast<T>(Tr::kCentre[i])));
      corner[i] = hn::Floor(u);
      r[i] = hn::Sub(u, corner[i]);
      rep[i] = corner[i];
    }
    // The coset representative of the corner (Hermite reduction) names its cube.
    for (int j = 0; j < n; ++j) {
      const V q = Tr::kHermite[j][j] == 1
                      ? rep[j]
                      : hn::Floor(hn::Div(rep[j], hn::Set(d, static_cast<T>(Tr::kHermite[j][j]))));
      for (int i = j; i < n; ++i)
        rep[i] = hn::Sub(rep[i], hn::Mul(q, hn::Set(d, static_cast<T>(Tr::kHermite[j][i]))));
    }
    V cube = hn::Zero(d);
    for (int i = n - 1; i >= 0; --i)
      cube = hn::Add(hn::Mul(cube, hn::Set(d, static_cast<T>(Tr::kHermite[i][i]))), rep[i]);
    // The combined knot-plane key: per normal, how many of its levels r lies at or above.
    V key = hn::Zero(d);
    for (int k = 0; k < Tr::kNormalCount; ++k) {
      V dot = hn::Zero(d);
      for (int i = 0; i < n; ++i)
        dot = hn::Add(dot, hn::Mul(hn::Set(d, static_cast<T>(Tr::kNormals[k][i])), r[i]));
      for (int m = 1; m < Tr::kNormalWidth[k]; ++m)
        key = hn::Add(
            key, hn::IfThenElseZero(hn::Ge(dot, hn::Set(d, static_cast<T>(Tr::kNormalMin[k] + m))),
                                    hn::Set(d, static_cast<T>(Tr::kNormalStride[k]))));
    }
    const V entry = hn::Add(hn::Mul(cube, hn::Set(d, static_cast<T>(Tr::kLookupSize))), key);
    const V cell = hn::GatherIndex(d, kTables.lookup, hn::ConvertTo(di, entry));
    // No cell (rounding put r on a knot plane): the caller takes the scalar path, so any valid
    // index serves for the gathers below.
    const auto index = hn::ConvertTo(di, hn::Max(cell, hn::Zero(d)));
    V ok = hn::IfThenElseZero(
        hn::And(hn::Ge(cell, hn::Zero(d)), hn::Gt(hn::LoadU(d, near + at), hn::Zero(d))),
        hn::Set(d, T(1)));
    for (int i = 0; i < n; ++i) {
      const V lo = hn::Add(corner[i], hn::Set(d, static_cast<T>(Tr::kStencilReachLo[i])));
      const V hi = hn::Add(corner[i], hn::Set(d, static_cast<T>(Tr::kStencilReachHi[i])));
      ok = hn::IfThenElseZero(
          hn::And(hn::Ge(lo, hn::Zero(d)), hn::Le(hi, hn::Set(d, static_cast<T>(frame.limit[i])))),
          ok);
    }
    hn::StoreU(cell, d, out + n * kRow + at);
    hn::StoreU(ok, d, out + (2 * n + 2) * kRow + at);
    hn::StoreU(hn::GatherIndex(d, kTables.orbit, index), d, out + (2 * n + 1) * kRow + at);
    for (int i = 0; i < n; ++i) {
      hn::StoreU(corner[i], d, out + i * kRow + at);
      // x_ref_i = sign_i (x_p - (corner_p - rep_p)) + a_i, p = perm_i.
      const V p = hn::GatherIndex(d, kTables.perm[i], index);
      V xp = xs[n - 1], shift = hn::Sub(corner[n - 1], rep[n - 1]);
      for (int q = n - 2; q >= 0; --q) {
        const auto is_q = hn::Eq(p, hn::Set(d, static_cast<T>(q)));
        xp = hn::IfThenElse(is_q, xs[q], xp);
        shift = hn::IfThenElse(is_q, hn::Sub(corner[q], rep[q]), shift);
      }
      const V ref = hn::Add(hn::Mul(hn::GatherIndex(d, kTables.sign[i], index), hn::Sub(xp, shift)),
                            hn::GatherIndex(d, kTables.a[i], index));
      hn::StoreU(ref, d, out + (n + 1 + i) * kRow + at);
    }
  }
}

// The kernels of Tr for this target, as the function pointers of simd::Kernels.
template <class Tr, class T>
void locate_for(const double* world, const Frame& frame, T* out) {
  locate_lanes<Tr>(world, frame, out);
}
template <class Tr, class T>
void orbit_for(int orbit, int order, const T* v, const T* x, T* out, int lanes) {
  if (order == support::kValue) return run<Tr, support::kValue>(orbit, v, x, out, lanes);
  if (order == support::kGradient) return run<Tr, support::kGradient>(orbit, v, x, out, lanes);
  run<Tr, support::kHessian>(orbit, v, x, out, lanes);
}
template <class Tr>
Kernels kernels_for() {
  return {&locate_for<Tr, float>, &locate_for<Tr, double>, &orbit_for<Tr, float>,
          &orbit_for<Tr, double>};
}

}  // namespace boxgen::runtime::simd::HWY_NAMESPACE
HWY_AFTER_NAMESPACE();

#endif  // BOXGEN_RUNTIME_SIMD_KERNELS_INL_H_
