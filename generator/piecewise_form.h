// The piecewise polynomial form of a box spline: every cell of the arrangement of its true knot
// planes inside its support, with the exact polynomial of the UNCENTRED M_Xi there (zero outside
// the support). The integer-level refinement of the same normals (FineArrangement) is what the
// emitter's lookup table uses; its cells take their polynomials from the knot cell holding them.
#pragma once
#include <functional>
#include <optional>

#include "generator/box_spline_derivation.h"
#include "generator/cell_complex.h"
#include "generator/spec.h"

namespace boxgen::generator {

// The bounding box [lo, hi] of the support Xi [0,1]^m.
class Zonotope {
 public:
  explicit Zonotope(const IntColumns& directions, int n);
  const IntVec& box_lo() const { return lo_; }
  const IntVec& box_hi() const { return hi_; }

 private:
  IntVec lo_, hi_;
};

// The fine arrangement: every integer level of the knot normals plus the axes (axes first), on
// the bounding box [lo, hi) of the support. It is invariant under integer shifts, so it holds the
// cells of the unit cube at the origin, split once (the cost estimate counts them, the spline
// structure translates them); every other cube's cells are their translates.
class FineArrangement {
 public:
  FineArrangement(std::vector<IntVec> normals, IntVec lo, IntVec hi)
      : normals_(std::move(normals)),
        lo_(std::move(lo)),
        hi_(std::move(hi)),
        unit_cells_(split_cube(normals_, IntVec(lo_.size(), 0))) {}
  const std::vector<IntVec>& normals() const { return normals_; }
  const IntVec& lo() const { return lo_; }
  const IntVec& hi() const { return hi_; }
  const std::vector<FineCell>& unit_cells() const { return unit_cells_; }
  // The arrangement of the directions divided by k (generator/common_scale.h): the same normals
  // and unit cube, on the box divided by k.
  FineArrangement scaled_down(std::int64_t k) const {
    FineArrangement out = *this;
    for (auto& v : out.lo_) v /= k;  // the support's box: sums of entries, multiples of k
    for (auto& v : out.hi_) v /= k;
    return out;
  }

 private:
  std::vector<IntVec> normals_;
  IntVec lo_, hi_;
  std::vector<FineCell> unit_cells_;
};

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
// The same pieces by the other method, on the cells of `form` (the second, independent derivation).
std::vector<Poly> rederive(const PiecewiseForm& form, DerivationMethod method,
                           const ProgressFn& progress = {});

}  // namespace boxgen::generator
