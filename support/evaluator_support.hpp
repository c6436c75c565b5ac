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

// Rounding put r on an empty key combination (it lies on a knot plane): take the cell of this
// cube whose slabs it violates least. The spline is continuous there, so either side is right.
template <class Tr, class T>
[[gnu::noinline]] int nearest_cell(int cube, const T* r) {
  int best = -1;
  double best_violation = 0;
  for (int c = 0; c < Tr::kCellCount; ++c) {
    if (Tr::kCells[c].cube != cube) continue;
    double violation = 0;
    for (int k = 0; k < Tr::kNormalCount; ++k) {
      double s = 0;
      for (int i = 0; i < Tr::kDimension; ++i) s += Tr::kNormals[k][i] * static_cast<double>(r[i]);
      const double lo = Tr::kCells[c].keys[k];
      violation += std::fmax(0.0, lo - s) + std::fmax(0.0, s - (lo + 1));
    }
    if (best < 0 || violation < best_violation) {
      best = c;
      best_violation = violation;
    }
  }
  return best;
}

// floor(nu_K . r) - min_K for r in [0,1)^n by comparisons: the normal is a compile-time constant,
// so after inlining this is a few adds and compares, no floor and no branch.
template <class Tr, int K, class T>
[[gnu::always_inline]] inline int knot_key(const T* r) {
  T s = 0;
  for (int i = 0; i < Tr::kDimension; ++i) s += static_cast<T>(Tr::kNormals[K][i]) * r[i];
  int f = 0;
  for (int m = 1; m < Tr::kNormalWidth[K]; ++m) f += s >= static_cast<T>(Tr::kNormalMin[K] + m);
  return f * Tr::kNormalStride[K];
}

template <class Tr, class T, int... K>
[[gnu::always_inline]] inline int lookup_index(const T* r, std::integer_sequence<int, K...>) {
  static_cast<void>(r);  // no knot planes besides the axes (M12, tricubic)
  return (0 + ... + knot_key<Tr, K>(r));
}

// The cell of cube `cube` holding r in [0,1)^n: the combined knot-plane key, one table lookup.
template <class Tr, class T>
[[gnu::always_inline]] inline int cell_of(int cube, const T* r) {
  const int index = lookup_index<Tr>(r, std::make_integer_sequence<int, Tr::kNormalCount>{});
  const int cell = Tr::kLookup[cube][index];
  return cell >= 0 ? cell : nearest_cell<Tr>(cube, r);
}

template <class Tr, class T>
[[gnu::always_inline]] inline Located<Tr::kDimension, T> locate(
    const std::array<T, Tr::kDimension>& x) {
  constexpr int n = Tr::kDimension;
  Located<n, T> out;
  T r[n];
  // A scaled pair (kScale = k) locates in the reduced frame (x + c) / k: its cubes have side k.
  constexpr std::int64_t k = Tr::kScale;
  std::int64_t rep[n];  // the cube's corner, then its coset representative, in that frame
  for (int i = 0; i < n; ++i) {
    const T u = x[i] + static_cast<T>(Tr::kCentre[i]);
    const T s = k == 1 ? u : u / static_cast<T>(k);
    const T f = std::floor(s);
    rep[i] = static_cast<std::int64_t>(f);
    out.corner[i] = rep[i] * k;
    r[i] = s - f;
  }
  // The coset representative of the corner (reduction by the Hermite basis) names its cube.
  for (int j = 0; j < n; ++j) {
    const std::int64_t q = floor_div(rep[j], Tr::kHermite[j][j] / k);
    for (int i = j; i < n; ++i) rep[i] -= q * (Tr::kHermite[j][i] / k);
  }
  int cube = 0;
  for (int i = n - 1; i >= 0; --i)
    cube = cube * static_cast<int>(Tr::kHermite[i][i] / k) + static_cast<int>(rep[i]);
  out.cell = cell_of<Tr>(cube, r);
  const auto& cell = Tr::kCells[out.cell];
  for (int i = 0; i < n; ++i) {
    const int p = cell.perm[i];
    out.x[i] = static_cast<T>(cell.sign[i]) * (x[p] - static_cast<T>(out.corner[p] - rep[p] * k)) +
               static_cast<T>(cell.a[i]);
  }
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
