// The piecewise polynomial form of a box spline: every cell of the arrangement of its true knot
// planes inside its support, with the exact polynomial of the UNCENTRED M_Xi there (zero outside
// the support). The integer-level refinement of the same normals (FineArrangement) is what the
// emitter's lookup table uses; its cells take their polynomials from the knot cell holding them.
#pragma once
#include <functional>
#include <optional>

#include "generator/box_spline_derivation.h"
#include "generator/cell_complex.h"
#include "generator/fine_arrangement.h"
#include "generator/spec.h"
#include "generator/zonotope.h"

namespace boxgen::generator {

struct PiecewiseForm {
  PiecewiseForm(BoxSplineSpec s, DerivationMethod m, KnotComplex k, FineArrangement f)
      : spec(std::move(s)),
        method(m),
        knots(std::move(k)),
        complex(std::move(f)),
        zero_(spec.dimension(), 0) {}

  BoxSplineSpec spec;
  DerivationMethod method;
  KnotComplex knots;        // where the pieces are derived
  FineArrangement complex;  // the emitter's refinement
  std::vector<Poly> polys;  // M_Xi on knots.cells()[i]
  double seconds = 0;

  int dimension() const { return spec.dimension(); }
  // Polynomial at a point on no knot plane (every interior point of a fine cell is one); zero
  // outside the support.
  const Poly& poly_at(const RatVec& x) const;
  // Exact value of M_Xi (uncentred) at any point. Throws InputError if the adjacent pieces
  // disagree there (a discontinuity of the value or of the requested derivative).
  Rational value_at(const RatVec& x, const std::array<int, 3>& derivative = {0, 0, 0}) const;

 private:
  Poly zero_;
};

// Reports progress of a long derivation: stage, cells done, cells in total.
using ProgressFn = std::function<void(const char* stage, std::size_t done, std::size_t total)>;

// Refuses (InputError, before deriving any polynomial) what the cost estimate puts beyond
// max_seconds or max_bytes; 0 means the default limit (cost_estimate.h: 600 s, the available
// memory). The estimate covers the analysis with its checks (default or full) when the caller will
// run them.
struct DerivationBudget {
  double max_seconds = 0;
  double max_bytes = 0;
  bool with_checks = false;
  bool full_checks = false;
};
PiecewiseForm derive_piecewise(const BoxSplineSpec& spec, DerivationMethod method,
                               const ProgressFn& progress = {},
                               const DerivationBudget& budget = {});
// The same pieces by the other method (the second, independent derivation), on every cell of
// `form`, or on the cells listed in `cells` only, in that order.
std::vector<Poly> rederive(const PiecewiseForm& form, DerivationMethod method,
                           const ProgressFn& progress = {},
                           const std::vector<int>* cells = nullptr);

}  // namespace boxgen::generator
