// What a derivation will cost, predicted without deriving: `boxgen analyze --estimate` prints it
// and the up-front refusal uses the same numbers, so a user can see and raise the limit.
//
// The work follows the cells: the knot cells of M_Xi (each gets a polynomial from both
// derivations and is checked) and the fine cells of the fundamental region (each sums its
// stencil's pieces). Knot cells are counted exactly by enumerating the arrangement (geometry
// only) unless a general-position bound shows there are too many to enumerate quickly. The
// per-cell costs are calibrated on this project's 2-core machine (README, "Derivation cost").
#pragma once
#include <cstddef>

#include "generator/spec.h"

namespace boxgen::generator {

struct CostEstimate {
  double seconds = 0;
  double bytes = 0;
  std::size_t knot_cells = 0;         // cells of the knot-plane arrangement in the support
  bool cells_exact = false;           // false: knot_cells is a general-position upper bound
  std::size_t fundamental_cells = 0;  // fine cells of the fundamental region
};

// Predicts `boxgen analyze` (with the exact checks if `verify`, every cell if `full_checks`).
CostEstimate estimate_cost(const BoxSplineSpec& spec, bool verify = true, bool full_checks = false);
// The same when the knot cells and the cells of one unit cube of the fine arrangement are
// already counted (no second enumeration or split).
CostEstimate estimate_cost(const BoxSplineSpec& spec, std::size_t knot_cells,
                           std::size_t cube_cells, bool verify, bool full_checks);
// Throws InputError before anything is enumerated if even a bound on the knot cells is beyond
// what can be enumerated (a guard against hangs; the estimate proper needs the count).
void refuse_if_too_many_cells(const BoxSplineSpec& spec);

inline constexpr double kDefaultMaxSeconds = 600;
// Throws InputError, with the prediction in the message, if it exceeds max_seconds (0: default).
void refuse_if_too_costly(const CostEstimate& e, double max_seconds);

}  // namespace boxgen::generator
