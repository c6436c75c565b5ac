// The BCC volumes most runtime tests start from: a function sampled over the cube [-1,1]^3 at
// density n with `margin` extra coset cells per side (runtime/sampling.h), and the same samples
// with the cosets stored the other way round.
#pragma once
#include <cstddef>
#include <utility>
#include <vector>

#include "runtime/sampling.h"

namespace boxgen::test {

template <class T>
runtime::LatticeVolume<T> sample_bcc_cube(const runtime::ScalarFunction& f, int n, int margin) {
  return runtime::sample_lattice<T>(
      f, runtime::cube_lattice_grid(runtime::CosetLattice::bcc(), n, margin));
}

// The same BCC samples stored with the cosets in the order (1,1,1) (0,0,0): a volume the
// runtime reads through the general lattice tables rather than BCC's parity tables.
template <class T>
runtime::LatticeVolume<T> swapped_cosets(const runtime::LatticeVolume<T>& bcc) {
  std::vector<T> samples(bcc.sample_count());
  for (std::size_t s = 0; s < samples.size(); ++s) samples[s] = bcc.samples()[s ^ 1];
  return runtime::LatticeVolume<T>(bcc.lattice().with_offsets({{1, 1, 1}, {0, 0, 0}}), bcc.sizes(),
                                   bcc.spacing(), bcc.origin(), std::move(samples));
}

}  // namespace boxgen::test
