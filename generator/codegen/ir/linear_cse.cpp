#include "generator/codegen/ir/linear_cse.h"

#include <algorithm>
#include <cstdint>
#include <limits>
#include <map>
#include <optional>
#include <queue>
#include <tuple>
#include <unordered_map>

namespace boxgen::expr {

using generator::to_double;

namespace {

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
  // The id of the double of w_b / w_a (equal doubles share an id), and that double.
  int ratio_id(int a, int b) {
    const std::size_t size = weights_.size();
    if (ratio_ids_.size() != size * size) {
      std::vector<int> grown(size * size, -1);
      const std::size_t old = size_;
      for (std::size_t i = 0; i < old; ++i)
        for (std::size_t j = 0; j < old; ++j) grown[i * size + j] = ratio_ids_[i * old + j];
      ratio_ids_ = std::move(grown);
      size_ = size;
    }
    int& id = ratio_ids_[static_cast<std::size_t>(a) * size + static_cast<std::size_t>(b)];
    if (id < 0) {
      const double r = to_double(weights_[b] / weights_[a]);
      const auto it = ratio_of_value_.find(r);
      if (it != ratio_of_value_.end()) {
        id = it->second;
      } else {
        id = static_cast<int>(ratios_.size());
        ratio_of_value_.emplace(r, id);
        ratios_.push_back(r);
      }
    }
    return id;
  }
  double ratio(int id) const { return ratios_[id]; }
  std::size_t ratio_count() const { return ratios_.size(); }
  const Rational& weight(int id) const { return weights_[id]; }

 private:
  struct Less {
    bool operator()(const Rational& x, const Rational& y) const { return x < y; }
  };
  std::map<Rational, int, Less> ids_;
  std::vector<Rational> weights_;
  std::vector<int> ratio_ids_;  // size_ x size_, -1 until computed
  std::size_t size_ = 0;
  std::map<double, int> ratio_of_value_;
  std::vector<double> ratios_;
};

using WorkRow = std::vector<std::pair<int, int>>;  // (input, weight id)

// A pair (a < b, ratio id) packed into one word: 20 bits each for the inputs, 24 for the ratio.
std::uint64_t pack(int a, int b, int r) {
  return (static_cast<std::uint64_t>(a) << 44) | (static_cast<std::uint64_t>(b) << 24) |
         static_cast<std::uint64_t>(r);
}

// How many rows hold each pair of inputs a < b with the same weight ratio, kept up to date as
// rows change (recounting every pair of every row after each replacement cost 90% of emitting
// tricubic). The best pair is the most frequent, among equally frequent ones the smallest
// (a, b, ratio): equal keys are the rows that could share t = x_a + r x_b. Pairs of two inputs
// only lose rows, so those in fewer than two rows at the start are never counted; pairs with a
// new temporary are counted from its creation.
class PairCounts {
 public:
  PairCounts(const std::vector<WorkRow>& work, WeightTable& table) : table_(table) {
    std::vector<std::uint64_t> keys;
    for (const auto& row : work)
      for (std::size_t i = 0; i < row.size(); ++i)
        for (std::size_t j = i + 1; j < row.size(); ++j) keys.push_back(key(row[i], row[j]));
    std::sort(keys.begin(), keys.end());
    for (std::size_t i = 0; i < keys.size();) {
      std::size_t j = i;
      while (j < keys.size() && keys[j] == keys[i]) ++j;
      if (j - i >= 2) {
        counts_[keys[i]] = static_cast<int>(j - i);
        push(keys[i], static_cast<int>(j - i));
      }
      i = j;
    }
  }

  // Counts (delta 1) or uncounts (delta -1) the pairs of entry i of `row` with the others (but
  // `skip`).
  void add_pairs_of(const WorkRow& row, std::size_t i, int delta,
                    std::size_t skip = std::numeric_limits<std::size_t>::max()) {
    for (std::size_t j = 0; j < row.size(); ++j) {
      if (j == i || j == skip) continue;
      const std::uint64_t k = key(row[i], row[j]);
      const auto it = counts_.find(k);
      if (delta < 0 && it == counts_.end()) continue;  // never in two rows
      set(k, (it == counts_.end() ? 0 : it->second) + delta);
    }
  }

  // The best pair (a, b, ratio) and its count; count 0 when no pair is left. Heap entries whose
  // count has changed since are dropped here.
  std::pair<std::tuple<int, int, double>, std::size_t> best() {
    // The counts changed since the last call enter the heap once each, at their final value.
    std::sort(changed_.begin(), changed_.end());
    changed_.erase(std::unique(changed_.begin(), changed_.end()), changed_.end());
    for (std::uint64_t k : changed_) {
      const auto it = counts_.find(k);
      if (it != counts_.end() && it->second >= 2) push(k, it->second);
    }
    changed_.clear();
    while (!heap_.empty()) {
      const Entry& e = heap_.top();
      const auto it = counts_.find(e.key);
      if (it != counts_.end() && it->second == e.count)
        return {{e.a, e.b, e.ratio}, static_cast<std::size_t>(e.count)};
      heap_.pop();
    }
    return {{0, 0, 0.0}, 0};
  }

 private:
  struct Entry {
    int count, a, b;
    double ratio;  // a ratio id is one double
    std::uint64_t key;
  };
  // The heap's order: the most frequent on top, then the smallest (a, b, ratio).
  struct Worse {
    bool operator()(const Entry& x, const Entry& y) const {
      return std::tie(x.count, y.a, y.b, y.ratio) < std::tie(y.count, x.a, x.b, x.ratio);
    }
  };

  std::uint64_t key(const std::pair<int, int>& x, const std::pair<int, int>& y) {
    const auto& [a, wa] = x.first < y.first ? x : y;
    const auto& [b, wb] = x.first < y.first ? y : x;
    return pack(a, b, table_.ratio_id(wa, wb));
  }

  void set(std::uint64_t k, int count) {
    if (count <= 0)
      counts_.erase(k);
    else
      counts_[k] = count;
    changed_.push_back(k);
  }

  void push(std::uint64_t k, int count) {
    const int a = static_cast<int>(k >> 44);
    const int b = static_cast<int>((k >> 24) & ((1u << 20) - 1));
    heap_.push({count, a, b, table_.ratio(static_cast<int>(k & ((1u << 24) - 1))), k});
  }

  WeightTable& table_;
  std::unordered_map<std::uint64_t, int> counts_;
  std::priority_queue<Entry, std::vector<Entry>, Worse> heap_;
  std::vector<std::uint64_t> changed_;  // keys whose count changed since the last best()
};

// Replaces x_a and x_b by the temporary `next` = x_a + r x_b in every row where they stand in the
// ratio r of the first row holding both (rows with another exact ratio keep theirs); returns r.
// Only the pairs with x_a, x_b or the temporary change, and `pairs` follows them.
Rational replace_pair(std::vector<WorkRow>& work, const WeightTable& table, int a, int b, int next,
                      PairCounts& pairs) {
  std::optional<Rational> r;
  for (auto& row : work) {
    auto ia = std::find_if(row.begin(), row.end(), [&](const auto& e) { return e.first == a; });
    auto ib = std::find_if(row.begin(), row.end(), [&](const auto& e) { return e.first == b; });
    if (ia == row.end() || ib == row.end()) continue;
    const Rational row_ratio = table.weight(ib->second) / table.weight(ia->second);
    if (!r) r = row_ratio;
    if (row_ratio != *r) continue;
    const int wa = ia->second;
    const auto i = static_cast<std::size_t>(ia - row.begin());
    const auto j = static_cast<std::size_t>(ib - row.begin());
    pairs.add_pairs_of(row, i, -1);
    pairs.add_pairs_of(row, j, -1, i);
    row.erase(std::max(ia, ib));
    row.erase(std::min(ia, ib));
    row.emplace_back(next, wa);
    pairs.add_pairs_of(row, row.size() - 1, 1);
  }
  return *r;  // the pair was counted in at least two rows
}

}  // namespace

SharedRows share_partial_sums(const std::vector<LinearRow>& rows, int inputs,
                              std::size_t max_entries) {
  SharedRows out{{}, rows};
  std::size_t entries = 0;
  for (const auto& row : rows) entries += row.size();
  // The packed pair keys hold inputs and temporaries (< inputs + entries) in 20 bits.
  if (entries > max_entries || static_cast<std::size_t>(inputs) + entries >= (1u << 20)) return out;
  // The rows with weights replaced by their ids in `table`.
  WeightTable table;
  std::vector<WorkRow> work;
  for (const auto& row : rows) {
    work.emplace_back();
    for (const auto& [input, w] : row) work.back().emplace_back(input, table.id(w));
  }
  PairCounts pairs(work, table);
  for (int next = inputs;; ++next) {
    const auto [best, count] = pairs.best();
    if (count < 2 || table.ratio_count() >= (1u << 24)) break;
    const int a = std::get<0>(best);
    const int b = std::get<1>(best);
    out.temporaries.push_back({a, b, replace_pair(work, table, a, b, next, pairs)});
  }
  out.rows.clear();
  for (const auto& row : work) {
    out.rows.emplace_back();
    for (const auto& [input, w] : row) out.rows.back().emplace_back(input, table.weight(w));
  }
  return out;
}

}  // namespace boxgen::expr
