// The renderings of explicit pieces, on small pieces written out by hand: what each printer must
// say is worked out here, independently of the derivation (tests/generator/pieces_test.cpp checks
// the derived pieces of every preset).
#include "generator/piece_format.h"

#include <gtest/gtest.h>

#include "generator/error.h"
#include "generator/ginac_bridge.h"

namespace boxgen::generator {
namespace {

// A 2-D filter piece M(x, y) = 1/2 x^2 - y on the triangle x >= 0, y >= 0, x + y <= 1.
Pieces filter_piece() {
  Piece p;
  p.vertices = {{0, 0}, {0, 1}, {1, 0}};
  p.inequalities = {{{-1, 0}, 0}, {{0, -1}, 0}, {{1, 1}, 1}};
  p.interior = {Rational(1) / 3, Rational(1) / 3};
  p.orbit = 0;
  p.orbit_size = 2;
  Poly m(2, 2);
  m.set_coefficient({2, 0, 0}, Rational(1) / 2);
  m.set_coefficient({0, 1, 0}, -1);
  p.polynomials = {m};
  Pieces all;
  all.of = PiecesOf::Filter;
  all.dimension = 2;
  all.degree = 2;
  all.orbits = 1;
  all.pieces = {p};
  return all;
}

// The same region as a spline piece with two stencil points: s = v0 * x + v1 * (1 - x).
Pieces spline_piece() {
  Pieces all = filter_piece();
  all.of = PiecesOf::Spline;
  Piece& p = all.pieces[0];
  p.stencil = {{0, 0}, {1, 0}};
  p.polynomials = {Poly::affine({0, 1, 0}), Poly::affine({1, -1, 0})};
  return all;
}

TEST(PieceFormat, OptionNames) {
  EXPECT_EQ(parse_piece_format("text"), PieceFormat::Text);
  EXPECT_EQ(parse_piece_format("latex"), PieceFormat::Latex);
  EXPECT_EQ(parse_piece_format("c"), PieceFormat::C);
  EXPECT_EQ(parse_piece_format("json"), PieceFormat::Json);
  EXPECT_THROW(parse_piece_format("C"), InputError);
  EXPECT_EQ(stencil_name(12), "v12");
  EXPECT_EQ(stencil_symbols(2)[1].get_name(), "v1");
  EXPECT_EQ(stencil_symbols(2, true)[1].get_name(), "v[1]");
}

TEST(PieceFormat, JsonIsTheExactData) {
  const nlohmann::json expected = nlohmann::json::parse(R"({
    "command": "t", "of": "filter", "frame": "centred", "degree": 2, "orbits": 1,
    "pieces": [{
      "orbit": 0, "orbit_size": 2,
      "region": {"vertices": [["0", "0"], ["0", "1"], ["1", "0"]],
                 "inequalities": [{"normal": [-1, 0], "bound": "0"}, {"normal": [0, -1], "bound": "0"},
                                  {"normal": [1, 1], "bound": "1"}]},
      "polynomial": {"variables": ["x", "y"],
                     "terms": [{"exponents": [0, 1], "coefficient": "-1"},
                               {"exponents": [2, 0], "coefficient": "1/2"}]}}]})");
  EXPECT_EQ(pieces_json(filter_piece(), "t"), expected);
  const nlohmann::json spline = pieces_json(spline_piece(), "t")["pieces"][0];
  EXPECT_EQ(spline["stencil"],
            nlohmann::json::parse(
                R"([{"name": "v0", "point": [0, 0]}, {"name": "v1", "point": [1, 0]}])"));
  EXPECT_EQ(spline["polynomial"]["terms"], nlohmann::json::parse(R"([
      {"exponents": [0, 0], "coefficient": {"v1": "1"}},
      {"exponents": [1, 0], "coefficient": {"v0": "1", "v1": "-1"}}])"));
}

TEST(PieceFormat, TextUsesGinacsPrinter) {
  const std::string text = format_pieces(filter_piece(), PieceFormat::Text, "t");
  EXPECT_NE(text.find("  vertices: (0,0) (0,1) (1,0)\n"), std::string::npos) << text;
  // Normals whose first nonzero entry is negative read as >=.
  EXPECT_NE(text.find("  inequalities: x >= 0, y >= 0, x+y <= 1\n"), std::string::npos) << text;
  // Terms in the monomials' graded order on every run (GiNaC's own order changes per process).
  EXPECT_NE(text.find("  M(x,y) = -y+1/2*x^2\n"), std::string::npos) << text;
  const std::string spline = format_pieces(spline_piece(), PieceFormat::Text, "t");
  EXPECT_NE(spline.find("    v1 = V(1,0)\n"), std::string::npos) << spline;
  EXPECT_NE(spline.find("  s(x,y) = v1+(v0-v1)*x\n"), std::string::npos) << spline;
}

TEST(PieceFormat, SplineExpressionIsCollectedInTheCoordinates) {
  const Pieces pieces = spline_piece();
  const Piece& p = pieces.pieces[0];
  const auto v = stencil_symbols(2);
  const GiNaC::ex e = piece_expression(p, v);
  const GiNaC::symbol x = coordinate_symbols(2)[0];
  EXPECT_TRUE((e - (v[0] * x + v[1] * (1 - x))).expand().is_zero()) << e;
  EXPECT_TRUE((e.coeff(x, 1) - (v[0] - v[1])).expand().is_zero()) << e;
}

TEST(PieceFormat, LatexAndC) {
  const std::string latex = format_pieces(filter_piece(), PieceFormat::Latex, "t");
  EXPECT_NE(latex.find("\\frac{1}{2}"), std::string::npos) << latex;
  EXPECT_NE(latex.find("$x \\ge 0$"), std::string::npos) << latex;
  EXPECT_NE(latex.find("\\begin{dmath*}\nM(x,y) = -y+\\frac{1}{2} x^{2}\n"), std::string::npos)
      << latex;
  const std::string c = format_pieces(spline_piece(), PieceFormat::C, "t");
  EXPECT_NE(c.find("double piece_0(double x, double y, const double v[2]) {\n  return "
                   "v[1]+(v[0]-v[1])*x;\n"),
            std::string::npos)
      << c;
  EXPECT_NE(c.find("v[1] = V(1,0)"), std::string::npos) << c;
}

}  // namespace
}  // namespace boxgen::generator
