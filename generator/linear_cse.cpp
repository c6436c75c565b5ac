#include "generator/linear_cse.h"

#include <algorithm>
#include <map>
#include <optional>
#include <tuple>

namespace boxgen {

SharedRows share_partial_sums(const std::vector<LinearRow>& rows, int inputs,
                              std::size_t max_entries) {
  SharedRows out{{}, rows};
  std::size_t entries = 0;
  for (const auto& row : rows) entries += row.size();
  if (entries > max_entries) return out;
  for (int next = inputs;; ++next) {
    // How many rows hold inputs a < b with weights in ratio r (keyed by the ratio's double; the
    // exact ratio is compared again when the pair is replaced).
    std::map<std::tuple<int, int, double>, int> count;
    for (const auto& row : out.rows)
      for (std::size_t i = 0; i < row.size(); ++i)
        for (std::size_t j = i + 1; j < row.size(); ++j) {
          const auto& [a, wa] = row[i].first < row[j].first ? row[i] : row[j];
          const auto& [b, wb] = row[i].first < row[j].first ? row[j] : row[i];
          ++count[{a, b, to_double(wb / wa)}];
        }
    auto best = count.end();
    for (auto it = count.begin(); it != count.end(); ++it)
      if (best == count.end() || it->second > best->second) best = it;
    if (best == count.end() || best->second < 2) break;
    const int a = std::get<0>(best->first);  // named, not bound: lambdas capture them (clang 14)
    const int b = std::get<1>(best->first);
    // The exact ratio from the first row holding the pair; rows with another exact ratio keep
    // theirs.
    std::optional<Rational> r;
    int replaced = 0;
    for (auto& row : out.rows) {
      auto ia = std::find_if(row.begin(), row.end(), [&](const auto& e) { return e.first == a; });
      auto ib = std::find_if(row.begin(), row.end(), [&](const auto& e) { return e.first == b; });
      if (ia == row.end() || ib == row.end()) continue;
      const Rational row_ratio = ib->second / ia->second;
      if (!r) r = row_ratio;
      if (row_ratio != *r) continue;
      const Rational wa = ia->second;
      row.erase(std::max(ia, ib));
      row.erase(std::min(ia, ib));
      row.emplace_back(next, wa);
      ++replaced;
    }
    if (replaced == 0) break;  // cannot happen: the first row holding the pair matches itself
    out.temporaries.push_back({a, b, *r});
  }
  return out;
}

}  // namespace boxgen
