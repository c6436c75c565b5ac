// The grid of a non-Cartesian output lattice that no volume gives (boxrecon resample and sample
// with --lattice, Python's resample(lattice=)): one rule for the CLI and Python, so that the same
// spacing or count gives the same samples.
#pragma once
#include <optional>

#include "runtime/resample.h"

namespace boxgen::runtime {

// `lattice` at spacing h when one is given, else at the h whose grid over `box` holds the count
// of samples nearest count^3 (spacing_for_count); centred in the box (lattice_grid_in, which
// throws std::invalid_argument for an h that is not finite and > 0, or too many samples).
inline LatticeGrid lattice_grid_for(const CosetLattice& lattice, const Box& box,
                                    std::optional<double> spacing, int count) {
  const double n = count;
  const double h = spacing ? *spacing : spacing_for_count(lattice, box, n * n * n);
  return lattice_grid_in(lattice, box, h);
}

}  // namespace boxgen::runtime
