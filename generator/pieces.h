// Explicit pieces (docs/design.md §12): the polynomials a user can put in a paper, each with its
// region given exactly by vertices and bounding inequalities, all in the centred frame that
// `boxgen eval` uses (x, with the filter M(x) = |det G| M^c(x)).
//  - the spline s(x) = sum_j V(j) M(x - j) on the regions of the fundamental region: one
//    polynomial M(x - j) per stencil point j, so that s = sum_k v_k basis[k] with v_k = V(j_k);
//  - the filter M itself on the maximal convex pieces of its support.
// Pieces related by the symmetry group (and, for the spline, lattice translations) form an
// orbit; `reference` selects one piece per orbit.
#pragma once
#include <string>
#include <string_view>
#include <vector>

#include "generator/spline_regions.h"

namespace boxgen::generator {

enum class PiecesOf { Spline, Filter };

// Which pieces: one per orbit, every piece, or the reference piece of one orbit.
struct PieceSelection {
  enum Kind { Reference, All, Orbit } kind = Reference;
  int orbit = 0;
};
PiecesOf parse_pieces_of(std::string_view text);              // spline | filter
PieceSelection parse_piece_selection(std::string_view text);  // reference | all | N

// normal . x <= bound
struct Inequality {
  IntVec normal;
  Rational bound;
};

struct Piece {
  std::vector<RatVec> vertices;          // sorted
  std::vector<Inequality> inequalities;  // one per boundary facet's plane
  RatVec interior;                       // strictly inside
  int orbit = 0;
  int orbit_size = 0;             // pieces (spline: per fundamental region) in the orbit
  std::vector<IntVec> stencil;    // spline only: lattice points j_k, sorted
  std::vector<Poly> polynomials;  // spline: M(x - j_k) per stencil point; filter: one, M(x)
};

struct Pieces {
  PiecesOf of = PiecesOf::Spline;
  int dimension = 0;
  int degree = 0;
  int orbits = 0;
  std::vector<Piece> pieces;
};

// Throws InputError for an orbit index out of range.
Pieces spline_pieces(const PiecewiseForm& form, const SplineStructure& structure,
                     const PieceSelection& selection);
Pieces filter_pieces(const PiecewiseForm& form, const PieceSelection& selection);

}  // namespace boxgen::generator
