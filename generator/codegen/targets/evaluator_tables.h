// The tables of an emitted evaluator, whatever its language (docs/design.md §11): the knot
// planes that key the cell lookup, the lattice's Hermite basis, and per fundamental cell its
// cube, orbit, keys, the signed permutation onto its orbit's reference region and its stencil.
#pragma once
#include <vector>

#include "generator/derivation.h"

namespace boxgen::generator {

// Knot planes other than the axes and the combined key of floor(nu . r), r in [0,1)^n, that
// indexes the lookup table: key = sum_k (floor(nu_k . r) - min_k) stride_k.
struct KnotPlaneKeys {
  std::vector<IntVec> planes;
  std::vector<int> mins, widths, strides{1};
  long size() const { return strides.back(); }
};

// Per fundamental cell: its place in the lookup table, its row of the cell table and its stencil
// offsets from the corner floor(x + c); with the stencil reach over all cells. Numbers only: each
// target's printer formats them.
struct CellTables {
  std::vector<std::vector<int>> lookup;  // [cube][key] -> cell or -1
  IntVec reach_lo, reach_hi;             // offsets j - floor(x + c) per axis, over every cell
  std::vector<int> cube, orbit;
  std::vector<std::vector<int>> keys;        // per cell: floor keys (and a trailing 0)
  std::vector<std::vector<int>> perm, sign;  // x_ref_i = sign_i (x - t)_perm_i + a_i
  std::vector<IntVec> a;
  std::vector<std::vector<IntVec>> offset;  // per cell, per stencil point
};

KnotPlaneKeys knot_plane_keys(const Derivation& a);
// The Hermite basis (columns) recovered from the coset representatives' ranges.
IntColumns hermite_basis(const Derivation& a);
CellTables cell_tables(const Derivation& a, const KnotPlaneKeys& keys, const IntColumns& hermite);

}  // namespace boxgen::generator
