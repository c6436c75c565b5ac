// Long check (CTest label `slow`, not in the default suite): "any integer direction matrix" in
// 3-D. Every set of three linearly independent directions with entries in {-1, 0, 1} (one of
// each +- pair), and every 7th set of four and every 53rd set of five of them, passes the full
// default analysis on the Cartesian lattice; its exact checks (two derivations agreeing, integral
// 1, symmetry, partition of unity, sharp continuity) throw on any inconsistency. Rank-deficient
// sets must be refused as bad input, never fail inside.
#include <gtest/gtest.h>

#include <fmt/format.h>

#include <array>
#include <vector>

#include "generator/derivation.h"
#include "generator/error.h"
#include "generator/spec.h"

namespace boxgen::generator {
namespace {

using Direction = std::array<int, 3>;

std::vector<Direction> unit_directions() {
  std::vector<Direction> dirs;
  for (int a = -1; a <= 1; ++a)
    for (int b = -1; b <= 1; ++b)
      for (int c = -1; c <= 1; ++c) {
        const Direction d{a, b, c};
        if (d > Direction{0, 0, 0}) dirs.push_back(d);  // lexicographically positive: one per pair
      }
  return dirs;  // 13
}

// Every k-subset of the directions, in lexicographic order, keeping every `step`-th one.
std::vector<std::vector<Direction>> subsets(const std::vector<Direction>& dirs, int k, int step) {
  std::vector<std::vector<Direction>> out;
  std::vector<int> idx(k);
  for (int i = 0; i < k; ++i) idx[i] = i;
  const int n = static_cast<int>(dirs.size());
  for (long count = 0;; ++count) {
    if (count % step == 0) {
      std::vector<Direction> s;
      for (int i : idx) s.push_back(dirs[i]);
      out.push_back(s);
    }
    int i = k - 1;
    while (i >= 0 && idx[i] == n - k + i) --i;
    if (i < 0) break;
    ++idx[i];
    for (int j = i + 1; j < k; ++j) idx[j] = idx[j - 1] + 1;
  }
  return out;
}

std::string spec_text(const std::vector<Direction>& s) {
  std::string t;
  for (const auto& d : s) t += fmt::format("{}{},{},{}", t.empty() ? "" : ";", d[0], d[1], d[2]);
  return t;
}

int determinant(const Direction& a, const Direction& b, const Direction& c) {
  return a[0] * (b[1] * c[2] - b[2] * c[1]) - a[1] * (b[0] * c[2] - b[2] * c[0]) +
         a[2] * (b[0] * c[1] - b[1] * c[0]);
}

bool spans_space(const std::vector<Direction>& s) {
  for (std::size_t i = 0; i < s.size(); ++i)
    for (std::size_t j = i + 1; j < s.size(); ++j)
      for (std::size_t k = j + 1; k < s.size(); ++k)
        if (determinant(s[i], s[j], s[k]) != 0) return true;
  return false;
}

TEST(CustomMatrices, SmallSpatialSetsPassTheExactChecks) {
  const auto dirs = unit_directions();
  ASSERT_EQ(dirs.size(), 13u);
  int analysed = 0, refused = 0;
  for (const auto& [k, step] : {std::pair{3, 1}, std::pair{4, 7}, std::pair{5, 53}}) {
    for (const auto& s : subsets(dirs, k, step)) {
      const std::string text = spec_text(s);
      try {
        const Derivation a = derive(parse_spec(text, "cartesian"));
        EXPECT_TRUE(spans_space(s)) << text << " was analysed although it does not span R^3";
        EXPECT_GT(a.pieces, 0) << text;
        ++analysed;
      } catch (const InputError& e) {
        EXPECT_FALSE(spans_space(s)) << text << ": " << e.what();
        ++refused;
      } catch (const std::exception& e) {
        ADD_FAILURE() << text << ": " << e.what();
      }
    }
  }
  RecordProperty("analysed", analysed);
  RecordProperty("refused_rank_deficient", refused);
  EXPECT_GT(analysed, 300);
}

}  // namespace
}  // namespace boxgen::generator
