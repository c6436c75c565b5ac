#include "generator/cell_key.h"

#include <algorithm>

namespace boxgen::generator {

CellKey floor_key(const std::vector<IntVec>& normals, const RatVec& x) {
  CellKey k;
  k.reserve(normals.size());
  for (const auto& nu : normals) k.push_back(static_cast<std::int32_t>(floor_to_int64(dot(nu, x))));
  return k;
}

CellKey sign_key(const std::vector<IntVec>& normals, const RatVec& x) {
  CellKey k;
  k.reserve(normals.size());
  for (const auto& nu : normals) k.push_back(cln::plusp(dot(nu, x)) ? 0 : -1);
  return k;
}

namespace {

// Number of levels strictly below v.
std::int32_t levels_below(const std::vector<std::int64_t>& levels, const Rational& v) {
  if (levels.empty() || v <= Rational(levels.front()))
    return 0;  // also far outside the 64-bit range
  if (v > Rational(levels.back())) return static_cast<std::int32_t>(levels.size());
  const std::int64_t f = floor_to_int64(v);
  // Below v means <= floor(v), except when v is itself an integer.
  auto it = is_integer(v) ? std::lower_bound(levels.begin(), levels.end(), f)
                          : std::upper_bound(levels.begin(), levels.end(), f);
  return static_cast<std::int32_t>(it - levels.begin());
}

}  // namespace

CellKey interval_key(const KnotPlanes& planes, const RatVec& x) {
  CellKey k;
  k.reserve(planes.normals.size());
  for (size_t i = 0; i < planes.normals.size(); ++i)
    k.push_back(levels_below(planes.levels[i], dot(planes.normals[i], x)));
  return k;
}

bool off_knot_planes(const KnotPlanes& planes, const RatVec& x) {
  for (size_t i = 0; i < planes.normals.size(); ++i) {
    const Rational v = dot(planes.normals[i], x);
    if (is_integer(v) &&
        std::binary_search(planes.levels[i].begin(), planes.levels[i].end(), floor_to_int64(v)))
      return false;
  }
  return true;
}

bool off_integer_planes(const std::vector<IntVec>& normals, const RatVec& x) {
  for (const auto& nu : normals)
    if (is_integer(dot(nu, x))) return false;
  return true;
}

}  // namespace boxgen::generator
