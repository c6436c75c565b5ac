#include "generator/linear_cse.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <optional>
#include <tuple>
#include <unordered_map>

namespace boxgen {

namespace {

// A pair of inputs a < b whose weights stand in the ratio w_b / w_a (its double; the exact ratio
// is compared again when the pair is replaced).
struct PairKey {
  int a, b;
  double ratio;
  bool operator==(const PairKey& o) const { return a == o.a && b == o.b && ratio == o.ratio; }
  bool operator<(const PairKey& o) const {
    return std::tie(a, b, ratio) < std::tie(o.a, o.b, o.ratio);
  }
};

struct PairHash {
  std::size_t operator()(const PairKey& k) const {
    const std::size_t h = std::hash<double>()(k.ratio);
    return h ^ (static_cast<std::size_t>(k.a) * 0x9e3779b97f4a7c15ull) ^
           (static_cast<std::size_t>(k.b) * 0xc2b2ae3d27d4eb4full);
  }
};

// The distinct weights of the rows, each converted once, and the doubles of their ratios, each
// computed once: the pair search touches every pair of every row in every round.
class WeightTable {
 public:
  int id(const Rational& w) {
    const auto it = ids_.find(w);
    if (it != ids_.end()) return it->second;
    const int next = static_cast<int>(weights_.size());
    ids_.emplace(w, next);
    weights_.push_back(w);
    return next;
  }
  double ratio(int a, int b) {  // to_double(w_b / w_a)
    const std::size_t size = weights_.size();
    if (ratios_.size() != size * size) {
      std::vector<double> grown(size * size, std::nan(""));
      const std::size_t old = size == 0 ? 0 : static_cast<std::size_t>(std::sqrt(ratios_.size()));
      for (std::size_t i = 0; i < old; ++i)
        for (std::size_t j = 0; j < old; ++j) grown[i * size + j] = ratios_[i * old + j];
      ratios_ = std::move(grown);
    }
    double& r = ratios_[static_cast<std::size_t>(a) * size + static_cast<std::size_t>(b)];
    if (std::isnan(r)) r = to_double(weights_[b] / weights_[a]);
    return r;
  }
  const Rational& weight(int id) const { return weights_[id]; }

 private:
  struct Less {
    bool operator()(const Rational& x, const Rational& y) const { return x < y; }
  };
  std::map<Rational, int, Less> ids_;
  std::vector<Rational> weights_;
  std::vector<double> ratios_;
};

}  // namespace

SharedRows share_partial_sums(const std::vector<LinearRow>& rows, int inputs,
                              std::size_t max_entries) {
  SharedRows out{{}, rows};
  std::size_t entries = 0;
  for (const auto& row : rows) entries += row.size();
  if (entries > max_entries) return out;
  // The rows with weights replaced by their ids in `table` (entries: input, weight id).
  WeightTable table;
  std::vector<std::vector<std::pair<int, int>>> work;
  for (const auto& row : rows) {
    work.emplace_back();
    for (const auto& [input, w] : row) work.back().emplace_back(input, table.id(w));
  }
  std::unordered_map<PairKey, int, PairHash> count;
  for (int next = inputs;; ++next) {
    // How many rows hold inputs a < b with weights in ratio r.
    count.clear();
    for (const auto& row : work)
      for (std::size_t i = 0; i < row.size(); ++i)
        for (std::size_t j = i + 1; j < row.size(); ++j) {
          const auto& [a, wa] = row[i].first < row[j].first ? row[i] : row[j];
          const auto& [b, wb] = row[i].first < row[j].first ? row[j] : row[i];
          ++count[{a, b, table.ratio(wa, wb)}];
        }
    // The most frequent pair; among equally frequent ones the smallest key (a, b, ratio).
    const PairKey* best = nullptr;
    int best_count = 0;
    for (const auto& [key, c] : count)
      if (c > best_count || (c == best_count && key < *best)) {
        best = &key;
        best_count = c;
      }
    if (!best || best_count < 2) break;
    const int a = best->a;
    const int b = best->b;
    // The exact ratio from the first row holding the pair; rows with another exact ratio keep
    // theirs.
    std::optional<Rational> r;
    int replaced = 0;
    for (auto& row : work) {
      auto ia = std::find_if(row.begin(), row.end(), [&](const auto& e) { return e.first == a; });
      auto ib = std::find_if(row.begin(), row.end(), [&](const auto& e) { return e.first == b; });
      if (ia == row.end() || ib == row.end()) continue;
      const Rational row_ratio = table.weight(ib->second) / table.weight(ia->second);
      if (!r) r = row_ratio;
      if (row_ratio != *r) continue;
      const int wa = ia->second;
      row.erase(std::max(ia, ib));
      row.erase(std::min(ia, ib));
      row.emplace_back(next, wa);
      ++replaced;
    }
    if (replaced == 0) break;  // cannot happen: the first row holding the pair matches itself
    out.temporaries.push_back({a, b, *r});
  }
  out.rows.clear();
  for (const auto& row : work) {
    out.rows.emplace_back();
    for (const auto& [input, w] : row) out.rows.back().emplace_back(input, table.weight(w));
  }
  return out;
}

}  // namespace boxgen
