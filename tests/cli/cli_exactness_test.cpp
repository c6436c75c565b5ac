// Exact values through the CLI, checked against values derived by hand (hex3, tricubic) or
// against properties every box spline must have (partition of unity, symmetry), and a cross-check
// between two commands (bbform's vertex coefficients against eval).
#include <algorithm>
#include <array>
#include <numeric>

#include <cln/integer.h>

#include "cli_support.h"

namespace boxgen::test {
namespace {

using nlohmann::json;

// Runs `eval SPEC --json` at the given points (exact text) and returns the exact values in order.
std::vector<Q> eval_exact(const std::string& spec, const std::vector<std::string>& points,
                          const std::vector<std::string>& extra = {}) {
  std::vector<std::string> args{"eval", spec, "--json"};
  args.insert(args.end(), extra.begin(), extra.end());
  for (const auto& p : points) {
    args.push_back("--at");
    args.push_back(p);
  }
  const json e = boxgen_json(args);
  std::vector<Q> out;
  if (!e.is_array() || e.size() != points.size()) {
    ADD_FAILURE() << "expected " << points.size() << " results, got " << e.dump().substr(0, 500);
    return out;
  }
  for (const auto& item : e) out.push_back(exact(item["value"]));
  return out;
}

std::string point_text(const std::vector<Q>& x) {
  std::string s;
  for (const auto& c : x) s += (s.empty() ? "" : " ") + str(c);
  return s;
}

// The three-direction box spline hex3, Xi = [(1,0) (0,1) (1,1)] on Z^2 (|det G| = 1, so the filter
// M is M^c). Derivation: the support is the zonotope with vertices (0,0),(1,0),(2,1),(2,2),(1,2),
// (0,1), centred at c = (1,1); M_Xi is piecewise linear (degree 3 - 2 = 1) on the mesh cut by the
// lines x, y, x - y in Z, continuous (C^0), vanishes on the boundary of the support and, since the
// shifts sum to 1 and only the centre shift is nonzero at the lattice point c, M^c(0) = 1. So the
// centred M is the Courant hat: on the triangle 0 <= y <= x <= 1 (vertices 0, (1,0), (1,1)) linear
// interpolation of the values 1, 0, 0 gives 1 - x; on 0 <= x <= y <= 1 it is 1 - y; on
// x <= 0 <= y, y - x <= 1 (vertices 0, (0,1), (-1,0)) it is 1 - (y - x); M(-x) = M(x) gives the
// other three. Together:
//     M(x, y) = max(0, 1 - max(|x|, |y|, |x - y|)).
Q hat(const Q& x, const Q& y) {
  const Q m = std::max({cln::abs(x), cln::abs(y), cln::abs(x - y)});
  return std::max(Q(0), 1 - m);
}

TEST(CliExactness, Hex3IsTheCourantHatFunction) {
  // Points in all six triangles, on knot lines, at the boundary and outside the support. The values
  // in the comments are worked out from the formula above.
  const std::vector<std::array<const char*, 2>> points{
      {"0", "0"},          // 1
      {"1/3", "1/3"},      // max(1/3, 1/3, 0) = 1/3: 2/3
      {"1/2", "0"},        // 1/2
      {"2/3", "1/3"},      // max(2/3, 1/3, 1/3): 1/3
      {"1/4", "1/2"},      // max(1/4, 1/2, 1/4): 1/2
      {"-1/3", "1/3"},     // |x - y| = 2/3: 1/3
      {"1/4", "-1/4"},     // |x - y| = 1/2: 1/2 (the anti-diagonal is not a mesh direction)
      {"1/2", "1/2"},      // 1/2 (along the mesh diagonal)
      {"1/2", "-1/2"},     // |x - y| = 1: 0 (on the support's edge)
      {"-1/10", "-3/10"},  // max(1/10, 3/10, 1/5): 7/10
      {"3/7", "5/7"},      // 2/7
      {"-5/7", "-3/7"},    // 2/7 (the point above reflected through 0)
      {"1", "1"},          // lattice neighbour: 0
      {"2", "0"},          // outside: 0
      {"-3/2", "1/5"},     // outside: 0
  };
  std::vector<std::string> texts;
  for (const auto& p : points) texts.push_back(std::string(p[0]) + " " + p[1]);
  const std::vector<Q> got = eval_exact("hex3", texts);
  ASSERT_EQ(got.size(), points.size());
  const std::vector<const char*> by_hand{"1", "2/3",  "1/2", "1/3", "1/2", "1/3", "1/2", "1/2",
                                         "0", "7/10", "2/7", "2/7", "0",   "0",   "0"};
  for (size_t i = 0; i < points.size(); ++i) {
    SCOPED_TRACE(texts[i]);
    EXPECT_EQ(got[i], hat(Q(points[i][0]), Q(points[i][1])));
    EXPECT_EQ(got[i], Q(by_hand[i]));
  }
}

TEST(CliExactness, Hex3DecimalPointsAreExact) {
  // -0.1 and -0.3 are read as -1/10 and -3/10 exactly (not as doubles): 7/10, not
  // 0.7000000000000001.
  EXPECT_EQ(eval_exact("hex3", {"-0.1 -0.3"}), std::vector<Q>{Q("7/10")});
}

TEST(CliExactness, Hex3DerivativesAreTheSlopesOfTheHat) {
  // Inside each triangle the hat is 1 - x, 1 - y or 1 - (y - x) (see above), so the gradient is
  // (-1, 0) on 0 < y < x < 1, (0, -1) on 0 < x < y < 1 and (1, -1) on x < 0 < y, y - x < 1;
  // second derivatives vanish.
  EXPECT_EQ(eval_exact("hex3", {"1/3 1/6", "1/6 1/3", "-1/4 1/4"}, {"--derivative", "1 0"}),
            (std::vector<Q>{-1, 0, 1}));
  EXPECT_EQ(eval_exact("hex3", {"1/3 1/6", "1/6 1/3", "-1/4 1/4"}, {"--derivative", "0 1"}),
            (std::vector<Q>{0, -1, -1}));
  EXPECT_EQ(eval_exact("hex3", {"1/3 1/6", "-1/4 1/4"}, {"--derivative", "2 0"}),
            (std::vector<Q>{0, 0}));
}

TEST(CliExactness, Hex3DerivativeIsExactWhereItIsContinuousAcrossAKnotLine) {
  // On the knot line y = 0 with 0 < x < 1 the hat is 1 - x above and 1 - (x - y) below (below,
  // max(|x|, |y|, |x - y|) = x - y): d/dx = -1 on both sides, so it exists and is -1. (d/dy is 0
  // above and 1 below: there the CLI must refuse, as in cli_bad_input_test.cpp DerivativeAtAKink.)
  EXPECT_EQ(eval_exact("hex3", {"1/3 0"}, {"--derivative", "1 0"}), std::vector<Q>{Q(-1)});
}

TEST(CliExactness, Hex3OnTheLatticeTwiceAsCoarseIsTheStretchedHat) {
  // Xi = 2 [(1,0) (0,1) (1,1)] on G = 2 I: M_{2 Xi}(x) = M_Xi(x / 2) / 4 (substitute x = 2 y in the
  // defining integral), and the filter M = |det G| M^c = 4 M^c is the hat stretched by 2:
  // M(x) = hat(x / 2). So M(0) = 1, M(2/3, 2/3) = hat(1/3, 1/3) = 2/3, M(1, 0) = hat(1/2, 0) = 1/2,
  // M(1, -1) = hat(1/2, -1/2) = 0.
  EXPECT_EQ(
      eval_exact("2,0; 0,2; 2,2", {"0 0", "2/3 2/3", "1 0", "1 -1"}, {"--lattice", "2,0; 0,2"}),
      (std::vector<Q>{1, Q("2/3"), Q("1/2"), 0}));
}

TEST(CliExactness, TricubicIsTheProductOfCubicBSplines) {
  // [I I I I] is the tensor product of three centred cubic B-splines (four unit boxes convolved),
  // B(t) = 2/3 - t^2 + |t|^3/2 for |t| <= 1, (2 - |t|)^3/6 for 1 <= |t| <= 2, 0 beyond:
  // B(0) = 2/3, B(1/2) = 2/3 - 1/4 + 1/16 = 23/48, B(1) = 1/6, B(3/2) = 1/48, B(2) = 0.
  EXPECT_EQ(eval_exact("tricubic", {"0 0 0", "1/2 0 1", "3/2 -1/2 1", "2 0 0", "1 1 1"}),
            (std::vector<Q>{Q("8/27"),                          // (2/3)^3
                            Q("23/432"),                        // 23/48 * 2/3 * 1/6
                            Q("1/48") * Q("23/48") * Q("1/6"),  // 23/13824
                            0, Q("1/216")}));
}

// BCC points (all coordinates even or all odd) j with x - j inside the box |.|_inf <= 3 that
// contains M7's centred support (half the sum of |xi_i| per axis: (1+1+1+1+2)/2 = 3).
std::vector<std::vector<long>> bcc_points_near(const std::array<Q, 3>& x) {
  std::vector<std::vector<long>> out;
  auto lo = [&](int i) { return cln::cl_I_to_long(cln::floor1(x[i])) - 3; };
  for (long a = lo(0); a <= lo(0) + 7; ++a)
    for (long b = lo(1); b <= lo(1) + 7; ++b)
      for (long c = lo(2); c <= lo(2) + 7; ++c)
        if ((a - b) % 2 == 0 && (a - c) % 2 == 0) out.push_back({a, b, c});
  return out;
}

TEST(CliExactness, M7ShiftsOverBccSumToOne) {
  // M = |det G| M^c: the shifts of M^c over a lattice containing Xi sum to 1/|det G|, so
  // sum_j M(x - j) = 1 for every x (partition of unity, exactly).
  for (const std::array<Q, 3>& x : {std::array<Q, 3>{Q("1/3"), Q("1/7"), Q("-2/5")},
                                    std::array<Q, 3>{Q("1/2"), Q("1/2"), Q("0")}}) {
    std::vector<std::string> points;
    for (const auto& j : bcc_points_near(x))
      points.push_back(point_text({x[0] - j[0], x[1] - j[1], x[2] - j[2]}));
    const std::vector<Q> values = eval_exact("m7", points);
    ASSERT_EQ(values.size(), points.size());
    const Q sum = std::accumulate(values.begin(), values.end(), Q(0));
    EXPECT_EQ(sum, 1) << "at x = " << point_text({x[0], x[1], x[2]});
  }
}

TEST(CliExactness, M7HasTheSymmetryOfTheCube) {
  // Xi_7 is invariant (up to sign) under every permutation and sign change of the coordinates,
  // so M7 is: all 48 images of a generic point give the same exact value.
  const std::array<Q, 3> x{Q("1/5"), Q("-2/7"), Q("3/4")};
  std::vector<std::string> points;
  std::array<int, 3> perm{0, 1, 2};
  do {
    for (int signs = 0; signs < 8; ++signs) {
      std::vector<Q> y;
      for (int i = 0; i < 3; ++i) y.push_back(((signs >> i) & 1) ? -x[perm[i]] : x[perm[i]]);
      points.push_back(point_text(y));
    }
  } while (std::next_permutation(perm.begin(), perm.end()));
  ASSERT_EQ(points.size(), 48u);
  const std::vector<Q> values = eval_exact("m7", points);
  ASSERT_EQ(values.size(), 48u);
  EXPECT_GT(values[0], 0);
  for (size_t i = 1; i < values.size(); ++i) EXPECT_EQ(values[i], values[0]) << points[i];
}

TEST(CliExactness, M7VertexCoefficientsOfBbformAreValuesOfEval) {
  // A spline s(x) = sum_j V(j) M(x - j) at a vertex v of the reference tetrahedron equals its BB-
  // coefficient c_{d e_i}. With V the k-th unit sample, the weight of V_k in that coefficient is
  // therefore M(v - j_k): bbform's corner weights must equal eval's values, exactly.
  const json b = boxgen_json({"bbform", "m7", "--json"});
  ASSERT_TRUE(b.contains("regions") && !b["regions"].empty()) << b.dump().substr(0, 500);
  const json& r = b["regions"][0];
  const json& simplex = r["simplices"][0];
  const auto stencil = r["stencil"].get<std::vector<std::vector<long>>>();
  const int degree = b["degree"].get<int>();
  const json& vertices = simplex["vertices"];
  ASSERT_EQ(vertices.size(), 4u);
  std::vector<std::string> points;
  for (const auto& v : vertices)
    for (const auto& j : stencil) {
      std::vector<Q> d;
      for (int i = 0; i < 3; ++i) d.push_back(exact(v[i]) - j[i]);
      points.push_back(point_text(d));
    }
  const std::vector<Q> values = eval_exact("m7", points);
  ASSERT_EQ(values.size(), points.size());
  for (size_t i = 0; i < 4; ++i) {
    std::vector<int> corner(4, 0);
    corner[i] = degree;
    const auto c =
        std::find_if(simplex["coefficients"].begin(), simplex["coefficients"].end(),
                     [&](const json& x) { return x["index"].get<std::vector<int>>() == corner; });
    ASSERT_NE(c, simplex["coefficients"].end()) << "no coefficient for vertex " << i;
    std::vector<Q> weights(stencil.size(), 0);
    for (const auto& t : (*c)["terms"]) weights.at(t["stencil"].get<size_t>()) = exact(t["weight"]);
    for (size_t k = 0; k < stencil.size(); ++k)
      EXPECT_EQ(weights[k], values[i * stencil.size() + k])
          << "vertex " << i << ", stencil point " << k;
  }
}

}  // namespace
}  // namespace boxgen::test
