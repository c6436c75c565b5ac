// Cells of a hyperplane arrangement are identified by integer keys: for integer-level
// arrangements key_i = floor(nu_i . x); for central arrangements key_i = 0 if nu_i . x > 0 else -1.
#pragma once
#include <cstdint>
#include <vector>

#include "generator/rational.h"

namespace boxgen {

using CellKey = std::vector<std::int32_t>;

struct CellKeyHash {
  std::size_t operator()(const CellKey& k) const noexcept {
    std::uint64_t h = 1469598103934665603ull;
    for (auto v : k) h = (h ^ static_cast<std::uint32_t>(v)) * 1099511628211ull;
    return static_cast<std::size_t>(h);
  }
};

CellKey floor_key(const std::vector<IntVec>& normals, const RatVec& x);
CellKey sign_key(const std::vector<IntVec>& normals, const RatVec& x);
// True if no nu . x is an integer (x lies on no plane of the integer-level arrangement).
bool off_integer_planes(const std::vector<IntVec>& normals, const RatVec& x);

}  // namespace boxgen
