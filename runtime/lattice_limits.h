// The runtime's bound on the integers of a lattice: a lattice matrix's entries
// (CosetLattice::from_rows, CosetLattice::parse) and a prefilter tap's offsets
// (runtime/prefilter.h) are at most 2^20 in magnitude, so that the runtime's integer arithmetic on
// them cannot overflow: the determinant of three rows fits 64 bits (6 * 2^60 < 2^63), a tap's step
// fits an int.
#pragma once
#include <cstdint>

namespace boxgen::runtime {

inline constexpr std::int64_t kMaxLatticeEntry = std::int64_t{1} << 20;

}  // namespace boxgen::runtime
