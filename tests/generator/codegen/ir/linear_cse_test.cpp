// Shared partial sums (generator/linear_cse): they reproduce every linear combination of M7's
// reference polynomial exactly and save operations.
#include "generator/codegen/ir/linear_cse.h"

#include <gtest/gtest.h>

#include <map>

#include "generator/derivation.h"
#include "generator/spec.h"

namespace boxgen::expr {
namespace {

using generator::Derivation;
using generator::derive;
using generator::monomial_count;
using generator::parse_spec;
using generator::ReferenceRegion;

// Expands a row over inputs and temporaries back to the original inputs.
std::map<int, Rational> expand(const LinearRow& row, const SharedRows& s, int inputs) {
  std::map<int, Rational> out;
  std::vector<std::pair<int, Rational>> work(row.begin(), row.end());
  while (!work.empty()) {
    const auto [input, w] = work.back();
    work.pop_back();
    if (input < inputs) {
      out[input] = out[input] + w;
      continue;
    }
    const SharedSum& t = s.temporaries[input - inputs];
    work.emplace_back(t.a, w);
    work.emplace_back(t.b, w * t.r);
  }
  for (auto it = out.begin(); it != out.end();)
    it = cln::zerop(it->second) ? out.erase(it) : std::next(it);
  return out;
}

// The monomial coefficients of M7's reference polynomial, as rows over its 30 stencil values.
std::vector<LinearRow> m7_rows(int& inputs) {
  const Derivation a = derive(parse_spec("m7"));
  const ReferenceRegion& ref = a.structure.references.at(0);
  inputs = static_cast<int>(ref.basis.size());
  std::vector<LinearRow> rows;
  for (std::size_t m = 0; m < monomial_count(3, a.properties.degree); ++m) {
    LinearRow row;
    for (int k = 0; k < inputs; ++k) {
      const auto& c = ref.basis[k].coefficients();
      if (m < c.size() && !cln::zerop(c[m])) row.emplace_back(k, c[m]);
    }
    if (!row.empty()) rows.push_back(row);
  }
  return rows;
}

TEST(LinearCse, SharedPartialSumsReproduceEveryRowExactlyWithFewerTerms) {
  int inputs = 0;
  const auto rows = m7_rows(inputs);
  const SharedRows s = share_partial_sums(rows, inputs);
  ASSERT_EQ(s.rows.size(), rows.size());
  EXPECT_GT(s.temporaries.size(), 10u);
  std::size_t before = 0, after = s.temporaries.size();
  for (std::size_t i = 0; i < rows.size(); ++i) {
    std::map<int, Rational> original(rows[i].begin(), rows[i].end());
    EXPECT_EQ(expand(s.rows[i], s, inputs), original) << "row " << i;
    before += rows[i].size();
    after += s.rows[i].size();
  }
  EXPECT_LT(after, before);
  // Beyond the entry limit the rows come back unchanged.
  const SharedRows none = share_partial_sums(rows, inputs, 10);
  EXPECT_TRUE(none.temporaries.empty());
}

}  // namespace
}  // namespace boxgen::expr
