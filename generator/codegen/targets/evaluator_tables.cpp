#include "generator/codegen/targets/evaluator_tables.h"

#include <limits>

#include "generator/error.h"

namespace boxgen::generator {

// Knot planes other than the axes and the combined key of floor(nu . r), r in [0,1)^n, that
// indexes the lookup table: key = sum_k (floor(nu_k . r) - min_k) stride_k.
KnotPlaneKeys knot_plane_keys(const Derivation& a) {
  const int n = a.spec.dimension();
  const auto& normals = a.form.complex.normals();
  KnotPlaneKeys keys;
  keys.planes.assign(normals.begin() + n, normals.end());  // axes come first in the arrangement
  for (const auto& nu : keys.planes) {
    int lo = 0, width = 0;
    for (auto v : nu) {
      lo += v < 0 ? static_cast<int>(v) : 0;
      width += static_cast<int>(v < 0 ? -v : v);
    }
    keys.mins.push_back(lo);
    keys.widths.push_back(width);
    keys.strides.push_back(keys.strides.back() * width);
  }
  if (keys.size() > 1 << 20)
    fail_input("emission: too many knot planes per unit cube for a lookup table");
  return keys;
}

// The Hermite basis (columns) recovered from the coset representatives' ranges: the first
// multiple d e_j that leaves the representatives' box is d e_j - reduce(d e_j) = column j.
IntColumns hermite_basis(const Derivation& a) {
  const int n = a.spec.dimension();
  IntColumns hermite(n, IntVec(n, 0));
  for (int j = 0; j < n; ++j) {
    IntVec e(n, 0);
    for (std::int64_t d = 1;; ++d) {
      e[j] = d;
      const IntVec r = a.spec.lattice.reduce(e);
      IntVec col(n);
      for (int i = 0; i < n; ++i) col[i] = e[i] - r[i];
      if (col[j] != 0) {
        hermite[j] = col;
        break;
      }
    }
  }
  return hermite;
}

CellTables cell_tables(const Derivation& a, const KnotPlaneKeys& keys, const IntColumns& hermite) {
  const SplineStructure& s = a.structure;
  const int n = a.spec.dimension();
  // The cubes and keys of a scaled pair are the reduced frame's (SplineStructure::scale); the
  // offsets and translations below are in the user's frame.
  const std::int64_t k = s.scale;
  auto cube_index = [&](const IntVec& rep) {
    int idx = 0;
    for (int i = n - 1; i >= 0; --i)
      idx = idx * static_cast<int>(hermite[i][i] / k) + static_cast<int>(rep[i]);
    return idx;
  };
  std::int64_t cubes = a.spec.lattice.det_abs();
  for (int i = 0; i < n; ++i) cubes /= k;
  CellTables t;
  t.lookup.assign(cubes, std::vector<int>(keys.size(), -1));
  t.reach_lo.assign(n, std::numeric_limits<std::int64_t>::max());
  t.reach_hi.assign(n, std::numeric_limits<std::int64_t>::min());
  for (size_t c = 0; c < s.cells.size(); ++c) {
    const auto& fc = s.cells[c];
    const IntVec rep(fc.cell.key.begin(), fc.cell.key.begin() + n);
    const auto& region = s.regions[fc.region];
    const int cube = cube_index(rep);
    std::vector<int> local_keys;
    long index = 0;
    for (size_t p = 0; p < keys.planes.size(); ++p) {
      const int local = fc.cell.key[n + p] - static_cast<int>(dot(keys.planes[p], rep));
      local_keys.push_back(local);
      index += static_cast<long>(local - keys.mins[p]) * keys.strides[p];
    }
    t.lookup[cube][index] = static_cast<int>(c);
    t.cube.push_back(cube);
    t.orbit.push_back(static_cast<int>(region.orbit));
    IntVec corner_offset = rep;  // rep in the user's frame
    for (auto& v : corner_offset) v *= k;
    local_keys.push_back(0);
    t.keys.push_back(local_keys);
    const auto& g = region.to_reference.g;
    // x_ref = g (x - t + p) + l = g (x - t) + (g p + l), t = corner - rep
    IntVec gp = g.apply(fc.placement), av(n);
    for (int i = 0; i < n; ++i) av[i] = gp[i] + region.to_reference.l[i];
    // Stencil point k of the orbit sits at j[perm_i] = sign_i (s_i - a_i) + t[perm_i].
    t.perm.emplace_back(g.perm.begin(), g.perm.end());
    t.sign.emplace_back(g.sign.begin(), g.sign.end());
    t.a.push_back(av);
    t.offset.emplace_back();
    for (const auto& sp : s.references[region.orbit].stencil) {
      IntVec d(n);
      for (int i = 0; i < n; ++i) {
        const int axis = g.perm[i];
        d[axis] = g.sign[i] * (sp[i] - av[i]) - corner_offset[axis];
        t.reach_lo[axis] = std::min(t.reach_lo[axis], d[axis]);
        t.reach_hi[axis] = std::max(t.reach_hi[axis], d[axis]);
      }
      t.offset.back().push_back(d);
    }
  }
  return t;
}

}  // namespace boxgen::generator
