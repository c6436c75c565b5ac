// The FIR interpolation prefilter qfir (docs/design.md §18), written once over the number type:
// the generator solves it in exact rationals (`boxgen prefilter --fir K`), the runtime in double
// from the evaluator's lattice values (`--prefilter qfir:K`), and a test requires the two to
// agree.
//
// With M(k) the filter's values at the lattice points and r = M * q (the spline at the samples
// after prefiltering a unit impulse with q), q minimises
//
//     sum_j ((M^s * (r - delta))(j))^2 + mu sum_j ((D * q)(j))^2,   M^s = M * ... * M (s times),
//
// over the weights of the given lattice points, subject to the moment conditions
// sum_j r(j) j^a = delta(a) for every multi-index |a| < order. Those say hat(q) A = 1 +
// O(|w|^order), A(w) = sum_k M(k) e^(-i w.k), which keeps the filter's approximation order because
// A = hat(M^c) + O(|w|^order) (the Strang-Fix conditions). By Parseval the first term is the
// integral over the Brillouin zone of |A|^(2 s) |A Q - 1|^2: the error at the samples for samples
// whose spectrum is |A|^(2 s) (s = 0: white samples). With s = 0 the objective is, up to a
// constant, the integral of (|A|^2 + mu |D|^2) |Q - conj(A) / (|A|^2 + mu |D|^2)|^2: the best
// approximation, in that weighted norm, of the interpolation prefilter 1 / A (mu = 0) or of its
// Tikhonov regularisation. It is well posed even where A vanishes at points (M7), since
// sum_j (M^(s+1) * q)(j)^2 = (1/|N|) integral_N |A^(s+1) Q|^2 > 0 for every q != 0.
#pragma once
#include <cstddef>
#include <cstdint>
#include <map>
#include <optional>
#include <utility>
#include <vector>

namespace boxgen::support {

// What the solver needs of a number type T: the magnitude used to choose pivots and a test for a
// value that counts as zero against a scale (exact types: exactly zero). double is below; the
// generator specialises it for CLN rationals.
template <class T>
struct FirArithmetic;

template <>
struct FirArithmetic<double> {
  static double magnitude(double x) { return x < 0 ? -x : x; }
  static bool negligible(double x, double scale) { return magnitude(x) <= 1e-11 * scale; }
  static double from_int(std::int64_t v) { return static_cast<double>(v); }
};

using FirPoint = std::vector<std::int64_t>;

template <class T>
struct FirTap {
  FirPoint point;
  T value;
};

// qfir's s (docs/design.md §18): the samples' spectrum modelled as |A|^4, the filter's lattice
// samples applied twice to white noise, so the taps follow 1 / A where A, and a signal's samples,
// are large rather than where A vanishes (s = 0 spends them there on M7).
inline constexpr int kQfirSmoothing = 2;

template <class T>
struct FirPrefilterProblem {
  int order = 0;                              // the moment conditions of degree < order
  std::vector<FirTap<T>> samples;             // M(k) at the lattice points where it is not zero
  std::vector<std::vector<FirPoint>> groups;  // the unknowns: each group shares one weight
  std::vector<FirTap<T>> regulariser;         // D (empty: none)
  T mu{};                                     // the weight of |D q|^2
  // s: the residual is measured after s further convolutions with M, sum_j ((M^s * (M * q -
  // delta))(j))^2, which weights |A Q - 1|^2 by |A|^(2 s) (0: the plain residual).
  int smoothing = 0;
};

namespace fir_detail {

template <class T>
using Matrix = std::vector<std::vector<T>>;

// The matrix of q -> filter * q on the groups: one row per lattice point the result can reach.
template <class T>
Matrix<T> convolution_rows(const std::vector<FirTap<T>>& filter,
                           const std::vector<std::vector<FirPoint>>& groups,
                           std::vector<FirPoint>* row_points = nullptr) {
  std::map<FirPoint, std::size_t> row_of;
  Matrix<T> rows;
  for (std::size_t g = 0; g < groups.size(); ++g)
    for (const FirPoint& p : groups[g])
      for (const FirTap<T>& tap : filter) {
        FirPoint j = p;
        for (std::size_t i = 0; i < j.size(); ++i) j[i] += tap.point[i];
        auto [it, added] = row_of.emplace(j, rows.size());
        if (added) {
          rows.emplace_back(groups.size(), T(0));
          if (row_points) row_points->push_back(j);
        }
        rows[it->second][g] = rows[it->second][g] + tap.value;
      }
  return rows;
}

// The taps of a * b.
template <class T>
std::vector<FirTap<T>> convolve(const std::vector<FirTap<T>>& a, const std::vector<FirTap<T>>& b) {
  std::map<FirPoint, T> sum;
  for (const FirTap<T>& x : a)
    for (const FirTap<T>& y : b) {
      FirPoint j = x.point;
      for (std::size_t i = 0; i < j.size(); ++i) j[i] += y.point[i];
      auto [it, added] = sum.emplace(j, T(0));
      it->second = it->second + x.value * y.value;
    }
  std::vector<FirTap<T>> out;
  for (auto& [j, v] : sum) out.push_back({j, v});
  return out;
}

// Multi-indices a with |a| < order in `dimension` variables.
inline std::vector<std::vector<int>> multi_indices(int dimension, int order) {
  std::vector<std::vector<int>> out;
  std::vector<int> a(static_cast<std::size_t>(dimension), 0);
  const auto walk = [&](auto&& self, int i, int budget) -> void {
    if (i == dimension) {
      out.push_back(a);
      return;
    }
    for (int e = 0; e <= budget; ++e) {
      a[static_cast<std::size_t>(i)] = e;
      self(self, i + 1, budget - e);
    }
    a[static_cast<std::size_t>(i)] = 0;
  };
  if (order > 0) walk(walk, 0, order - 1);
  return out;
}

// Gauss-Jordan elimination of the augmented rows [A | b] with partial pivoting. Returns the pivot
// column of each leading row (the rows are left reduced, pivots 1), or nullopt when a row without
// a pivot keeps a right-hand side that is not negligible.
template <class T>
std::optional<std::vector<std::size_t>> reduce(Matrix<T>& rows, std::size_t unknowns) {
  using A = FirArithmetic<T>;
  T scale(0);
  for (const auto& row : rows)
    for (std::size_t c = 0; c < unknowns; ++c)
      if (A::magnitude(scale) < A::magnitude(row[c])) scale = A::magnitude(row[c]);
  std::vector<std::size_t> pivots;
  std::size_t next = 0;
  for (std::size_t c = 0; c < unknowns && next < rows.size(); ++c) {
    std::size_t best = next;
    for (std::size_t r = next + 1; r < rows.size(); ++r)
      if (A::magnitude(rows[best][c]) < A::magnitude(rows[r][c])) best = r;
    if (A::negligible(rows[best][c], scale)) continue;
    std::swap(rows[best], rows[next]);
    const T inverse = T(1) / rows[next][c];
    for (T& x : rows[next]) x = x * inverse;
    for (std::size_t r = 0; r < rows.size(); ++r) {
      if (r == next) continue;
      const T f = rows[r][c];
      if (f == T(0)) continue;
      for (std::size_t k = 0; k <= unknowns; ++k) rows[r][k] = rows[r][k] - f * rows[next][k];
    }
    pivots.push_back(c);
    ++next;
  }
  T rhs_scale(1);
  for (std::size_t r = next; r < rows.size(); ++r)
    if (!A::negligible(rows[r][unknowns], rhs_scale)) return std::nullopt;
  return pivots;
}

}  // namespace fir_detail

// The weight of each group; nullopt when no weights on these groups satisfy the moment
// conditions (too few lattice points for the order).
template <class T>
// NOLINTNEXTLINE(readability-function-cognitive-complexity): one elimination, kept whole to read
std::optional<std::vector<T>> solve_fir_prefilter(const FirPrefilterProblem<T>& problem) {
  using A = FirArithmetic<T>;
  using fir_detail::Matrix;
  const std::size_t unknowns = problem.groups.size();
  if (unknowns == 0 || problem.samples.empty()) return std::nullopt;
  const int n = static_cast<int>(problem.samples.front().point.size());

  // r = R q, with the lattice point of every row.
  std::vector<FirPoint> points;
  const Matrix<T> r = fir_detail::convolution_rows(problem.samples, problem.groups, &points);

  // The moment conditions sum_j r(j) j^a = delta(a), as rows [C | d].
  Matrix<T> conditions;
  for (const auto& a : fir_detail::multi_indices(n, problem.order)) {
    std::vector<T> row(unknowns + 1, T(0));
    bool constant = true;
    for (int e : a) constant = constant && e == 0;
    row[unknowns] = constant ? T(1) : T(0);
    for (std::size_t j = 0; j < points.size(); ++j) {
      T power(1);
      for (int i = 0; i < n; ++i)
        for (int e = 0; e < a[static_cast<std::size_t>(i)]; ++e)
          power = power * A::from_int(points[j][static_cast<std::size_t>(i)]);
      for (std::size_t g = 0; g < unknowns; ++g) row[g] = row[g] + power * r[j][g];
    }
    conditions.push_back(std::move(row));
  }
  const auto pivots = fir_detail::reduce(conditions, unknowns);
  if (!pivots) return std::nullopt;

  // q = q0 + N t: q0 the particular solution with the free weights zero, N one column per free
  // weight.
  std::vector<bool> is_pivot(unknowns, false);
  for (std::size_t c : *pivots) is_pivot[c] = true;
  std::vector<T> q0(unknowns, T(0));
  for (std::size_t i = 0; i < pivots->size(); ++i) q0[(*pivots)[i]] = conditions[i][unknowns];
  std::vector<std::size_t> free;
  for (std::size_t c = 0; c < unknowns; ++c)
    if (!is_pivot[c]) free.push_back(c);
  if (free.empty()) return q0;
  Matrix<T> basis(free.size(), std::vector<T>(unknowns, T(0)));
  for (std::size_t f = 0; f < free.size(); ++f) {
    basis[f][free[f]] = T(1);
    for (std::size_t i = 0; i < pivots->size(); ++i)
      basis[f][(*pivots)[i]] = T(0) - conditions[i][free[f]];
  }

  // The normal equations [H | g] of the least squares in t, term by term. (The row is grown by
  // one rather than sized free.size() + 1, which GCC 12 takes for a possible overflow.)
  std::vector<T> zero_row(free.size(), T(0));
  zero_row.push_back(T(0));
  Matrix<T> h(free.size(), zero_row);
  const auto add_term = [&](const std::vector<FirTap<T>>& filter, const T& weight,
                            const std::vector<FirTap<T>>& target) {
    // op (q0 + N t) - e, op: q -> filter * q, e: the target's values (none: 0).
    std::vector<FirPoint> op_points;
    const Matrix<T> op = fir_detail::convolution_rows(filter, problem.groups, &op_points);
    std::vector<std::vector<T>> columns(free.size(), std::vector<T>(op.size(), T(0)));
    std::vector<T> offset(op.size(), T(0));
    for (std::size_t j = 0; j < op.size(); ++j) {
      for (std::size_t c = 0; c < unknowns; ++c) offset[j] = offset[j] + op[j][c] * q0[c];
      for (std::size_t f = 0; f < free.size(); ++f)
        for (std::size_t c = 0; c < unknowns; ++c)
          columns[f][j] = columns[f][j] + op[j][c] * basis[f][c];
    }
    // A target value where op reaches nothing adds a constant to the objective: skipped.
    std::map<FirPoint, std::size_t> row_of;
    for (std::size_t j = 0; j < op_points.size(); ++j) row_of.emplace(op_points[j], j);
    for (const FirTap<T>& e : target)
      if (const auto it = row_of.find(e.point); it != row_of.end())
        offset[it->second] = offset[it->second] - e.value;
    for (std::size_t a = 0; a < free.size(); ++a) {
      for (std::size_t b = 0; b < free.size(); ++b) {
        T s(0);
        for (std::size_t j = 0; j < op.size(); ++j) s = s + columns[a][j] * columns[b][j];
        h[a][b] = h[a][b] + weight * s;
      }
      T s(0);
      for (std::size_t j = 0; j < op.size(); ++j) s = s + columns[a][j] * offset[j];
      h[a][free.size()] = h[a][free.size()] - weight * s;
    }
  };
  // The residual M^s * (M * q - delta) = M^(s+1) * q - M^s.
  std::vector<FirTap<T>> smoothing{{FirPoint(static_cast<std::size_t>(n), 0), T(1)}};
  for (int s = 0; s < problem.smoothing; ++s)
    smoothing = fir_detail::convolve(smoothing, problem.samples);
  add_term(fir_detail::convolve(smoothing, problem.samples), T(1), smoothing);
  if (!problem.regulariser.empty() && !(problem.mu == T(0)))
    add_term(problem.regulariser, problem.mu, {});
  // H is positive definite (the objective is strictly convex in t).
  const auto solved = fir_detail::reduce(h, free.size());
  if (!solved || solved->size() != free.size()) return std::nullopt;
  std::vector<T> q = q0;
  for (std::size_t f = 0; f < free.size(); ++f)
    for (std::size_t c = 0; c < unknowns; ++c) q[c] = q[c] + h[f][free.size()] * basis[f][c];
  return q;
}

}  // namespace boxgen::support
