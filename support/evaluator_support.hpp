// The fixed glue of every emitted evaluator (README.md, `boxgen emit`): locating the cell of a
// point, mapping it onto its orbit's reference region, fetching the stencil and mapping the
// derivatives back. Hand-written and compiled like any other header (tests/emitted exercises it
// through every emitted filter); the generated headers carry only what varies: the tables and the
// polynomial code, collected in a traits type `Traits` that the functions below take.
//
// A Traits type provides (all static constexpr):
//   kDimension, kStencilSize, kNormalCount, kLookupSize, kCubeCount, kCellCount
//   kCentre[n]                          c: the uncentred frame is u = x + c
//   kHermite[n][n]                      lower-triangular Hermite basis of the lattice (columns)
//   kScale                              1, or k: cubes and keys are those of the frame (x + c) / k
//   kNormals[K+1][n], kNormalMin[K+1], kNormalWidth[K+1], kNormalStride[K+1]
//   kLookup[kCubeCount][kLookupSize]    cell for (cube, combined knot-plane key), -1 if none
//   kCells[kCellCount]                  Cell<n, K>: cube, orbit, keys, perm, sign, a
//   kOrbitStencilSize[orbits]
//   kOffsets[kCellCount][kStencilSize][n]  stencil point j minus the corner floor(x + c)
//   template <int Order, class T> static T orbit(int o, const T* v, const T* x, T* d)
//       the reference polynomial of orbit o at reference coordinates x from stencil values v;
//       Order >= 1 writes the gradient to d[0..n), Order >= 2 also the Hessian's upper triangle
//       (row by row: xx xy xz yy yz zz in 3-D) to d[n..).
#pragma once
#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <utility>

#include "support/cell_glue.h"
#include "support/integer_math.h"

namespace boxgen::generated::support {

// What an evaluation computes: the value, also the gradient, also the Hessian.
inline constexpr int kValue = 0, kGradient = 1, kHessian = 2;

// Entries of a symmetric n x n matrix's upper triangle, and the index of (i, j), i <= j, in it.
constexpr int hessian_size(int n) { return n * (n + 1) / 2; }
constexpr int hessian_index(int n, int i, int j) { return i * n - i * (i - 1) / 2 + (j - i); }

template <int N, int K>
struct Cell {
  std::int16_t cube;
  std::int16_t orbit;
  std::int8_t keys[K + 1];
  std::int8_t perm[N];  // x_ref = g (x - t) + a, (g x)_i = sign_i x_perm_i
  std::int8_t sign[N];
  std::int32_t a[N];
};

// A point located in its cell: the evaluator's decision, published so that a caller (the
// runtime) can check the stencil box floor(x + c) + reach and prepare its fetches without
// recomputing anything the evaluator does.
template <int N, class T>
struct Located {
  std::array<std::int64_t, N> corner;  // floor(x + c), the unit cube of the uncentred frame
  int cell;                            // index into Traits::kCells / kOffsets
  T x[N];                              // reference coordinates of the point
};

// floor(a / b): the one definition (support/integer_math.h); b is a compile-time constant after
// inlining, so no division is executed for the power-of-two diagonals of the usual lattices.
using ::boxgen::support::floor_div;

// Rounding put r on an empty key combination: the cell of this cube whose slabs r violates least
// (support/cell_glue.h, the one definition the CUDA headers share), out of line since it is rare.
template <class Tr, class T>
[[gnu::noinline]] int nearest_cell(int cube, const T* r) {
  return ::boxgen::support::nearest_cell(cube, r, Tr::kCells, Tr::kNormals);
}

// The arithmetic locate_in() is written in, so that one algorithm locates one point (ScalarArith,
// below) and a SIMD pack of points (runtime/simd_batch.cpp): Real holds coordinates (of Scalar,
// float or double), Whole the integers (corners, cube and cell indices). An Arith provides
//   Real floor(Real), Real real(Whole), Whole whole(Real) (of an integral Real),
//   Whole constant(int64), Real constant_real(Scalar), Whole floor_div(Whole, int64 constant),
//   Whole at_least(Real s, Scalar c): 1 where s >= c, else 0,
//   Whole cell_of<Tr>(Whole cube, Whole key, const Real* r): kLookup[cube][key] (the scalar
//     arithmetic settles an empty entry; a pack leaves -1 to its caller),
//   void cell_maps<Tr>(Whole cell, CellMap<Whole, Real>* g): g[i] = perm_i, sign_i and a_i of
//     the cell, every axis at once (a pack reads the cell's map once),
//   X pick<n>(Whole p, const X* xs): xs[p], for p in [0, n).
template <class Whole, class Real>
struct CellMap {
  Whole perm;
  Real sign, a;
};

// One point in T, its integers in int64.
template <class T>
struct ScalarArith {
  using Scalar = T;
  using Real = T;
  using Whole = std::int64_t;
  [[gnu::always_inline]] static Real floor(Real s) { return std::floor(s); }
  [[gnu::always_inline]] static Real real(Whole w) { return static_cast<T>(w); }
  [[gnu::always_inline]] static Whole whole(Real f) { return static_cast<Whole>(f); }
  [[gnu::always_inline]] static Whole constant(std::int64_t c) { return c; }
  [[gnu::always_inline]] static Real constant_real(T c) { return c; }
  [[gnu::always_inline]] static Whole floor_div(Whole a, std::int64_t b) {
    return ::boxgen::support::floor_div(a, b);
  }
  [[gnu::always_inline]] static Whole at_least(Real s, Scalar c) { return s >= c; }
  template <class Tr>
  [[gnu::always_inline]] static Whole cell_of(Whole cube, Whole key, const Real* r) {
    const int cell = Tr::kLookup[cube][key];
    return cell >= 0 ? cell : nearest_cell<Tr>(static_cast<int>(cube), r);
  }
  template <class Tr>
  [[gnu::always_inline]] static void cell_maps(Whole cell, CellMap<Whole, Real>* g) {
    const auto& c = Tr::kCells[cell];
    for (int i = 0; i < Tr::kDimension; ++i)
      g[i] = {c.perm[i], static_cast<T>(c.sign[i]), static_cast<T>(c.a[i])};
  }
  template <int N, class X>
  [[gnu::always_inline]] static X pick(Whole p, const X* xs) {
    return xs[p];
  }
};

// nu_K . r from component I on, added to `sum` (Started) or starting it: a zero component costs
// nothing and a unit one no multiplication. The value is the one the full sum 0 + nu_0 r_0 + ...
// gives (1 r = r, (-1) r = -r, s + 0 = s and 0 + s = s exactly, up to the sign of a zero, which
// no comparison sees), so the cells found do not change; a SIMD pack cannot drop them itself
// (0 r is not 0 for every float).
template <class Tr, class A, int K, int I, bool Started>
[[gnu::always_inline]] inline typename A::Real normal_dot(const typename A::Real* r,
                                                          typename A::Real sum) {
  if constexpr (I == Tr::kDimension) {
    return Started ? sum : A::constant_real(0);
  } else {
    constexpr int c = Tr::kNormals[K][I];
    if constexpr (c == 0) {
      return normal_dot<Tr, A, K, I + 1, Started>(r, sum);
    } else if constexpr (c == 1 || c == -1) {
      if constexpr (Started)
        return normal_dot<Tr, A, K, I + 1, true>(r, c == 1 ? sum + r[I] : sum - r[I]);
      else
        return normal_dot<Tr, A, K, I + 1, true>(r, c == 1 ? r[I] : -r[I]);
    } else {
      const typename A::Real term = A::constant_real(static_cast<typename A::Scalar>(c)) * r[I];
      return normal_dot<Tr, A, K, I + 1, true>(r, Started ? sum + term : term);
    }
  }
}

// floor(nu_K . r) - min_K times the key's stride, for r in [0,1)^n, by comparisons: K is a
// template argument so that the normal's components are constants and the zero ones vanish.
template <class Tr, class A, int K>
[[gnu::always_inline]] inline typename A::Whole knot_level(const typename A::Real* r) {
  const typename A::Real dot = normal_dot<Tr, A, K, 0, false>(r, A::constant_real(0));
  typename A::Whole levels = A::constant(0);
  for (int m = 1; m < Tr::kNormalWidth[K]; ++m)
    levels = levels + A::at_least(dot, static_cast<typename A::Scalar>(Tr::kNormalMin[K] + m));
  return levels * A::constant(Tr::kNormalStride[K]);
}

template <class Tr, class A, int... K>
[[gnu::always_inline]] inline typename A::Whole knot_key(const typename A::Real* r,
                                                         std::integer_sequence<int, K...>) {
  static_cast<void>(r);  // no knot planes besides the axes (M12, tricubic)
  return (A::constant(0) + ... + knot_level<Tr, A, K>(r));
}

// The cell of x (lattice coordinates) and its reference coordinates, in the arithmetic A: the one
// implementation of locating (docs/design.md §11). corner = floor(x + c), cell
// indexes Traits::kCells, xref = g (x - t) + a maps the point onto its orbit's reference region.
template <class Tr, class A>
[[gnu::always_inline]] inline void locate_in(const typename A::Real* x, typename A::Whole* corner,
                                             typename A::Whole& cell, typename A::Real* xref) {
  using Real = typename A::Real;
  using Whole = typename A::Whole;
  using Scalar = typename A::Scalar;
  constexpr int n = Tr::kDimension;
  // A scaled pair (kScale = k) locates in the reduced frame (x + c) / k: its cubes have side k.
  constexpr std::int64_t k = Tr::kScale;
  Real r[n];
  Whole rep[n];  // the cube's corner, then its coset representative, in that frame
  for (int i = 0; i < n; ++i) {
    const Real u = x[i] + A::constant_real(static_cast<Scalar>(Tr::kCentre[i]));
    Real s = u;
    if constexpr (k != 1) s = u / A::constant_real(static_cast<Scalar>(k));
    const Real f = A::floor(s);
    rep[i] = A::whole(f);
    corner[i] = k == 1 ? rep[i] : rep[i] * A::constant(k);
    r[i] = s - f;
  }
  // The coset representative of the corner (reduction by the Hermite basis) names its cube.
  for (int j = 0; j < n; ++j) {
    const Whole q = A::floor_div(rep[j], Tr::kHermite[j][j] / k);
    for (int i = j; i < n; ++i) rep[i] = rep[i] - q * A::constant(Tr::kHermite[j][i] / k);
  }
  Whole cube = A::constant(0);
  for (int i = n - 1; i >= 0; --i) cube = cube * A::constant(Tr::kHermite[i][i] / k) + rep[i];
  // The combined knot-plane key: per normal, how many of its levels r lies at or above.
  const Whole key = knot_key<Tr, A>(r, std::make_integer_sequence<int, Tr::kNormalCount>{});
  cell = A::template cell_of<Tr>(cube, key, r);
  // x_ref_i = sign_i (x_p - t_p) + a_i, p = perm_i, with the cell's translation t = corner - rep.
  // x_p - t_p for every p first, so that each axis picks once (the same values).
  Real shifted[n];
  for (int i = 0; i < n; ++i)
    shifted[i] = x[i] - A::real(corner[i] - (k == 1 ? rep[i] : rep[i] * A::constant(k)));
  CellMap<Whole, Real> g[n];
  A::template cell_maps<Tr>(cell, g);
  for (int i = 0; i < n; ++i)
    xref[i] = g[i].sign * A::template pick<n>(g[i].perm, shifted) + g[i].a;
}

template <class Tr, class T>
[[gnu::always_inline]] inline Located<Tr::kDimension, T> locate(
    const std::array<T, Tr::kDimension>& x) {
  Located<Tr::kDimension, T> out;
  std::int64_t cell = 0;
  locate_in<Tr, ScalarArith<T>>(x.data(), out.corner.data(), cell, out.x);
  out.cell = static_cast<int>(cell);
  return out;
}

// The derivatives of a cell's reference polynomial (ref[j * stride], j as in the orbit functions'
// d) in the lattice frame: x_ref_i = sign_i x_perm_i + const, so d/dx_perm_i = sign_i d/dx_ref_i.
// The stride lets a batch of points keep its derivatives lane by lane (runtime/simd_batch.h).
template <int Order, class Tr, class T>
void from_reference_frame(int cell_index, const T* ref, std::ptrdiff_t stride, T* d) {
  constexpr int n = Tr::kDimension;
  const auto& cell = Tr::kCells[cell_index];
  for (int i = 0; i < n; ++i) d[cell.perm[i]] = static_cast<T>(cell.sign[i]) * ref[i * stride];
  if constexpr (Order >= kHessian) {
    for (int i = 0; i < n; ++i)
      for (int j = i; j < n; ++j) {
        const int pi = cell.perm[i], pj = cell.perm[j];
        const int at_user = pi <= pj ? hessian_index(n, pi, pj) : hessian_index(n, pj, pi);
        d[n + at_user] = static_cast<T>(cell.sign[i] * cell.sign[j]) *
                         ref[(n + hessian_index(n, i, j)) * stride];
      }
  }
}

// The spline and, by Order, its derivatives (lattice frame, d as in the orbit functions) at a
// located point from its stencil values v (v[k] is the sample at corner + kOffsets[cell][k]).
template <int Order, class Tr, class T>
T evaluate_located(const Located<Tr::kDimension, T>& at, const T* v, T* d) {
  constexpr int n = Tr::kDimension;
  const auto& cell = Tr::kCells[at.cell];
  if constexpr (Order == kValue) {
    return Tr::template orbit<kValue>(cell.orbit, v, at.x, d);
  } else {
    T ref[n + hessian_size(n)] = {};  // every orbit function fills it; zeroed for the compiler
    const T value = Tr::template orbit<Order>(cell.orbit, v, at.x, ref);
    from_reference_frame<Order, Tr>(at.cell, ref, 1, d);
    return value;
  }
}

// The scalar entry point through a user's fetch(const std::array<int64_t, n>& j) -> sample.
template <class Tr, class T, class Fetch>
T evaluate(const std::array<T, Tr::kDimension>& x, Fetch&& fetch,
           std::array<T, Tr::kDimension>* gradient,
           std::array<T, hessian_size(Tr::kDimension)>* hessian) {
  constexpr int n = Tr::kDimension;
  const Located<n, T> at = locate<Tr>(x);
  T v[Tr::kStencilSize];
  const int size = Tr::kOrbitStencilSize[Tr::kCells[at.cell].orbit];
  for (int k = 0; k < size; ++k) {
    std::array<std::int64_t, n> j;
    for (int i = 0; i < n; ++i) j[i] = at.corner[i] + Tr::kOffsets[at.cell][k][i];
    v[k] = static_cast<T>(fetch(j));
  }
  T d[n + hessian_size(n)] = {};
  T value;
  if (hessian) {
    value = evaluate_located<kHessian, Tr>(at, v, d);
    for (int i = 0; i < hessian_size(n); ++i) (*hessian)[i] = d[n + i];
  } else if (gradient) {
    value = evaluate_located<kGradient, Tr>(at, v, d);
  } else {
    return evaluate_located<kValue, Tr>(at, v, d);
  }
  if (gradient)
    for (int i = 0; i < n; ++i) (*gradient)[i] = d[i];
  return value;
}

}  // namespace boxgen::generated::support
