// boxgen pieces (generator/pieces.h, piece_format.h) for every preset:
//  - the text output, read back with GiNaC's parser, is exactly the derived polynomial
//    (the reference regions' basis for the spline, the piecewise form's cell polynomial for the
//    filter);
//  - the JSON pieces, evaluated exactly at generic interior points of their regions, agree with
//    the independent de Boor-Hoellig recurrence (generator/recurrence.h), and the stencil values
//    sum to one there (M >= 0, so no nonzero shift is missing from the stencil);
//  - orbits, counts and the other renderings are consistent.
#include "generator/pieces.h"

#include <gtest/gtest.h>

#include <sstream>

#include "generator/error.h"
#include "generator/ginac_bridge.h"
#include "generator/piece_format.h"
#include "generator/recurrence.h"
#include "tests/generator/derivation_fixture.h"

namespace boxgen::generator {
namespace {

using fixture::derivation_of;

// The right-hand sides of the lines "  s(x,y,z) = ..." (or M(...)) of the text output. (Plain
// string matching: std::regex recurses per character and overflows the stack on M12's lines.)
std::vector<std::string> expression_lines(const std::string& text, const std::string& lhs) {
  std::vector<std::string> out;
  std::istringstream in(text);
  std::string s;
  while (std::getline(in, s))
    for (const std::string& prefix : {"  " + lhs + "(x,y,z) = ", "  " + lhs + "(x,y) = "})
      if (s.rfind(prefix, 0) == 0) out.push_back(s.substr(prefix.size()));
  return out;
}

GiNaC::ex parse(const std::string& text, int n, const std::vector<GiNaC::symbol>& stencil) {
  GiNaC::symtab table;
  for (const auto& s : coordinate_symbols(n)) table[s.get_name()] = s;
  for (const auto& s : stencil) table[s.get_name()] = s;
  GiNaC::parser reader(table);
  reader.strict = true;  // an unknown name is an error, not a new symbol
  return reader(text);
}

int count(const std::string& text, const std::string& what) {
  int k = 0;
  for (auto at = text.find(what); at != std::string::npos; at = text.find(what, at + 1)) ++k;
  return k;
}

class PiecesOfPreset : public ::testing::TestWithParam<const char*> {};

TEST_P(PiecesOfPreset, TextReadsBackAsTheDerivedPolynomials) {
  const Derivation& a = derivation_of(GetParam());
  const int n = a.spec.dimension();

  // The spline: coefficient of v_k in s is M(x - j_k) on the reference region.
  const Pieces spline = spline_pieces(a.form, a.structure, {PieceSelection::Reference, 0});
  const auto lines = expression_lines(format_pieces(spline, PieceFormat::Text, "test"), "s");
  ASSERT_EQ(lines.size(), a.structure.references.size());
  for (std::size_t o = 0; o < lines.size(); ++o) {
    const ReferenceRegion& ref = a.structure.references[o];
    ASSERT_EQ(spline.pieces[o].stencil, ref.stencil);
    const auto v = stencil_symbols(ref.stencil.size());
    const GiNaC::ex s = parse(lines[o], n, v).expand();
    GiNaC::exmap zero;
    for (std::size_t k = 0; k < v.size(); ++k) {
      EXPECT_EQ(to_poly(s.coeff(v[k], 1), coordinate_symbols(n)), ref.basis[k])
          << "orbit " << o << ", v" << k;
      zero[v[k]] = 0;
    }
    EXPECT_TRUE(s.subs(zero).is_zero()) << "a term without a stencil value";
  }

  // The filter: every piece is the derived polynomial of the cell holding its interior point.
  const Pieces filter = filter_pieces(a.form, {PieceSelection::All, 0});
  EXPECT_EQ(static_cast<int>(filter.pieces.size()), a.pieces);  // all pieces are convex here
  const auto m_lines = expression_lines(format_pieces(filter, PieceFormat::Text, "test"), "M");
  ASSERT_EQ(m_lines.size(), filter.pieces.size());
  const RatVec c = spline_centre(a.spec);
  RatVec minus_c = c;
  for (auto& x : minus_c) x = -x;
  for (std::size_t i = 0; i < m_lines.size(); ++i) {
    RatVec u = filter.pieces[i].interior;
    for (int k = 0; k < n; ++k) u[k] = u[k] + c[k];
    const Poly derived = a.form.poly_at(u).translated(minus_c) * Rational(a.spec.lattice.det_abs());
    EXPECT_EQ(to_poly(parse(m_lines[i], n, {}), coordinate_symbols(n)), derived) << "piece " << i;
  }
}

// A generic point strictly inside the convex hull of `vertices`: positive weights with large
// prime denominators, moved on until the uncentred point is off every knot plane.
RatVec generic_interior_point(const std::vector<RatVec>& vertices, const BoxSplineSpec& spec,
                              int seed) {
  const RatVec c = spline_centre(spec);
  for (int attempt = 0; attempt < 50; ++attempt) {
    std::vector<Rational> w;
    Rational total = 0;
    for (std::size_t i = 0; i < vertices.size(); ++i) {
      w.push_back(Rational(1) +
                  Rational(static_cast<long>((i * 7 + static_cast<std::size_t>(seed) * 13 +
                                              static_cast<std::size_t>(attempt) * 5) %
                                                 17 +
                                             1)) /
                      1000003);
      total = total + w.back();
    }
    RatVec x(c.size(), Rational(0)), u(c.size());
    for (std::size_t i = 0; i < vertices.size(); ++i)
      for (std::size_t k = 0; k < x.size(); ++k) x[k] = x[k] + w[i] / total * vertices[i][k];
    for (std::size_t k = 0; k < x.size(); ++k) u[k] = x[k] + c[k];
    if (is_generic_point(spec.directions, u)) return x;
  }
  ADD_FAILURE() << "no generic interior point found";
  return vertices.front();
}

// Exact value of a JSON polynomial term list at x; `name` selects a stencil coefficient.
Rational evaluate(const nlohmann::json& polynomial, const RatVec& x, const std::string& name = "") {
  Rational sum = 0;
  for (const auto& term : polynomial["terms"]) {
    const nlohmann::json& c =
        name.empty() ? term["coefficient"] : term["coefficient"].value(name, nlohmann::json("0"));
    Rational t = parse_rational(c.get<std::string>());
    for (std::size_t k = 0; k < x.size(); ++k)
      t = t * cln::expt(x[k], term["exponents"][k].get<int>());
    sum = sum + t;
  }
  return sum;
}

RatVec rationals(const nlohmann::json& list) {
  RatVec out;
  for (const auto& v : list) out.push_back(parse_rational(v.get<std::string>()));
  return out;
}

void expect_inside(const nlohmann::json& region, const RatVec& x) {
  for (const auto& q : region["inequalities"]) {
    Rational lhs = 0;
    for (std::size_t k = 0; k < x.size(); ++k)
      lhs = lhs + Rational(q["normal"][k].get<long>()) * x[k];
    EXPECT_LT(lhs, parse_rational(q["bound"].get<std::string>())) << q.dump();
  }
}

TEST_P(PiecesOfPreset, JsonPiecesAgreeWithTheRecurrence) {
  const Derivation& a = derivation_of(GetParam());
  const RatVec c = spline_centre(a.spec);
  const Rational det = Rational(a.spec.lattice.det_abs());
  BoxSplineRecurrence recurrence(a.spec.directions);
  auto uncentred = [&](const RatVec& x) {
    RatVec u = x;
    for (std::size_t k = 0; k < u.size(); ++k) u[k] = u[k] + c[k];
    return u;
  };

  // The spline on every region of the fundamental region: coefficient of v_k is M(x - j_k).
  const nlohmann::json spline =
      pieces_json(spline_pieces(a.form, a.structure, {PieceSelection::All, 0}), "test");
  ASSERT_EQ(spline["pieces"].size(), a.structure.regions.size());
  for (const auto& piece : spline["pieces"]) {
    std::vector<RatVec> vertices;
    for (const auto& v : piece["region"]["vertices"]) vertices.push_back(rationals(v));
    for (int seed = 0; seed < 2; ++seed) {
      const RatVec x = generic_interior_point(vertices, a.spec, seed);
      expect_inside(piece["region"], x);
      recurrence.set_base(uncentred(x));
      Rational sum = 0;
      for (const auto& s : piece["stencil"]) {
        IntVec minus_j;
        for (const auto& v : s["point"]) minus_j.push_back(-v.get<std::int64_t>());
        const Rational expected = det * recurrence.at_shift(minus_j);
        sum = sum + expected;
        EXPECT_EQ(evaluate(piece["polynomial"], x, s["name"].get<std::string>()), expected)
            << s.dump();
      }
      EXPECT_EQ(sum, 1) << "the stencil misses a shift of M that is not zero here";
    }
  }

  // The filter on one piece per orbit (orbit 0 of each, listed in full by the text test above).
  const nlohmann::json filter =
      pieces_json(filter_pieces(a.form, {PieceSelection::Reference, 0}), "test");
  for (const auto& piece : filter["pieces"]) {
    std::vector<RatVec> vertices;
    for (const auto& v : piece["region"]["vertices"]) vertices.push_back(rationals(v));
    for (int seed = 0; seed < 3; ++seed) {
      const RatVec x = generic_interior_point(vertices, a.spec, seed);
      expect_inside(piece["region"], x);
      EXPECT_EQ(evaluate(piece["polynomial"], x),
                det * box_spline_recurrence(a.spec.directions, uncentred(x)));
    }
  }
}

TEST_P(PiecesOfPreset, OrbitsCountsAndRenderingsAreConsistent) {
  const Derivation& a = derivation_of(GetParam());
  const Pieces all = filter_pieces(a.form, {PieceSelection::All, 0});
  const Pieces reference = filter_pieces(a.form, {PieceSelection::Reference, 0});
  ASSERT_EQ(static_cast<int>(reference.pieces.size()), reference.orbits);
  int listed = 0;
  for (int o = 0; o < reference.orbits; ++o) {
    EXPECT_EQ(reference.pieces[o].orbit, o);
    listed += reference.pieces[o].orbit_size;
  }
  // --region N selects orbit N's reference piece (first and last orbit: each call derives anew).
  for (int o : {0, reference.orbits - 1}) {
    const Pieces one = filter_pieces(a.form, {PieceSelection::Orbit, o});
    ASSERT_EQ(one.pieces.size(), 1u);
    EXPECT_EQ(one.pieces[0].vertices, reference.pieces[o].vertices);
  }
  EXPECT_EQ(listed, static_cast<int>(all.pieces.size()));
  int regions = 0;
  const Pieces spline = spline_pieces(a.form, a.structure, {PieceSelection::Reference, 0});
  for (const auto& p : spline.pieces) regions += p.orbit_size;
  EXPECT_EQ(regions, static_cast<int>(a.structure.regions.size()));

  for (const Pieces* p : {&spline, &reference}) {
    const std::size_t k = p->pieces.size();
    EXPECT_EQ(count(format_pieces(*p, PieceFormat::Latex, "t"), "\\begin{dmath*}"),
              static_cast<int>(k));
    EXPECT_EQ(count(format_pieces(*p, PieceFormat::C, "t"), "\ndouble piece_"),
              static_cast<int>(k));
    EXPECT_EQ(nlohmann::json::parse(format_pieces(*p, PieceFormat::Json, "t"))["pieces"].size(), k);
  }
}

INSTANTIATE_TEST_SUITE_P(AllPresets, PiecesOfPreset, ::testing::ValuesIn(fixture::kAllPresets));

TEST(Pieces, BadOptionsAreInputErrors) {
  EXPECT_THROW(parse_pieces_of("splines"), InputError);
  EXPECT_THROW(parse_piece_format("pdf"), InputError);
  for (const char* r : {"", "refrence", "-1", "1.5", "9999999"})
    EXPECT_THROW(parse_piece_selection(r), InputError) << r;
  const Derivation& a = derivation_of("zp");
  EXPECT_THROW(spline_pieces(a.form, a.structure, {PieceSelection::Orbit, 1}),
               InputError);                                                     // one orbit
  EXPECT_THROW(filter_pieces(a.form, {PieceSelection::Orbit, 5}), InputError);  // five orbits
  EXPECT_NO_THROW(filter_pieces(a.form, {PieceSelection::Orbit, 4}));
}

// The paper's reference tetrahedron for M7 (section 4.2): (0,0,0), (1,1,1), (1,0,0), (1,1,0).
TEST(Pieces, M7ReferenceRegionIsThePapersTetrahedron) {
  const Derivation& a = derivation_of("m7");
  const Pieces p = spline_pieces(a.form, a.structure, {PieceSelection::Reference, 0});
  ASSERT_EQ(p.pieces.size(), 1u);
  const std::vector<RatVec> expected{{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {1, 1, 1}};
  EXPECT_EQ(p.pieces[0].vertices, expected);
  EXPECT_EQ(p.pieces[0].stencil.size(), 30u);
  EXPECT_EQ(p.pieces[0].orbit_size, 24);
}

}  // namespace
}  // namespace boxgen::generator
