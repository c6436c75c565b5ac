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
#include <vector>

#include "generator/spec.h"

namespace boxgen::generator {

struct CostEstimate {
  double seconds = 0;
  double bytes = 0;
  std::size_t knot_cells = 0;         // cells of the knot-plane arrangement in the support
  bool cells_exact = false;           // false: knot_cells is a general-position upper bound
  std::size_t fundamental_cells = 0;  // fine cells of the fundamental region
  // The second derivation (directional integration, the default check) integrates, column by
  // column, every cell of M_k for the first k = n, ..., m - 1 columns (in basis_first order):
  // their cells, exact when cells_exact, and the predicted seconds and bytes of that work.
  std::vector<std::size_t> level_cells;
  // The work counts the terms multiply (printed by `analyze --estimate --json`), so a prediction
  // can be checked term by term.
  struct Work {
    double plane_checks = 0;     // knot cell x monomial x knot plane (checks on the pieces)
    double integration = 0;      // sum over levels: cells x integration_work
    double integration_deg = 0;  // the same, each level weighted by its degree (longer numbers)
    double stored = 0;           // sum over levels: coefficients a cell keeps (poly, G_e, jump)
    double stencil = 0;          // fine cell x stencil point
    double fine = 0;             // fine cells of F
  } work;
};

// Cells of M_k for the first k = n, ..., m - 1 columns of basis_first(directions); a
// general-position bound for a level with too many cells to enumerate (then `exact` is false).
std::vector<std::size_t> integration_level_cells(const BoxSplineSpec& spec, bool* exact = nullptr);
// Rational multiply-adds of one cell of degree `degree` integrated along `direction`:
// Poly::along_direction's loop (per monomial, the product over nonzero components of e_k + 1)
// plus the Horner composition of one jump (LevelIntegrator::jump).
double integration_work(int n, int degree, const IntVec& direction);

// Predicts `boxgen analyze` (with the exact checks if `verify`, every cell if `full_checks`).
CostEstimate estimate_cost(const BoxSplineSpec& spec, bool verify = true, bool full_checks = false);
// The same when the knot cells and the cells of one unit cube of the fine arrangement are
// already counted (no second enumeration or split).
CostEstimate estimate_cost(const BoxSplineSpec& spec, std::size_t knot_cells,
                           std::size_t cube_cells, bool verify, bool full_checks);
// Throws InputError before anything is enumerated if even a bound on the knot cells is beyond
// what can be enumerated (a guard against hangs; the estimate proper needs the count).
void refuse_if_too_many_cells(const BoxSplineSpec& spec);

// Throws InputError, as refuse_if_too_costly, when the knot cells are too many to be counted
// exactly (their general-position bound beyond what estimate_cost enumerates) and the prediction
// on that bound (what `--estimate` prints) is beyond the limits: before anything is enumerated,
// which for such a SPEC alone takes minutes and gigabytes. Does nothing otherwise (the exact
// count, made by the derivation itself, decides then).
void refuse_up_front_if_too_costly(const BoxSplineSpec& spec, bool verify, bool full_checks,
                                   double max_seconds, double max_bytes);

inline constexpr double kDefaultMaxSeconds = 600;
// Throws InputError, with the prediction and the limit in one line, if the predicted time
// exceeds max_seconds (0: kDefaultMaxSeconds) or the predicted memory exceeds max_bytes (0: the
// memory this process may still take, support::available_memory_bytes).
void refuse_if_too_costly(const CostEstimate& e, double max_seconds, double max_bytes = 0);

}  // namespace boxgen::generator
