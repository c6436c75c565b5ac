// The piecewise polynomial form of a box spline: every fine cell of the bounding box of its
// support with the exact polynomial of the UNCENTRED M_Xi there (zero outside the support).
#pragma once
#include <optional>

#include "generator/box_spline_derivation.h"
#include "generator/cell_complex.h"
#include "generator/spec.h"

namespace boxgen {

class Zonotope {
 public:
  explicit Zonotope(const IntColumns& directions, int n);
  bool contains_interior(const RatVec& x) const;  // strictly inside
  const IntVec& box_lo() const { return lo_; }
  const IntVec& box_hi() const { return hi_; }

 private:
  std::vector<IntVec> normals_;
  std::vector<Rational> centre_dot_, half_width_;
  IntVec lo_, hi_;
};

struct PiecewiseForm {
  PiecewiseForm(const BoxSplineSpec& s, DerivationMethod m, CellComplex c)
      : spec(s), method(m), complex(std::move(c)), zero_(spec.dimension(), 0) {}

  BoxSplineSpec spec;
  DerivationMethod method;
  CellComplex complex;
  std::vector<Poly> polys;  // M_Xi on complex.cells()[i]
  double seconds = 0;

  int dimension() const { return spec.dimension(); }
  // Polynomial of the cell with this key; zero polynomial for keys outside the box.
  const Poly& poly_for_key(const CellKey& key) const;
  // Exact value of M_Xi (uncentred) at any point. Throws InputError if the adjacent pieces
  // disagree there (a discontinuity of the value or of the requested derivative).
  Rational value_at(const RatVec& x, const std::array<int, 3>& derivative = {0, 0, 0}) const;

 private:
  Poly zero_;
};

// Throws InputError if the derivation would be too large to finish in reasonable time.
void check_derivation_size(const BoxSplineSpec& spec);
PiecewiseForm derive_piecewise(const BoxSplineSpec& spec, DerivationMethod method);

}  // namespace boxgen
