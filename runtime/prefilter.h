// Discrete convolution of a BCC volume with a filter given as data (the generator's prefilters
// Q^I, Q^II arrive as tables of lattice offsets and weights; no weight is written here).
//
//   (V * q)(j) = sum_o q(o) V(j - o),  j and o in Z_bcc (lattice coordinates).
//
// Border policy: shrink, never invent data. The result keeps only samples whose whole
// neighbourhood {j - o} lies inside the input: the largest such volume of two equal cosets. It
// starts s_a = ceil(max(0, max_o o_a) / 2) coset cells further in (origin o + 2 h s) and has
// N_a - s_a - ceil(max(0, -min_o o_a) / 2) samples per coset along axis a. World coordinates
// keep their meaning, so a caller who sampled prefilter_margin(q) extra coset cells per side
// (sampling.h) gets back a volume that still covers the region of interest. A volume too small
// to keep any sample is an error.
#pragma once
#include <array>
#include <utility>
#include <vector>

#include "runtime/bcc_volume.h"
#include "runtime/lattice_volume.h"

namespace boxgen::runtime {

// Taps (lattice offset o, weight q(o)). Offsets must be BCC lattice vectors; a repeated offset
// counts with the sum of its weights.
using DiscreteFilter = std::vector<std::pair<std::array<int, 3>, double>>;

// Coset cells the result loses on each side, per axis.
struct PrefilterShrink {
  Sizes lower;  // s_a: the result starts this many cells further in
  Sizes upper;  // cells lost at the upper end
};

// Throws std::invalid_argument (one line) for an empty filter, an offset that is not a BCC
// lattice vector or beyond +-2^20, or a weight that is not finite.
PrefilterShrink prefilter_shrink(const DiscreteFilter& q);
// The largest entry of prefilter_shrink(q): the margin a caller must add for q (1 for filters
// whose taps lie within max-norm 2, such as Q^I and Q^II).
int prefilter_margin(const DiscreteFilter& q);

// V * q under the border policy above, accumulated in double. Throws std::invalid_argument (one
// line) for a bad filter or when no sample would remain.
template <class T>
BccVolume<T> prefilter(const BccVolume<T>& volume, const DiscreteFilter& q);

// The same on any lattice (lattice_volume.h): taps are vectors of the volume's lattice, and the
// result keeps the samples whose whole neighbourhood is inside, the largest such volume of K equal
// cosets. With delta(c, o) = (off_c - o - off_c') / d, c' the coset of off_c - o, the result
// starts s_a = max(0, -min delta_a) coset cells further in (origin o + d h s) and loses
// max(0, max delta_a) cells at the upper end. On BCC this is the shrink described above.
// Throws std::invalid_argument (one line) for a bad filter (an offset not in the lattice
// included) or when no sample would remain.
PrefilterShrink prefilter_shrink(const DiscreteFilter& q, const CosetLattice& lattice);
template <class T>
LatticeVolume<T> prefilter(const LatticeVolume<T>& volume, const DiscreteFilter& q);

extern template LatticeVolume<float> prefilter<float>(const LatticeVolume<float>&,
                                                      const DiscreteFilter&);
extern template LatticeVolume<double> prefilter<double>(const LatticeVolume<double>&,
                                                        const DiscreteFilter&);
extern template BccVolume<float> prefilter<float>(const BccVolume<float>&, const DiscreteFilter&);
extern template BccVolume<double> prefilter<double>(const BccVolume<double>&,
                                                    const DiscreteFilter&);

}  // namespace boxgen::runtime
