// Common-subexpression elimination on fixed linear combinations (README.md, `boxgen emit`):
// the monomial coefficients of a reference polynomial are rows of a sparse rational matrix times
// the stencil values. Pairs of inputs that occur with the same weight ratio in several rows are
// summed once into a temporary t = x_a + r x_b that those rows then share (greedy, the most
// frequent pair first).
#pragma once
#include <utility>
#include <vector>

#include "generator/rational.h"

namespace boxgen::expr {

using generator::Rational;

using LinearRow = std::vector<std::pair<int, Rational>>;  // (input, weight), weight != 0

struct SharedSum {
  int a, b;    // inputs (stencil values or earlier temporaries)
  Rational r;  // t = x_a + r x_b
};

struct SharedRows {
  std::vector<SharedSum> temporaries;  // temporary j is input `inputs + j`
  std::vector<LinearRow> rows;         // the same linear forms over inputs and temporaries
};

// rows over `inputs` inputs; gives up sharing (returns the rows unchanged) beyond `max_entries`
// non-zeros, where the pair search would cost more than the emission is worth.
SharedRows share_partial_sums(const std::vector<LinearRow>& rows, int inputs,
                              std::size_t max_entries = 4000);

}  // namespace boxgen::expr
