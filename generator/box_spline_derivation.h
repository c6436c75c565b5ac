// The two independent exact derivations of the piecewise polynomials of the uncentred box
// spline M_Xi (integral 1, support Xi[0,1]^m):
//  - DirectionalIntegration: the box-spline recurrence M_{Xi+xi}(x) = int_0^1 M_Xi(x - t xi) dt
//    (docs/design.md §5), lazily from the parallelepiped up;
//  - TruncatedPower: finite differences of the truncated power (docs/design.md §5),
//    M_Xi(x) = sum_S (-1)^|S| T_Xi(x - sum S), with T derived along rays on the central
//    arrangement.
// Both answer "the polynomial of M_Xi on the cell containing the generic point p".
#pragma once
#include <map>
#include <memory>
#include <unordered_map>

#include "generator/level_integrator.h"
#include "generator/poly_sum.h"
#include "generator/spec.h"

namespace boxgen::generator {

enum class DerivationMethod { TruncatedPower, DirectionalIntegration };

class BoxSplineDerivation {
 public:
  virtual ~BoxSplineDerivation() = default;
  // p must lie on no plane nu.x = integer of the knot normals.
  virtual Poly polynomial_at(const RatVec& p) = 0;
  static std::unique_ptr<BoxSplineDerivation> make(const IntColumns& directions, int n,
                                                   DerivationMethod m);
};

class DirectionalIntegrationDerivation final : public BoxSplineDerivation {
 public:
  DirectionalIntegrationDerivation(const IntColumns& directions, int n);
  Poly polynomial_at(const RatVec& p) override { return integrator_.top(p); }

 private:
  LevelIntegrator integrator_;
};

class TruncatedPowerDerivation final : public BoxSplineDerivation {
 public:
  TruncatedPowerDerivation(const IntColumns& directions, int n);
  Poly polynomial_at(const RatVec& p) override;

 private:
  struct KeyHash {
    std::size_t operator()(const std::pair<CellKey, int>& k) const noexcept {
      return CellKeyHash{}(k.first) * 31u + static_cast<std::size_t>(k.second);
    }
  };
  int n_;
  LevelIntegrator integrator_;
  std::vector<std::pair<IntVec, Integer>> shifts_;  // M_Xi(x) = sum_s w_s T(x - s)
  std::vector<std::vector<std::int64_t>>
      normal_dot_shift_;  // per shift: nu . s for every normal of T
  // T's piece moved by shift k and weighted, as integers over a denominator (summed per cell).
  std::unordered_map<std::pair<CellKey, int>, ScaledPoly, KeyHash> translated_;
};

// Columns flipped into the open half-space h.x > 0 (h generic), and the sum of the flipped
// original columns delta, so that M_Xi(y) = M_Xi'(y - delta).
struct HalfSpaceFlip {
  IntColumns columns;
  IntVec delta;
};
HalfSpaceFlip flip_into_half_space(const IntColumns& directions, int n);

}  // namespace boxgen::generator
