#include "generator/rational_linear_systems.h"

#include <utility>

namespace boxgen::generator {

namespace {

// Brings `rows` to reduced row echelon form, with pivots only in the first `pivot_columns`
// columns (the row operations act on whole rows). Returns the pivot column of each leading row.
std::vector<int> reduce(std::vector<RatVec>& rows, int pivot_columns) {
  std::vector<int> pivots;
  std::size_t rank = 0;
  for (int col = 0; col < pivot_columns && rank < rows.size(); ++col) {
    std::size_t pivot = rank;
    while (pivot < rows.size() && cln::zerop(rows[pivot][col])) ++pivot;
    if (pivot == rows.size()) continue;
    std::swap(rows[pivot], rows[rank]);
    RatVec& lead = rows[rank];
    const Rational inverse = Rational(1) / lead[col];
    for (std::size_t j = col; j < lead.size(); ++j) lead[j] = lead[j] * inverse;
    for (std::size_t i = 0; i < rows.size(); ++i) {
      if (i == rank || cln::zerop(rows[i][col])) continue;
      const Rational f = rows[i][col];
      for (std::size_t j = col; j < lead.size(); ++j)
        if (!cln::zerop(lead[j])) rows[i][j] = rows[i][j] - f * lead[j];
    }
    pivots.push_back(col);
    ++rank;
  }
  return pivots;
}

std::vector<int> free_columns(const std::vector<int>& pivots, int columns) {
  std::vector<char> is_pivot(columns, 0);
  for (int c : pivots) is_pivot[c] = 1;
  std::vector<int> free;
  for (int c = 0; c < columns; ++c)
    if (!is_pivot[c]) free.push_back(c);
  return free;
}

}  // namespace

std::optional<LinearSolution> solve_exactly(std::vector<RatVec> rows, int unknowns) {
  const std::vector<int> pivots = reduce(rows, unknowns);
  for (std::size_t i = pivots.size(); i < rows.size(); ++i)
    if (!cln::zerop(rows[i][unknowns])) return std::nullopt;  // 0 = b with b != 0
  LinearSolution solution{RatVec(unknowns, Rational(0)), free_columns(pivots, unknowns)};
  for (std::size_t k = 0; k < pivots.size(); ++k) solution.values[pivots[k]] = rows[k][unknowns];
  return solution;
}

std::vector<RatVec> null_space(std::vector<RatVec> rows, int columns) {
  const std::vector<int> pivots = reduce(rows, columns);
  std::vector<RatVec> basis;
  for (int free : free_columns(pivots, columns)) {
    RatVec v(columns, Rational(0));
    v[free] = 1;
    for (std::size_t r = 0; r < pivots.size(); ++r) v[pivots[r]] = -rows[r][free];
    basis.push_back(std::move(v));
  }
  return basis;
}

}  // namespace boxgen::generator
