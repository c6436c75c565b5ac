// Cells of a hyperplane arrangement are identified by integer keys: for integer-level
// arrangements key_i = floor(nu_i . x); for knot-plane arrangements (levels L_0 < ... < L_r of
// normal i) key_i = the number of levels below nu_i . x, so that key_i = k means
// L_(k-1) < nu_i . x < L_k; for central arrangements key_i = 0 if nu_i . x > 0 else -1.
#pragma once
#include <cstdint>
#include <vector>

#include "generator/knot_normals.h"
#include "generator/rational.h"

namespace boxgen::generator {

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
// Key in the knot-plane arrangement (levels below nu_i . x, per normal).
CellKey interval_key(const KnotPlanes& planes, const RatVec& x);
// True if x lies on no knot plane.
bool off_knot_planes(const KnotPlanes& planes, const RatVec& x);
// True if no nu . x is an integer (x lies on no plane of the integer-level arrangement).
bool off_integer_planes(const std::vector<IntVec>& normals, const RatVec& x);

}  // namespace boxgen::generator
