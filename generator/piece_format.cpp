#include "generator/piece_format.h"

#include <algorithm>
#include <sstream>

#include <fmt/core.h>

#include "generator/error.h"
#include "generator/ginac_bridge.h"

namespace boxgen::generator {

PieceFormat parse_piece_format(std::string_view text) {
  if (text == "text") return PieceFormat::Text;
  if (text == "latex") return PieceFormat::Latex;
  if (text == "c") return PieceFormat::C;
  if (text == "json") return PieceFormat::Json;
  fail_input(fmt::format("--format must be 'text', 'latex', 'c' or 'json', got '{}'", text));
}

std::string stencil_name(std::size_t k) { return "v" + std::to_string(k); }

std::vector<GiNaC::symbol> stencil_symbols(std::size_t count, bool c_names) {
  std::vector<GiNaC::symbol> out;
  for (std::size_t k = 0; k < count; ++k)
    out.emplace_back(c_names ? fmt::format("v[{}]", k) : stencil_name(k),
                     fmt::format("v_{{{}}}", k));
  return out;
}

GiNaC::ex piece_expression(const Piece& piece, const std::vector<GiNaC::symbol>& stencil) {
  if (piece.stencil.empty()) return to_ex(piece.polynomials.front());
  if (stencil.size() != piece.polynomials.size())
    fail_internal("piece_expression: one symbol per stencil point is needed");
  GiNaC::ex sum = 0;
  for (std::size_t k = 0; k < stencil.size(); ++k) sum += stencil[k] * to_ex(piece.polynomials[k]);
  GiNaC::lst vars;
  for (const auto& s : coordinate_symbols(piece.polynomials.front().vars())) vars.append(s);
  return GiNaC::collect(sum.expand(), vars, true);
}

namespace {

enum class Printer { Text, Latex, C };

// GiNaC's printer for the format, on an atom (a number, a power of one coordinate, a symbol).
std::string print(const GiNaC::ex& e, Printer printer) {
  std::ostringstream os;
  if (printer == Printer::Latex)
    e.print(GiNaC::print_latex(os));
  else if (printer == Printer::C)
    e.print(GiNaC::print_csrc_double(os));
  else
    e.print(GiNaC::print_dflt(os));
  return os.str();
}

// GiNaC orders the operands of a sum or a product by hash values seeded with the addresses of
// type descriptors, which change from run to run (address-space randomisation): a GiNaC sum
// printed as a whole lists its terms in a different order on each run. Sums and products are
// therefore assembled here in a fixed order (the monomials' graded order, then x before y
// before z, then stencil index), from atoms that GiNaC's printer for the format prints.
const char* times(Printer printer) { return printer == Printer::Latex ? " " : "*"; }

// One term of a sum: coefficient * factor, where an empty factor means 1.
struct Term {
  Rational coefficient;
  std::string factor;
};

std::string sum_text(const std::vector<Term>& terms, Printer printer) {
  std::string out;
  for (const Term& t : terms) {
    if (cln::zerop(t.coefficient)) continue;
    const bool negative = cln::minusp(t.coefficient);
    if (negative)
      out += "-";
    else if (!out.empty())
      out += "+";
    const Rational c = negative ? Rational(-t.coefficient) : t.coefficient;
    if (t.factor.empty())
      out += print(to_numeric(c), printer);
    else if (c == 1)
      out += t.factor;
    else
      out += print(to_numeric(c), printer) + times(printer) + t.factor;
  }
  return out.empty() ? print(GiNaC::numeric(0), printer) : out;
}

// x^a y^b z^c as a product of GiNaC-printed powers; "" for the constant monomial.
std::string monomial_text(const Exponent& e, int n, Printer printer) {
  const auto& vars = coordinate_symbols(n);
  std::string out;
  for (int i = 0; i < n; ++i) {
    if (e[i] == 0) continue;
    if (!out.empty()) out += times(printer);
    out += print(GiNaC::pow(vars[i], e[i]), printer);
  }
  return out;
}

std::string joined_factor(const std::string& a, const std::string& b, Printer printer) {
  if (a.empty()) return b;
  if (b.empty()) return a;
  return a + times(printer) + b;
}

// The piece's polynomial: M(x) for the filter; for the spline sum_k v_k M(x - j_k) collected in
// the coordinates, each coefficient a combination of the stencil symbols `stencil` (in parentheses
// when it has several terms).
std::string polynomial_text(const Piece& piece, const std::vector<GiNaC::symbol>& stencil, int n,
                            Printer printer) {
  int capacity = 0;
  for (const auto& q : piece.polynomials) capacity = std::max(capacity, q.capacity());
  std::vector<Term> terms;
  for (const auto& e : monomial_exponents(n, capacity)) {
    if (e[0] + e[1] + e[2] > capacity) break;
    const std::string monomial = monomial_text(e, n, printer);
    if (piece.stencil.empty()) {
      terms.push_back({piece.polynomials.front().coefficient(e), monomial});
      continue;
    }
    std::vector<Term> combination;
    for (std::size_t k = 0; k < piece.polynomials.size(); ++k) {
      const Rational& c = piece.polynomials[k].coefficient(e);
      if (!cln::zerop(c)) combination.push_back({c, print(stencil[k], printer)});
    }
    if (combination.size() == 1 || monomial.empty()) {
      for (Term& t : combination)
        terms.push_back({t.coefficient, joined_factor(t.factor, monomial, printer)});
      continue;
    }
    if (!combination.empty())
      terms.push_back({Rational(1), joined_factor("(" + sum_text(combination, printer) + ")",
                                                  monomial, printer)});
  }
  return sum_text(terms, printer);
}

std::string point_text(const RatVec& p, Printer printer) {
  std::string s = "(";
  for (std::size_t i = 0; i < p.size(); ++i) s += (i ? "," : "") + print(to_numeric(p[i]), printer);
  return s + ")";
}

std::string point_text(const IntVec& p) {
  std::string s = "(";
  for (std::size_t i = 0; i < p.size(); ++i) s += (i ? "," : "") + std::to_string(p[i]);
  return s + ")";
}

// normal.x <= bound, written as (-normal).x >= -bound when the normal's first nonzero entry is
// negative, so that "x >= 2" reads as such.
std::string inequality_text(const Inequality& q, Printer printer) {
  const auto first =
      std::find_if(q.normal.begin(), q.normal.end(), [](std::int64_t v) { return v != 0; });
  const long sign = first != q.normal.end() && *first < 0 ? -1 : 1;
  std::vector<Term> lhs;
  const auto& vars = coordinate_symbols(static_cast<int>(q.normal.size()));
  for (std::size_t i = 0; i < q.normal.size(); ++i)
    lhs.push_back({Rational(sign * static_cast<long>(q.normal[i])), print(vars[i], printer)});
  const char* relation =
      printer == Printer::Latex ? (sign > 0 ? " \\le " : " \\ge ") : (sign > 0 ? " <= " : " >= ");
  return sum_text(lhs, printer) + relation + print(to_numeric(q.bound * Rational(sign)), printer);
}

std::string variables_text(int n) { return n == 2 ? "x,y" : "x,y,z"; }

std::string what_text(const Pieces& p) {
  return p.of == PiecesOf::Spline ? "the spline s(x) = sum_j V(j) M(x - j) with v_k = V(j_k)"
                                  : "the filter M = |det G| M^c";
}

std::string piece_heading(const Pieces& all, const Piece& p, std::size_t index) {
  return all.of == PiecesOf::Spline
             ? fmt::format("piece {}: orbit {}, {} region(s) per fundamental region map onto it",
                           index, p.orbit, p.orbit_size)
             : fmt::format("piece {}: orbit {}, {} congruent piece(s) in the orbit", index, p.orbit,
                           p.orbit_size);
}

std::string text_pieces(const Pieces& all, const std::string& title) {
  std::string out =
      fmt::format("# {}\n# {} in the centred frame of `boxgen eval`; degree {}, {} orbit(s)\n",
                  title, what_text(all), all.degree, all.orbits);
  for (std::size_t i = 0; i < all.pieces.size(); ++i) {
    const Piece& p = all.pieces[i];
    out += piece_heading(all, p, i) + "\n  vertices:";
    for (const auto& v : p.vertices) out += " " + point_text(v, Printer::Text);
    out += "\n  inequalities:";
    for (std::size_t k = 0; k < p.inequalities.size(); ++k)
      out += (k ? ", " : " ") + inequality_text(p.inequalities[k], Printer::Text);
    out += "\n";
    if (!p.stencil.empty()) {
      out += fmt::format("  stencil ({} points):\n", p.stencil.size());
      for (std::size_t k = 0; k < p.stencil.size(); ++k)
        out += fmt::format("    {} = V{}\n", stencil_name(k), point_text(p.stencil[k]));
    }
    const std::string lhs = all.of == PiecesOf::Spline ? "s" : "M";
    out += fmt::format(
        "  {}({}) = {}\n", lhs, variables_text(all.dimension),
        polynomial_text(p, stencil_symbols(p.stencil.size()), all.dimension, Printer::Text));
  }
  return out;
}

std::string latex_pieces(const Pieces& all, const std::string& title) {
  std::string out = fmt::format(
      "% {}\n% {} in the centred frame of `boxgen eval`; degree {}, {} orbit(s).\n"
      "% Long polynomials break across lines with \\usepackage{{breqn}} (dmath*).\n",
      title, what_text(all), all.degree, all.orbits);
  for (std::size_t i = 0; i < all.pieces.size(); ++i) {
    const Piece& p = all.pieces[i];
    out += fmt::format("% {}\n\\paragraph{{Piece {}.}} Vertices", piece_heading(all, p, i), i);
    for (std::size_t k = 0; k < p.vertices.size(); ++k)
      out += fmt::format("{} ${}$", k ? "," : "", point_text(p.vertices[k], Printer::Latex));
    out += "; region";
    for (std::size_t k = 0; k < p.inequalities.size(); ++k)
      out +=
          fmt::format("{} ${}$", k ? "," : "", inequality_text(p.inequalities[k], Printer::Latex));
    out += ".\n";
    if (!p.stencil.empty()) {
      out += "Stencil";
      for (std::size_t k = 0; k < p.stencil.size(); ++k)
        out += fmt::format("{} $v_{{{}}} = V{}$", k ? "," : "", k, point_text(p.stencil[k]));
      out += ".\n";
    }
    out += fmt::format(
        "\\begin{{dmath*}}\n{}({}) = {}\n\\end{{dmath*}}\n", all.of == PiecesOf::Spline ? "s" : "M",
        variables_text(all.dimension),
        polynomial_text(p, stencil_symbols(p.stencil.size()), all.dimension, Printer::Latex));
  }
  return out;
}

std::string c_pieces(const Pieces& all, const std::string& title) {
  std::string out =
      fmt::format("/* {}\n   {} in the centred frame of `boxgen eval`; degree {}, {} orbit(s).\n",
                  title, what_text(all), all.degree, all.orbits);
  out += all.of == PiecesOf::Spline
             ? "   piece_N(x, v) = s(x) on piece N's region, v[k] = V(j_k). */\n"
             : "   piece_N(x) = M(x) on piece N's region. */\n";
  const std::string coordinates =
      all.dimension == 2 ? "double x, double y" : "double x, double y, double z";
  for (std::size_t i = 0; i < all.pieces.size(); ++i) {
    const Piece& p = all.pieces[i];
    out += fmt::format("\n/* {}\n   region:", piece_heading(all, p, i));
    for (std::size_t k = 0; k < p.inequalities.size(); ++k)
      out += (k ? ", " : " ") + inequality_text(p.inequalities[k], Printer::Text);
    out += "\n   vertices:";
    for (const auto& v : p.vertices) out += " " + point_text(v, Printer::Text);
    for (std::size_t k = 0; k < p.stencil.size(); ++k)
      out += fmt::format("{}v[{}] = V{}", k % 6 ? ", " : "\n   ", k, point_text(p.stencil[k]));
    const std::string body =
        polynomial_text(p, stencil_symbols(p.stencil.size(), true), all.dimension, Printer::C);
    out += fmt::format(
        " */\ndouble piece_{}({}{}) {{\n  return {};\n}}\n", i, coordinates,
        p.stencil.empty() ? "" : fmt::format(", const double v[{}]", p.stencil.size()), body);
  }
  return out;
}

nlohmann::json rationals(const RatVec& v) {
  nlohmann::json out = nlohmann::json::array();
  for (const auto& x : v) out.push_back(to_string(x));
  return out;
}

nlohmann::json polynomial_json(const Piece& p, int n) {
  nlohmann::json terms = nlohmann::json::array();
  int capacity = 0;
  for (const auto& q : p.polynomials) capacity = std::max(capacity, q.capacity());
  for (const auto& e : monomial_exponents(n, capacity)) {
    if (e[0] + e[1] + e[2] > capacity) break;
    nlohmann::json exponents = nlohmann::json::array();
    for (int k = 0; k < n; ++k) exponents.push_back(e[k]);
    if (p.stencil.empty()) {
      const Rational& c = p.polynomials.front().coefficient(e);
      if (!cln::zerop(c))
        terms.push_back({{"exponents", exponents}, {"coefficient", to_string(c)}});
      continue;
    }
    nlohmann::json coefficient = nlohmann::json::object();
    for (std::size_t k = 0; k < p.polynomials.size(); ++k) {
      const Rational& c = p.polynomials[k].coefficient(e);
      if (!cln::zerop(c)) coefficient[stencil_name(k)] = to_string(c);
    }
    if (!coefficient.empty())
      terms.push_back({{"exponents", exponents}, {"coefficient", coefficient}});
  }
  return {{"variables", n == 2 ? nlohmann::json{"x", "y"} : nlohmann::json{"x", "y", "z"}},
          {"terms", terms}};
}

}  // namespace

nlohmann::json pieces_json(const Pieces& all, const std::string& title) {
  nlohmann::json pieces = nlohmann::json::array();
  for (const auto& p : all.pieces) {
    nlohmann::json region{{"vertices", nlohmann::json::array()},
                          {"inequalities", nlohmann::json::array()}};
    for (const auto& v : p.vertices) region["vertices"].push_back(rationals(v));
    for (const auto& q : p.inequalities)
      region["inequalities"].push_back({{"normal", q.normal}, {"bound", to_string(q.bound)}});
    nlohmann::json piece{{"orbit", p.orbit}, {"orbit_size", p.orbit_size}, {"region", region}};
    if (!p.stencil.empty()) {
      piece["stencil"] = nlohmann::json::array();
      for (std::size_t k = 0; k < p.stencil.size(); ++k)
        piece["stencil"].push_back({{"name", stencil_name(k)}, {"point", p.stencil[k]}});
    }
    piece["polynomial"] = polynomial_json(p, all.dimension);
    pieces.push_back(piece);
  }
  return {{"command", title},     {"of", all.of == PiecesOf::Spline ? "spline" : "filter"},
          {"frame", "centred"},   {"degree", all.degree},
          {"orbits", all.orbits}, {"pieces", pieces}};
}

std::string format_pieces(const Pieces& pieces, PieceFormat format, const std::string& title) {
  switch (format) {
    case PieceFormat::Text:
      return text_pieces(pieces, title);
    case PieceFormat::Latex:
      return latex_pieces(pieces, title);
    case PieceFormat::C:
      return c_pieces(pieces, title);
    case PieceFormat::Json:
      return pieces_json(pieces, title).dump(2) + "\n";
  }
  fail_internal("unknown piece format");
}

}  // namespace boxgen::generator
