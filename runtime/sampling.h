// Sampling an analytic function on the BCC lattice, and the margins that reconstruction and
// prefiltering need around the region of interest.
//
// The cube [-1,1]^3 at density N ("N^3 x 2 samples", docs/design.md §13): h = 1/(N-1), the even
// (primary) points -1 + 2hi, i = 0..N-1, span [-1,1] on each axis, and the odd points
// -1 + h(2i+1) are the centres of the cubes between them. A margin of m coset cells adds m
// samples per coset on every side: N + 2m samples per coset and axis, origin o = -1 - 2hm.
// (The odd coset then runs from -1 - 2hm + h to 1 + 2hm + h: one odd point lies beyond each
// cube face, the cost of storing both cosets with equal sizes.)
//
// How much margin: required_margin(filter, prefilter) in reconstruction.h derives it from the
// stencil reach the generator publishes with each evaluator (2 coset cells for M7, M8 and M12,
// one more with Q^I or Q^II, whose taps reach one coset cell: prefilter_margin in prefilter.h).
#pragma once
#include <array>
#include <functional>
#include <vector>

#include "runtime/bcc_volume.h"
#include "runtime/lattice_volume.h"

namespace boxgen::runtime {

using ScalarFunction = std::function<double(const Vec3&)>;

// Where the samples go: sizes per coset, spacing and origin (the arguments of BccVolume).
struct BccGrid {
  Sizes sizes;
  double h;
  Vec3 origin;
};

// The grid of [-1,1]^3 at density n (h = 1/(n-1)) with `margin` extra coset cells per side.
// Throws std::invalid_argument (one line) unless n >= 2, margin >= 0 and n + 2 margin <= kMaxSize.
BccGrid cube_grid(int n, int margin);

// Every sample of the grid set to f at its world position (f is evaluated in double, then
// rounded to T by to_sample). Throws std::invalid_argument for an invalid grid (see BccVolume).
template <class T>
BccVolume<T> sample_bcc(const ScalarFunction& f, const BccGrid& grid);

// sample_bcc(f, cube_grid(n, margin)).
template <class T>
BccVolume<T> sample_cube(const ScalarFunction& f, int n, int margin) {
  return sample_bcc<T>(f, cube_grid(n, margin));
}

// Sampling on any lattice (lattice_volume.h). The cube [-1,1]^3 at density N: coset cells of
// d h = 2/(N-1), so that each coset has N samples per axis over the cube (plus 2 margin), as for
// BCC above: h = 2/(d (N-1)), origin -1 - d h margin. On BCC this is cube_grid exactly; on the
// Cartesian lattice it is the N^3 grid of spacing 2/(N-1); FCC has 4 N^3 samples.
struct LatticeGrid {
  CosetLattice lattice;
  Sizes sizes;
  double h;
  Vec3 origin;
};

// Throws std::invalid_argument (one line) unless n >= 2, margin >= 0 and n + 2 margin <= kMaxSize.
LatticeGrid cube_lattice_grid(const CosetLattice& lattice, int n, int margin);

// Every sample of the grid set to f at its world position (f evaluated in double, rounded to T).
template <class T>
LatticeVolume<T> sample_lattice(const ScalarFunction& f, const LatticeGrid& grid);

extern template LatticeVolume<float> sample_lattice<float>(const ScalarFunction&,
                                                           const LatticeGrid&);
extern template LatticeVolume<double> sample_lattice<double>(const ScalarFunction&,
                                                             const LatticeGrid&);

extern template BccVolume<float> sample_bcc<float>(const ScalarFunction&, const BccGrid&);
extern template BccVolume<double> sample_bcc<double>(const ScalarFunction&, const BccGrid&);

}  // namespace boxgen::runtime
