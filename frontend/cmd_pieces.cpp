// `boxgen pieces`: the explicit piecewise polynomials of the spline or the filter, printed by
// GiNaC (generator/piece_format.h). Every option is checked before the derivation starts.
#include <fmt/core.h>

#include "frontend/commands.h"
#include "generator/error.h"
#include "generator/piece_format.h"
#include "generator/pieces.h"

namespace boxgen::frontend {

std::string pieces_text(const Common& c, const std::string& of, const std::string& region,
                        const std::string& format) {
  const PiecesOf what = parse_pieces_of(of);
  const PieceSelection selection = parse_piece_selection(region);
  const PieceFormat printer = c.json ? PieceFormat::Json : parse_piece_format(format);
  const BoxSplineSpec spec = parse_spec(c.spec, c.lattice);
  const std::string title =
      fmt::format("boxgen pieces {}{} --of {} --region {}",
                  spec.name == "custom" ? fmt::format("\"{}\"", spec.directions_text()) : spec.name,
                  c.lattice.empty() ? "" : fmt::format(" --lattice \"{}\"", c.lattice), of, region);
  const PiecewiseForm form =
      derive_piecewise(spec, DerivationMethod::TruncatedPower, {}, derivation_budget(c));
  const Pieces pieces = what == PiecesOf::Spline
                            ? spline_pieces(form, spline_structure(form), selection)
                            : filter_pieces(form, selection);
  return format_pieces(pieces, printer, title);
}

int run_pieces(const Common& c, const std::string& of, const std::string& region,
               const std::string& format) {
  fmt::print("{}", pieces_text(c, of, region, format));
  return 0;
}

}  // namespace boxgen::frontend
