#include "generator/knot_normals.h"

#include <algorithm>
#include <set>

#include "generator/error.h"

namespace boxgen::generator {

std::vector<IntVec> knot_normals(const IntColumns& columns, int n) {
  std::set<IntVec> found;
  const size_t m = columns.size();
  if (n == 2) {
    for (size_t i = 0; i < m; ++i)
      if (auto nu = hyperplane_normal({columns[i]}, 2)) found.insert(*nu);
  } else {
    for (size_t i = 0; i < m; ++i)
      for (size_t j = i + 1; j < m; ++j)
        if (auto nu = hyperplane_normal({columns[i], columns[j]}, 3)) found.insert(*nu);
  }
  return {found.begin(), found.end()};
}

std::vector<std::int64_t> subset_sum_levels(const IntVec& nu, const IntColumns& columns) {
  std::set<std::int64_t> sums{0};
  for (const auto& xi : columns) {
    const std::int64_t d = dot(nu, xi);
    if (d == 0) continue;
    std::set<std::int64_t> next = sums;
    for (auto s : sums) next.insert(s + d);
    sums = std::move(next);
  }
  return {sums.begin(), sums.end()};
}

KnotPlanes knot_planes(const IntColumns& columns, int n) {
  KnotPlanes k;
  k.normals = knot_normals(columns, n);
  for (const auto& nu : k.normals) k.levels.push_back(subset_sum_levels(nu, columns));
  return k;
}

std::vector<IntVec> arrangement_normals(const IntColumns& columns, int n) {
  std::vector<IntVec> out;
  for (int i = 0; i < n; ++i) {
    IntVec e(n, 0);
    e[i] = 1;
    out.push_back(e);
  }
  for (auto& nu : knot_normals(columns, n))
    if (std::find(out.begin(), out.end(), nu) == out.end()) out.push_back(nu);
  return out;
}

IntColumns basis_first(const IntColumns& columns, int n) {
  IntColumns basis, rest;
  for (const auto& c : columns) {
    IntColumns trial = basis;
    trial.push_back(c);
    if (static_cast<int>(basis.size()) < n && rank(trial, n) == static_cast<int>(trial.size()))
      basis.push_back(c);
    else
      rest.push_back(c);
  }
  if (static_cast<int>(basis.size()) < n)
    fail_input("the directions do not span the space (rank deficient)");
  basis.insert(basis.end(), rest.begin(), rest.end());
  return basis;
}

}  // namespace boxgen::generator
