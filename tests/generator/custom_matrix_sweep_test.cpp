// "Any integer direction matrix": every 2-D set of two or three directions with entries in
// [-2, 2] (282 sets with rank 2, parallel and repeated directions included) passes the full
// default analysis, whose exact checks (two derivations agreeing, integral 1, symmetry,
// partition of unity, sharp continuity) throw on any inconsistency.
#include <gtest/gtest.h>

#include <fmt/format.h>

#include "generator/derivation.h"
#include "generator/spec.h"

namespace boxgen::generator {
namespace {

std::vector<std::string> small_planar_sets() {
  std::vector<std::array<int, 2>> dirs;  // one of each +-pair
  for (int a = -2; a <= 2; ++a)
    for (int b = -2; b <= 2; ++b)
      if (a > 0 || (a == 0 && b > 0)) dirs.push_back({a, b});
  auto text = [&](std::initializer_list<std::size_t> idx) {
    std::string s;
    for (std::size_t i : idx)
      s += fmt::format("{}{},{}", s.empty() ? "" : ";", dirs[i][0], dirs[i][1]);
    return s;
  };
  std::vector<std::string> sets;
  for (std::size_t i = 0; i < dirs.size(); ++i)
    for (std::size_t j = i + 1; j < dirs.size(); ++j) {
      if (dirs[i][0] * dirs[j][1] != dirs[i][1] * dirs[j][0]) sets.push_back(text({i, j}));
      for (std::size_t k = j + 1; k < dirs.size(); ++k) sets.push_back(text({i, j, k}));
    }
  return sets;
}

TEST(CustomMatrices, EverySmallPlanarSetPassesTheExactChecks) {
  const auto sets = small_planar_sets();
  ASSERT_EQ(sets.size(), 282u);
  for (const auto& s : sets) {
    try {
      const Derivation a = derive(parse_spec(s));
      EXPECT_GT(a.pieces, 0) << s;
    } catch (const std::exception& e) {
      ADD_FAILURE() << s << ": " << e.what();
    }
  }
}

}  // namespace
}  // namespace boxgen::generator
