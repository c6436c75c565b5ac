// Discrete convolution of a lattice volume with a filter given as data (the generator's
// prefilters Q^I, Q^II arrive as tables of lattice offsets and weights; no weight is written
// here).
//
//   (V * q)(j) = sum_o q(o) V(j - o),  j and o in L (lattice coordinates).
//
// Border policy: shrink, never invent data. The result keeps only samples whose whole
// neighbourhood {j - o} lies inside the input: the largest such volume of K equal cosets. With
// delta(c, o) = (off_c - o - off_c') / d, c' the coset of off_c - o, it starts
// s_a = max(0, -min delta_a) coset cells further in (origin o + d h s) and loses
// max(0, max delta_a) cells at the upper end (on BCC: ceil(max o_a / 2) and ceil(-min o_a / 2)).
// World coordinates keep their meaning, so a caller who sampled prefilter_margin(q) extra coset
// cells per side (sampling.h) gets back a volume that still covers the region of interest. A
// volume too small to keep any sample is an error.
#pragma once
#include <array>
#include <cstdint>
#include <utility>
#include <vector>

#include "runtime/lattice_volume.h"

namespace boxgen::runtime {

// Taps (lattice offset o, weight q(o)). Offsets must be lattice vectors; a repeated offset counts
// with the sum of its weights.
using PrefilterTaps = std::vector<std::pair<std::array<int, 3>, double>>;

// Where tap o reads for output coset c: the lattice point off_c - o lies in coset `coset`, at
// off_coset + d delta; the read of sample (c, i) is sample (coset, i + delta). Offsets must be
// lattice vectors.
struct TapStep {
  int coset;
  std::array<std::int64_t, 3> delta;
};
TapStep tap_step(const CosetLattice& lattice, int c, const std::array<int, 3>& o);

// Coset cells the result loses on each side, per axis.
struct PrefilterShrink {
  Sizes lower;  // s_a: the result starts this many cells further in
  Sizes upper;  // cells lost at the upper end
};

// Throws std::invalid_argument (one line) for an empty filter, an offset that is not a vector of
// the lattice or beyond +-kMaxLatticeEntry (runtime/lattice_limits.h), or a weight that is not
// finite.
PrefilterShrink prefilter_shrink(const PrefilterTaps& q, const CosetLattice& lattice);
// The largest entry of prefilter_shrink: the margin a caller must add for q (1 for the taps of
// Q^I and Q^II on BCC, which lie within max-norm 2).
int prefilter_margin(const PrefilterTaps& q, const CosetLattice& lattice);

// V * q under the border policy above, accumulated in double. Throws std::invalid_argument (one
// line) for a bad filter or when no sample would remain.
template <class T>
LatticeVolume<T> prefilter(const LatticeVolume<T>& volume, const PrefilterTaps& q);

// A Gaussian low-pass of a Cartesian volume against aliasing before subsampling: standard
// deviation sigma samples along each axis (anisotropic volumes: sigma of each axis's own spacing),
// separable, truncated at r = ceil(3 sigma) samples and normalised to sum 1, under the border
// policy above (r samples fewer on each side). Throws std::invalid_argument (one line) for another
// lattice, sigma not in (0, 1000] or a volume of at most 2 r samples on some axis.
template <class T>
LatticeVolume<T> gaussian_smooth(const LatticeVolume<T>& volume, double sigma);

extern template LatticeVolume<float> gaussian_smooth<float>(const LatticeVolume<float>&, double);
extern template LatticeVolume<double> gaussian_smooth<double>(const LatticeVolume<double>&, double);
extern template LatticeVolume<float> prefilter<float>(const LatticeVolume<float>&,
                                                      const PrefilterTaps&);
extern template LatticeVolume<double> prefilter<double>(const LatticeVolume<double>&,
                                                        const PrefilterTaps&);

}  // namespace boxgen::runtime
