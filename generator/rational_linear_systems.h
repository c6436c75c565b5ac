// Exact linear systems over the rationals, by reduced row echelon form: the prefilter's order
// conditions (a particular solution) and the autocorrelation's eigenvector (a null space).
#pragma once
#include <optional>
#include <vector>

#include "generator/rational.h"

namespace boxgen::generator {

struct LinearSolution {
  RatVec values;
  std::vector<int> free_columns;  // unknowns without a pivot, set to zero
};

// Solves the augmented rows [A | b] (each row has unknowns + 1 entries). Pivots are taken left to
// right, so the free unknowns are the last ones in column order. nullopt if inconsistent.
std::optional<LinearSolution> solve_exactly(std::vector<RatVec> rows, int unknowns);

// A basis of { x : A x = 0 } for rows of `columns` entries: one vector per free column.
std::vector<RatVec> null_space(std::vector<RatVec> rows, int columns);

}  // namespace boxgen::generator
