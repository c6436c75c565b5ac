// Quasi-interpolation prefilters and the approximation order, checked exactly against values
// from the literature and the paper's Table 1, and independently of the series code through the
// moment conditions of docs/design.md §8.
#include "generator/prefilter.h"

#include <cln/rational_io.h>
#include <gtest/gtest.h>

#include <map>
#include <string>

#include "generator/approximation_order.h"
#include "generator/error.h"
#include "generator/symmetry.h"

namespace boxgen::generator {
namespace {

// The presets, written out here so these tests do not depend on the SPEC parser.
BoxSplineSpec m7() {
  return {"m7",
          "",
          {{1, 1, 1}, {1, -1, -1}, {-1, 1, -1}, {-1, -1, 1}, {2, 0, 0}, {0, 2, 0}, {0, 0, 2}},
          Lattice::bcc()};
}
BoxSplineSpec m8() {
  return {"m8",
          "",
          {{1, 1, 1},
           {1, -1, -1},
           {-1, 1, -1},
           {-1, -1, 1},
           {1, 1, 1},
           {1, -1, -1},
           {-1, 1, -1},
           {-1, -1, 1}},
          Lattice::bcc()};
}
BoxSplineSpec m12() {
  IntColumns xi;
  for (int sign : {1, 1, -1, -1})
    for (const IntVec& e : {IntVec{2, 0, 0}, IntVec{0, 2, 0}, IntVec{0, 0, 2}})
      xi.push_back({sign * e[0], sign * e[1], sign * e[2]});
  return {"m12", "", xi, Lattice::bcc()};
}
BoxSplineSpec cart7() {
  return {"cart7",
          "",
          {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}, {1, 1, 1}, {1, 1, -1}, {1, -1, 1}, {-1, 1, 1}},
          Lattice::cartesian(3)};
}
BoxSplineSpec fcc6() {
  return {"fcc6",
          "",
          {{1, 1, 0}, {1, -1, 0}, {1, 0, 1}, {1, 0, -1}, {0, 1, 1}, {0, 1, -1}},
          Lattice::fcc()};
}
BoxSplineSpec tricubic() {
  IntColumns xi;
  for (int k = 0; k < 4; ++k)
    for (const IntVec& e : {IntVec{1, 0, 0}, IntVec{0, 1, 0}, IntVec{0, 0, 1}}) xi.push_back(e);
  return {"tricubic", "", xi, Lattice::cartesian(3)};
}
BoxSplineSpec hex3() { return {"hex3", "", {{1, 0}, {0, 1}, {1, 1}}, Lattice::cartesian(2)}; }
BoxSplineSpec zp() { return {"zp", "", {{1, 0}, {0, 1}, {1, 1}, {-1, 1}}, Lattice::cartesian(2)}; }

std::vector<BoxSplineSpec> all_presets() {
  return {m7(), m8(), m12(), cart7(), fcc6(), tricubic(), hex3(), zp()};
}

Rational r(long long p, long long q = 1) { return Rational(p) / Rational(q); }

std::string point_string(const IntVec& p) {
  std::string s;
  for (auto x : p) s += std::to_string(x) + " ";
  return s;
}

int shell_of(const IntVec& p) {  // BCC: S1 has squared norm 3, S2 squared norm 4
  const auto norm = dot(p, p);
  return norm == 0 ? 0 : norm == 3 ? 1 : norm == 4 ? 2 : -1;
}

// Checks that q has the shells' points, the origin weight and one weight on every other point.
void expect_origin_and_common(const Prefilter& q, size_t points, const Rational& origin,
                              const Rational& neighbour) {
  ASSERT_EQ(q.weights.size(), points);
  EXPECT_EQ(q.parametrisation, "common");
  EXPECT_EQ(q.note, "");
  for (const auto& w : q.weights) {
    const bool at_origin = dot(w.offset, w.offset) == 0;
    EXPECT_EQ(w.weight, at_origin ? origin : neighbour) << to_string(w.weight);
  }
}

// ---- approximation order ------------------------------------------------------------------------

TEST(ApproximationOrder, PresetsMatchTheLiterature) {
  // Expected values, each from the literature and a hand count of the most columns on one
  // plane/line: m7, m8, m12: Table 1 of the paper (order 4 for all three). cart7: 7 columns; the
  // plane x = y holds e3, (1,1,1), (1,1,-1) and no plane holds 4 -> 7 - 3 = 4. fcc6: Kim, Entezari,
  // Peters 2008 (paper ref [15]): order 3; the plane x + y + z = 0 holds
  //   (1,-1,0), (1,0,-1), (0,1,-1) -> 6 - 3 = 3.
  // tricubic: the tensor-product cubic B-spline has order 4 (de Boor); a coordinate plane holds 8
  // of 12. hex3: the Courant element (piecewise linear) has order 2; each line holds one of 3
  // columns. zp: the Zwart-Powell element (C^1 quadratic) has order 3; each line holds one of 4
  // columns.
  const std::map<std::string, int> expected{{"m7", 4},   {"m8", 4},       {"m12", 4},  {"cart7", 4},
                                            {"fcc6", 3}, {"tricubic", 4}, {"hex3", 2}, {"zp", 3}};
  for (const auto& spec : all_presets())
    EXPECT_EQ(approximation_order(spec.directions, spec.dimension()), expected.at(spec.name))
        << spec.name;
}

TEST(ApproximationOrder, EdgeCasesCountedByHand) {
  EXPECT_EQ(approximation_order({{1, 0, 0}, {0, 1, 0}, {0, 0, 1}}, 3), 1);  // a box: order 1
  EXPECT_EQ(approximation_order({{1, 0}, {1, 0}, {0, 1}}, 2), 1);           // drop (0,1)
  EXPECT_EQ(approximation_order({{1, 0}, {2, 0}, {-3, 0}, {0, 1}, {0, 5}}, 2),
            2);  // parallel columns share a line
  EXPECT_EQ(approximation_order({{1, 0, 0}, {0, 1, 0}, {1, 1, 0}}, 3), 0);  // no span at all
  EXPECT_EQ(approximation_order({{1, 0, 0}, {0, 0, 0}, {0, 1, 0}, {0, 0, 1}}, 3),
            1);  // a zero column lies on every plane
}

// ---- the paper's Table 1 ------------------------------------------------------------------------

TEST(Prefilter, PaperTable1ForM7AndM8) {
  for (const auto& spec : {m7(), m8()}) {
    SCOPED_TRACE(spec.name);
    const Prefilter first = derive_prefilter(spec, {0, 1});  // Q^I: 5/3 - 1/12 sum_S1
    EXPECT_EQ(first.order, 4);
    expect_origin_and_common(first, 9, r(5, 3), r(-1, 12));
    const Prefilter second = derive_prefilter(spec, {0, 1, 2});  // Q^II: 19/12 - 1/24 sum_(S1 u S2)
    expect_origin_and_common(second, 15, r(19, 12), r(-1, 24));
    for (const auto& w : second.weights) EXPECT_GE(shell_of(w.offset), 0);
  }
}

TEST(Prefilter, PaperTable1ForM12) {
  const Prefilter first = derive_prefilter(m12(), {0, 1});  // 7/3 - 1/6 sum_S1
  EXPECT_EQ(first.order, 4);
  expect_origin_and_common(first, 9, r(7, 3), r(-1, 6));
  const Prefilter second = derive_prefilter(m12(), {0, 1, 2});  // 13/6 - 1/12 sum_(S1 u S2)
  expect_origin_and_common(second, 15, r(13, 6), r(-1, 12));
}

TEST(Prefilter, WeightsAreOrderedByShellThenOffset) {
  const Prefilter q = derive_prefilter(m7(), {2, 0, 1});
  EXPECT_EQ(q.shells, (std::vector<int>{0, 1, 2}));
  for (size_t i = 1; i < q.weights.size(); ++i) {
    const auto &a = q.weights[i - 1].offset, &b = q.weights[i].offset;
    const int sa = shell_of(a), sb = shell_of(b);
    EXPECT_TRUE(sa < sb || (sa == sb && a < b)) << i;
  }
}

// ---- independent checks: moments and symmetry --------------------------------------------------

// For symmetric q, hat(q)(w) = sum_j q_j - w^T (sum_j q_j j j^T) w / 2 + O(|w|^4), and
// 1/hat(M^c)(w) = prod 1/sinc(xi.w/2) = 1 + sum (xi.w)^2/24 + O(|w|^4) = 1 + w^T Sigma w / 2 + ...
// with Sigma = sum_xi xi xi^T / 12. For order <= 4 the conditions are exactly: sum q = 1 and, from
// order 3 on, sum_j q_j j j^T = -Sigma. Computed here from the weights alone.
void expect_moment_conditions(const BoxSplineSpec& spec, const Prefilter& q) {
  const int n = spec.dimension();
  ASSERT_LE(q.order, 4) << "these moments decide only orders up to 4";
  Rational total = 0;
  std::vector<RatVec> second(n, RatVec(n, Rational(0))), sigma(n, RatVec(n, Rational(0)));
  for (const auto& w : q.weights) {
    total = total + w.weight;
    for (int a = 0; a < n; ++a)
      for (int b = 0; b < n; ++b)
        second[a][b] = second[a][b] + w.weight * w.offset[a] * w.offset[b];
  }
  for (const auto& xi : spec.directions)
    for (int a = 0; a < n; ++a)
      for (int b = 0; b < n; ++b) sigma[a][b] = sigma[a][b] + r(xi[a] * xi[b], 12);
  EXPECT_EQ(total, 1);
  if (q.order < 3) return;
  for (int a = 0; a < n; ++a)
    for (int b = 0; b < n; ++b) EXPECT_EQ(second[a][b], -sigma[a][b]) << a << b;
}

void expect_symmetric(const BoxSplineSpec& spec, const Prefilter& q) {
  std::map<IntVec, Rational> weight;
  for (const auto& w : q.weights) weight[w.offset] = w.weight;
  for (const auto& g : symmetry_group(spec))
    for (const auto& w : q.weights) {
      auto it = weight.find(g.apply(w.offset));
      ASSERT_NE(it, weight.end());
      EXPECT_EQ(it->second, w.weight);
    }
}

TEST(Prefilter, MomentConditionsAndSymmetryHoldForEveryPreset) {
  for (const auto& spec : all_presets())
    for (const std::vector<int>& shells : {std::vector<int>{0, 1}, {0, 1, 2}, {0, 1, 2, 3}}) {
      SCOPED_TRACE(spec.name + " shells " + std::to_string(shells.size()));
      const Prefilter q = derive_prefilter(spec, shells);
      EXPECT_EQ(q.order, approximation_order(spec.directions, spec.dimension()));
      expect_moment_conditions(spec, q);
      expect_symmetric(spec, q);
    }
}

TEST(Prefilter, MomentSigmaOfThePaper) {
  // docs/design.md §8: M7 and M8 have Sigma = (2/3) I, M12 (4/3) I; so the second moments of q are
  // -(2/3) I and -(4/3) I. A direct check of the Sigma used above for the paper's splines.
  for (const auto& [spec, diagonal] :
       {std::pair{m7(), r(-2, 3)}, {m8(), r(-2, 3)}, {m12(), r(-4, 3)}}) {
    const Prefilter q = derive_prefilter(spec, {0, 1, 2});
    Rational xx = 0, xy = 0;
    for (const auto& w : q.weights) {
      xx = xx + w.weight * w.offset[0] * w.offset[0];
      xy = xy + w.weight * w.offset[0] * w.offset[1];
    }
    EXPECT_EQ(xx, diagonal) << spec.name;
    EXPECT_EQ(xy, 0) << spec.name;
  }
}

// ---- beyond the common weight -------------------------------------------------------------------

TEST(Prefilter, OrderSixNeedsOneWeightPerShell) {
  // Tensor-product quintic B-spline in 2-D: [e1 x6, e2 x6] on Z^2, order 6. With s = w/2,
  // 1/sinc(s)^6 = 1 + s^2 + (8/15) s^4 + ..., so 1/hat(M^c) = 1 + (w1^2+w2^2)/4 + (w1^4+w2^4)/30
  // + w1^2 w2^2/16 + O(|w|^6). Weights q0, q1 on (+-1,0),(0,+-1), q2 on (+-1,+-1), q3 on
  // (+-2,0),(0,+-2); matching 1, w1^2, w1^4, w1^2 w2^2 (by hand):
  //   q0 + 4q1 + 4q2 + 4q3 = 1, 2q1 + 4q2 + 8q3 = -1/2, 2q1 + 4q2 + 32q3 = 4/5, 4q2 = 1/4
  //   -> q3 = 13/240, q2 = 1/16, q1 = -71/120, q0 = 29/10.
  // One common neighbour weight cannot do this (14c = -1/2 and 38c = 4/5 contradict).
  IntColumns xi;
  for (int k = 0; k < 6; ++k) xi.push_back({1, 0});
  for (int k = 0; k < 6; ++k) xi.push_back({0, 1});
  const BoxSplineSpec spec{"tp6", "", xi, Lattice::cartesian(2)};
  const Prefilter q = derive_prefilter(spec, {0, 1, 2, 3});
  EXPECT_EQ(q.order, 6);
  EXPECT_EQ(q.parametrisation, "per_shell");
  EXPECT_EQ(q.note, "");
  const std::map<std::int64_t, Rational> by_norm{
      {0, r(29, 10)}, {1, r(-71, 120)}, {2, r(1, 16)}, {4, r(13, 240)}};
  ASSERT_EQ(q.weights.size(), 13u);
  for (const auto& w : q.weights) EXPECT_EQ(w.weight, by_norm.at(dot(w.offset, w.offset)));
  // Independent cross-check: on the axis w2 = 0 the condition is the 1-D one for the quintic
  // B-spline, whose quasi-interpolant on -2..2 is (13/240, -7/15, 73/40, -7/15, 13/240); the sums
  // of q over the columns x = -2..2 must be exactly that.
  std::map<std::int64_t, Rational> projected;
  for (const auto& w : q.weights) projected[w.offset[0]] = projected[w.offset[0]] + w.weight;
  EXPECT_EQ(projected[0], r(73, 40));
  EXPECT_EQ(projected[1], r(-7, 15));
  EXPECT_EQ(projected[-1], r(-7, 15));
  EXPECT_EQ(projected[2], r(13, 240));
  EXPECT_EQ(projected[-2], r(13, 240));
}

TEST(Prefilter, AnisotropicSplineNeedsOneWeightPerOrbit) {
  // [e1 e1 e2 e2 d d], d = (1,1), on Z^2: order 4, Sigma = [[1/3,1/6],[1/6,1/3]]. Its symmetry
  // group
  // {+-I, +-swap} splits shell 2 into {(1,1),(-1,-1)} and {(1,-1),(-1,1)}. Equal weights on a shell
  // give sum q j1 j2 = 0 != -1/6, so only per-orbit weights work; they leave one free parameter.
  // With the outermost one (the orbit of (-1,1)) zero, by hand: q(1,1) = -1/12, shell 1 -1/12,
  // origin 3/2.
  const BoxSplineSpec spec{
      "aniso", "", {{1, 0}, {1, 0}, {0, 1}, {0, 1}, {1, 1}, {1, 1}}, Lattice::cartesian(2)};
  const Prefilter q = derive_prefilter(spec, {0, 1, 2});
  EXPECT_EQ(q.order, 4);
  EXPECT_EQ(q.parametrisation, "per_orbit");
  EXPECT_NE(q.note.find("shell 2 orbit of (-1,1)"), std::string::npos) << q.note;
  const std::map<IntVec, Rational> expected{
      {{0, 0}, r(3, 2)},     {{1, 0}, r(-1, 12)},  {{-1, 0}, r(-1, 12)},
      {{0, 1}, r(-1, 12)},   {{0, -1}, r(-1, 12)}, {{1, 1}, r(-1, 12)},
      {{-1, -1}, r(-1, 12)}, {{1, -1}, 0},         {{-1, 1}, 0}};
  ASSERT_EQ(q.weights.size(), expected.size());
  for (const auto& w : q.weights)
    EXPECT_EQ(w.weight, expected.at(w.offset)) << point_string(w.offset);
  expect_moment_conditions(spec, q);
  expect_symmetric(spec, q);
}

TEST(Prefilter, NonUniqueWeightsAreSetToZeroAndNoted) {
  // hex3 has order 2: only sum q = 1 is required, so on shells 0,1 the neighbour weight is free.
  const Prefilter q = derive_prefilter(hex3(), {0, 1});
  EXPECT_EQ(q.order, 2);
  EXPECT_NE(q.note, "");
  for (const auto& w : q.weights) EXPECT_EQ(w.weight, dot(w.offset, w.offset) == 0 ? 1 : 0);
  // On the origin alone the answer is unique: q = delta.
  const Prefilter delta = derive_prefilter(hex3(), {0});
  ASSERT_EQ(delta.weights.size(), 1u);
  EXPECT_EQ(delta.weights[0].weight, 1);
  EXPECT_EQ(delta.note, "");
}

// ---- errors -------------------------------------------------------------------------------------

TEST(Prefilter, ImpossibleRequestIsAnInputError) {
  try {
    derive_prefilter(m7(), {0});
    FAIL() << "shells {0} cannot give order 4";
  } catch (const InputError& e) {
    const std::string message = e.what();
    EXPECT_EQ(message.find('\n'), std::string::npos);
    EXPECT_NE(message.find("approximation order 4"), std::string::npos) << message;
    EXPECT_NE(message.find("only order 2"), std::string::npos) << message;
    EXPECT_NE(message.find("--shells 0,1 reaches it"), std::string::npos) << message;
  }
  // Order 6 with only the first shell around the origin: too few conditions can be met.
  IntColumns xi;
  for (int k = 0; k < 6; ++k) xi.push_back({1, 0});
  for (int k = 0; k < 6; ++k) xi.push_back({0, 1});
  EXPECT_THROW(derive_prefilter({"tp6", "", xi, Lattice::cartesian(2)}, {0, 1}), InputError);
}

TEST(Prefilter, InvalidShellSetsAreInputErrors) {
  EXPECT_THROW(derive_prefilter(m7(), {}), InputError);
  EXPECT_THROW(derive_prefilter(m7(), {1}), InputError);
  EXPECT_THROW(derive_prefilter(m7(), {0, 1, 1}), InputError);
  EXPECT_THROW(derive_prefilter(m7(), {0, 9}), InputError);
  EXPECT_THROW(derive_prefilter(m7(), {0, -1}), InputError);
}

TEST(ParseShells, AcceptsListsWithTheOrigin) {
  EXPECT_EQ(parse_shells("0,1,2"), (std::vector<int>{0, 1, 2}));
  EXPECT_EQ(parse_shells(" 2 , 0 "), (std::vector<int>{0, 2}));
  EXPECT_EQ(parse_shells("0"), (std::vector<int>{0}));
  EXPECT_EQ(parse_shells("0,8"), (std::vector<int>{0, 8}));
}

TEST(ParseShells, RejectsMalformedLists) {
  for (const char* bad : {"", " ", "1", "0,0", "0,9", "0,10", "0,a", "0,,1", "0,1,", "-1", "0;1",
                          "0,1.5", "0,99999999999999999999"})
    EXPECT_THROW(parse_shells(bad), InputError) << "'" << bad << "'";
}

}  // namespace
}  // namespace boxgen::generator
