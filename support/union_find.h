// Disjoint sets over 0..n-1 with path compression: the generator merges cells into regions and
// regions into symmetry orbits with it.
#pragma once
#include <cstddef>
#include <numeric>
#include <vector>

namespace boxgen::support {

class UnionFind {
 public:
  explicit UnionFind(std::size_t n) : parent_(n) { std::iota(parent_.begin(), parent_.end(), 0); }
  // The representative of a's set.
  int find(int a) {
    auto& p = parent_[static_cast<std::size_t>(a)];
    return p == a ? a : p = find(p);
  }
  // Merges the sets of a and b (b's representative becomes the root).
  void unite(int a, int b) { parent_[static_cast<std::size_t>(find(a))] = find(b); }

 private:
  std::vector<int> parent_;
};

}  // namespace boxgen::support
