// The grid `boxrecon sample` and Python's sample() sample on: --n, --h, --lattice and --filter
// checked before anything is allocated (apps/boxrecon/sample_command.h writes the samples).
#pragma once
#include <cstddef>
#include <optional>
#include <string>

#include "runtime/sampling.h"
#include "runtime/spline_filter.h"

namespace boxgen::frontend {

// The lattice `--lattice` names (bcc | fcc | cartesian | rows of G), which must hold the same
// points as the filter's own lattice; empty: the filter's. Throws std::invalid_argument (one line)
// for a lattice that is not the filter's: error and render sample on the filter's lattice only.
runtime::CosetLattice lattice_for(const runtime::SplineFilter& f, const std::string& lattice);

// --n, --h, --lattice (bcc | fcc | cartesian | "a,b,c; d,e,f; g,h,i"; empty: the filter's
// lattice, else bcc) and --filter (a registry filter, or empty: with --lattice, its lattice must
// be the filter's), with the memory of K N^3 samples of `bytes_per_sample` bytes; a bad one throws
// std::invalid_argument, one line. The margin beyond [-1,1]^3 is 3 coset cells, or more where a
// registry filter of the lattice needs more for reconstruction after Q^I or Q^II: the grid does
// not depend on --filter.
runtime::LatticeGrid sample_grid(int n, const std::optional<double>& h, const std::string& lattice,
                                 const std::string& filter, std::size_t bytes_per_sample);

}  // namespace boxgen::frontend
