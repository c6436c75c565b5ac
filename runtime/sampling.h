// Sampling an analytic function on the BCC lattice, and the margins that reconstruction and
// prefiltering need around the region of interest.
//
// The cube [-1,1]^3 at density N ("N^3 x 2 samples", design.md 10): h = 1/(N-1), the even
// (primary) points -1 + 2hi, i = 0..N-1, span [-1,1] on each axis, and the odd points
// -1 + h(2i+1) are the centres of the cubes between them. A margin of m coset cells adds m
// samples per coset on every side: N + 2m samples per coset and axis, origin o = -1 - 2hm.
// (The odd coset then runs from -1 - 2hm + h to 1 + 2hm + h: one odd point lies beyond each
// cube face, the cost of storing both cosets with equal sizes.)
//
// How much margin: in lattice coordinates the cube is [2m, 2m + 2N - 2] per axis. A box spline
// whose support reaches r lattice units from its centre (max-norm; support_radius below) needs
// the samples j with |x_a - j_a| <= r for every x in the cube (<= rather than <: points on a
// region boundary, including ones moved there by rounding, may be evaluated with the stencil of
// the neighbouring region). As j is an integer the lower side needs 2m >= floor(r), the upper side
// only 2m >= floor(r) - 1, so m = ceil(floor(r)/2) = reconstruction_margin(r) suffices:
//   M7 (r = 3): 2,  M8 (r = 4): 2,  M12 (r = 4): 2.
// A prefilter shrinks the volume by prefilter_margin(q) coset cells per side (prefilter.h; 1 for
// Q^I and Q^II, whose taps lie within max-norm 2), so sample with
//   margin = reconstruction_margin(support_radius(directions)) + prefilter_margin(q).
#pragma once
#include <array>
#include <functional>
#include <vector>

#include "runtime/bcc_volume.h"

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

// Max-norm radius, in lattice units, of the support of the centred box spline with these
// direction vectors (columns of Xi): max over axes a of sum_xi |xi_a| / 2.
double support_radius(const std::vector<std::array<int, 3>>& directions);
// Coset cells of margin that reconstruction with a filter of that support radius needs:
// ceil(floor(r) / 2), see above. Throws std::invalid_argument for a negative or non-finite radius.
int reconstruction_margin(double support_radius);

extern template BccVolume<float> sample_bcc<float>(const ScalarFunction&, const BccGrid&);
extern template BccVolume<double> sample_bcc<double>(const ScalarFunction&, const BccGrid&);

}  // namespace boxgen::runtime
