#include "generator/linear_cse.h"

#include <algorithm>
#include <cstdint>
#include <map>
#include <optional>
#include <tuple>

namespace boxgen::generator {

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

// The pair of inputs a < b whose weights stand in the same ratio in the most rows (among equally
// frequent ones the smallest (a, b, ratio)), with that count. Every pair of every row goes into
// `pairs`, sorted: equal keys are the rows that could share t = x_a + r x_b.
std::pair<std::tuple<int, int, double>, std::size_t> most_frequent_pair(
    const std::vector<WorkRow>& work, WeightTable& table, std::vector<std::uint64_t>& pairs) {
  pairs.clear();
  for (const auto& row : work)
    for (std::size_t i = 0; i < row.size(); ++i)
      for (std::size_t j = i + 1; j < row.size(); ++j) {
        const auto& [a, wa] = row[i].first < row[j].first ? row[i] : row[j];
        const auto& [b, wb] = row[i].first < row[j].first ? row[j] : row[i];
        pairs.push_back(pack(a, b, table.ratio_id(wa, wb)));
      }
  std::sort(pairs.begin(), pairs.end());
  auto unpack = [&](std::uint64_t key) {
    return std::make_tuple(static_cast<int>(key >> 44),
                           static_cast<int>((key >> 24) & ((1u << 20) - 1)),
                           table.ratio(static_cast<int>(key & ((1u << 24) - 1))));
  };
  std::tuple<int, int, double> best{0, 0, 0.0};
  std::size_t best_count = 0;
  for (std::size_t i = 0; i < pairs.size();) {
    std::size_t j = i;
    while (j < pairs.size() && pairs[j] == pairs[i]) ++j;
    if (j - i > best_count || (j - i == best_count && unpack(pairs[i]) < best)) {
      best = unpack(pairs[i]);
      best_count = j - i;
    }
    i = j;
  }
  return {best, best_count};
}

// Replaces x_a and x_b by the temporary `next` = x_a + r x_b in every row where they stand in the
// ratio r of the first row holding both (rows with another exact ratio keep theirs); returns r.
Rational replace_pair(std::vector<WorkRow>& work, const WeightTable& table, int a, int b,
                      int next) {
  std::optional<Rational> r;
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
  std::vector<std::uint64_t> pairs;
  for (int next = inputs;; ++next) {
    const auto [best, count] = most_frequent_pair(work, table, pairs);
    if (count < 2 || table.ratio_count() >= (1u << 24)) break;
    const int a = std::get<0>(best);
    const int b = std::get<1>(best);
    out.temporaries.push_back({a, b, replace_pair(work, table, a, b, next)});
  }
  out.rows.clear();
  for (const auto& row : work) {
    out.rows.emplace_back();
    for (const auto& [input, w] : row) out.rows.back().emplace_back(input, table.weight(w));
  }
  return out;
}

}  // namespace boxgen::generator
