// boxrecon sample: a test function sampled on any lattice (runtime/lattice_volume.h) over
// [-1,1]^3, written as a lattice NRRD (or NIfTI for a Cartesian one, by the output's name).
#pragma once
#include <cstddef>
#include <optional>
#include <string>

#include "runtime/sampling.h"
#include "runtime/spline_filter.h"

namespace boxgen::app {

// The lattice `--lattice` names (bcc | fcc | cartesian | rows of G), which must hold the same
// points as the filter's own lattice; empty: the filter's. Throws std::invalid_argument (one line)
// for a lattice that is not the filter's: error and render sample on the filter's lattice only.
runtime::CosetLattice lattice_for(const runtime::SplineFilter& f, const std::string& lattice);

// --function, --n, --h, --lattice (bcc | fcc | cartesian | "a,b,c; d,e,f; g,h,i"; empty: the
// filter's lattice, else bcc), --filter (a registry filter, or empty: with --lattice, its lattice
// must be the filter's), --precision, -o. Every argument is checked before anything is allocated or
// written; a bad one throws std::invalid_argument (or runtime::NrrdError for -o), one line.
// The margin beyond [-1,1]^3 is 3 coset cells, or more where a registry filter of the lattice
// needs more for reconstruction after Q^I or Q^II: the file does not depend on --filter.
// The grid run_sample samples on: every argument but --function, --precision and -o checked as
// run_sample does, the memory of K N^3 samples of `bytes_per_sample` bytes too (the Python
// module's sample() takes the same grid).
runtime::LatticeGrid sample_grid(int n, const std::optional<double>& h, const std::string& lattice,
                                 const std::string& filter, std::size_t bytes_per_sample);

int run_sample(const std::string& function, int n, const std::optional<double>& h,
               const std::string& lattice, const std::string& filter, const std::string& precision,
               const std::string& output, const std::string& type = {});

}  // namespace boxgen::app
