#include "generator/cell_key.h"

namespace boxgen {

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

bool off_integer_planes(const std::vector<IntVec>& normals, const RatVec& x) {
  for (const auto& nu : normals)
    if (is_integer(dot(nu, x))) return false;
  return true;
}

}  // namespace boxgen
