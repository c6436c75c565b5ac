// The explicit pieces (pieces.h) in four renderings (docs/design.md §12): `text`, `latex` and `c`
// through GiNaC's default, LaTeX and C printers, `json` the exact data. Every number stays an
// exact rational except in `c`, where GiNaC writes p/q as a quotient of double literals. GiNaC
// orders a sum's terms by hashes that change from run to run, so the formulas are assembled in a
// fixed order (the monomials' graded order) from atoms GiNaC prints: the output is reproducible.
#pragma once
#include <ginac/ginac.h>

#include <string>
#include <string_view>
#include <vector>

#include <nlohmann/json.hpp>

#include "generator/pieces.h"

namespace boxgen::generator {

enum class PieceFormat { Text, Latex, C, Json };
PieceFormat parse_piece_format(std::string_view text);  // text | latex | c | json

// Stencil names v0, v1, ... (the names `boxgen bbform` uses for V(j_0), V(j_1), ...).
std::string stencil_name(std::size_t k);
// One symbol per stencil point; `c_names` gives v[0], v[1], ... for the C printer.
std::vector<GiNaC::symbol> stencil_symbols(std::size_t count, bool c_names = false);
// The piece's polynomial as a GiNaC expression: M(x) for the filter; for the spline
// sum_k v_k M(x - j_k), collected as a polynomial in x, y, z with coefficients linear in the v_k.
GiNaC::ex piece_expression(const Piece& piece, const std::vector<GiNaC::symbol>& stencil);

// `title` names what was asked (the command line), printed as a comment in the output.
std::string format_pieces(const Pieces& pieces, PieceFormat format, const std::string& title);
nlohmann::json pieces_json(const Pieces& pieces, const std::string& title);

}  // namespace boxgen::generator
