// Integer lattices L = G Z^n (docs/design.md §1): membership, reduction to coset
// representatives of Z^n / L (the fundamental region is the union of the unit cubes at those
// representatives), and shells of lattice points by distance.
#pragma once
#include <string>
#include <vector>

#include "generator/int_linalg.h"

namespace boxgen::generator {

class Lattice {
 public:
  // `generator` holds the columns of G. Throws InputError if G is singular.
  Lattice(std::string name, IntColumns generator);
  static Lattice cartesian(int n);
  static Lattice bcc();
  static Lattice fcc();

  const std::string& name() const { return name_; }
  int dimension() const { return n_; }
  const IntColumns& generator() const { return g_; }
  IntColumns generator_rows() const;
  std::int64_t det_abs() const { return det_abs_; }

  bool contains(const IntVec& x) const;
  // Returns the canonical representative r of x + L with 0 <= r_i < h_ii (Hermite form).
  IntVec reduce(const IntVec& x) const;
  // All |det G| canonical representatives of Z^n / L.
  std::vector<IntVec> coset_representatives() const;
  // Shells: lattice points grouped by squared norm, ascending; shells[0] = {0}.
  std::vector<std::vector<IntVec>> shells(int count) const;
  // Lattice points inside the box [lo_i, hi_i] (inclusive).
  std::vector<IntVec> points_in_box(const IntVec& lo, const IntVec& hi) const;

 private:
  std::string name_;
  int n_;
  IntColumns g_;
  IntColumns hermite_;  // lower-triangular basis: column j has zeros above row j
  std::int64_t det_abs_;
};

}  // namespace boxgen::generator
