// Sampling an analytic function on any lattice (lattice_volume.h), and the grid of the cube
// [-1,1]^3 with the margins that reconstruction and prefiltering need around it.
//
// The cube [-1,1]^3 at density N: coset cells of d h = 2/(N-1), so that each coset has N samples
// per axis over the cube: h = 2/(d (N-1)). A margin of m coset cells adds m samples per coset on
// every side: N + 2m samples per coset and axis, origin o = -1 - d h m. On BCC (d = 2) these are
// the "N^3 x 2 samples" of docs/design.md §13: the even (primary) points -1 + 2hi span [-1,1] on
// each axis and the odd points -1 + h(2i+1) are the centres of the cubes between them (one odd
// point lies beyond each cube face, the cost of storing both cosets with equal sizes); on the
// Cartesian lattice it is the N^3 grid of spacing 2/(N-1); FCC has 4 N^3 samples.
//
// How much margin: SplineFilter::required_margin(prefilter) derives it from the stencil reach the
// generator publishes with each evaluator (2 coset cells for M7, M8 and M12, one more with Q^I or
// Q^II, whose taps reach one coset cell: prefilter_margin in prefilter.h).
#pragma once
#include <functional>

#include "runtime/lattice_volume.h"

namespace boxgen::runtime {

using ScalarFunction = std::function<double(const Vec3&)>;

// Where the samples go: the lattice, sizes per coset, spacing and origin (LatticeVolume's
// arguments).
struct LatticeGrid {
  CosetLattice lattice;
  Sizes sizes;
  double h;
  Vec3 origin;
};

// The grid of [-1,1]^3 at density n with `margin` extra coset cells per side. Throws
// std::invalid_argument (one line) unless n >= 2, margin >= 0 and n + 2 margin <= kMaxSize.
LatticeGrid cube_lattice_grid(const CosetLattice& lattice, int n, int margin);

// Every sample of the grid set to f at its world position (f is evaluated in double, then
// rounded to T by to_sample). Throws std::invalid_argument for an invalid grid (see
// LatticeVolume).
template <class T>
LatticeVolume<T> sample_lattice(const ScalarFunction& f, const LatticeGrid& grid);

extern template LatticeVolume<float> sample_lattice<float>(const ScalarFunction&,
                                                           const LatticeGrid&);
extern template LatticeVolume<double> sample_lattice<double>(const ScalarFunction&,
                                                             const LatticeGrid&);

}  // namespace boxgen::runtime
