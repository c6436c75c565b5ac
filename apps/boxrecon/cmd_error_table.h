// `boxrecon error --table`: the Marschner-Lobb reconstruction error of M7, M8 and M12 on BCC
// for every density and prefilter of the paper, beside the tricubic B-spline on a Cartesian grid
// with the same number of samples (cmd_error_table.cpp).
#pragma once
#include <cstdint>

namespace boxgen::recon {

int run_error_table(int points, std::uint64_t seed, bool json);

}  // namespace boxgen::recon
