// boxrecon sample: a test function sampled on any lattice (runtime/lattice_volume.h) over
// [-1,1]^3, written as a lattice NRRD (or NIfTI for a Cartesian one, by the output's name).
#pragma once
#include <optional>
#include <string>

namespace boxgen::app {

// --function, --n, --h, --lattice, --filter (frontend/sample_grid.h: the grid, checked as Python's
// sample() checks it), --precision, -o. Every argument is checked before anything is allocated or
// written; a bad one throws std::invalid_argument (or runtime::NrrdError for -o), one line.
int run_sample(const std::string& function, int n, const std::optional<double>& h,
               const std::string& lattice, const std::string& filter, const std::string& precision,
               const std::string& output, const std::string& type = {});

}  // namespace boxgen::app
