// Resampling a lattice volume onto a Cartesian grid (for 3D Slicer, ParaView, unu: nrrd_io.h
// writes the result), and the default grid: the largest box in which the filter can be evaluated.
//
// Where a filter can be evaluated: the generated evaluator of a filter with centre shift c
// (kCentre: the uncentred frame u = x + c has its knot planes at integer levels) fetches, for a
// point x in lattice coordinates, a stencil that depends only on the unit cube k = floor(x + c)
// holding x and on the cell of that cube. Over all cells of all cubes the fetched lattice points
// j satisfy  k_a + lo_a <= j_a <= k_a + hi_a  (StencilReach: the generator publishes lo and hi
// with each evaluator as kStencilReachLo/Hi, and tests/runtime checks them against the fetches).
// A volume of K cosets of N_a samples per axis (period d) holds every lattice point of the box
// 0 <= j_a <= d N_a - 1 (the coset offsets lie in [0, d)^3), and every cube type occurs on every
// face of a box at least d units wide, so the exact region where every point evaluates is the
// half-open box
//   -lo_a - c_a  <=  x_a  <  d N_a - hi_a - c_a        (lattice coordinates, per axis a).
// The default box is that region, closed, and pulled in on each side by a rounding guard g (a few
// ulps of the coordinates, in T and in double: see default_box) so that a grid point on its faces
// still lands in the right unit cube after world -> lattice conversion. Growing it by one grid
// step (anything more than g) on any side leaves the region.
#pragma once
#include <array>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <optional>
#include <span>

#include "runtime/affine.h"
#include "runtime/cartesian_volume.h"
#include "runtime/lattice_volume.h"
#include "runtime/sampling.h"
#include "runtime/spline_filter.h"

namespace boxgen::runtime {

// An axis-aligned box of world points, min <= x <= max.
struct Box {
  Vec3 min{}, max{};
};

// The region where f can be evaluated on `volume` (the half-open box above), in world
// coordinates: every point with min <= x < max (componentwise) evaluates. Throws
// std::invalid_argument (one line) for a volume of another lattice than f's or one too small for
// the stencil (empty region).
template <class T>
Box evaluable_region(const LatticeVolume<T>& volume, const SplineFilter& f);
// The default resampling box: evaluable_region closed and pulled in by the rounding guard.
// Throws std::invalid_argument (one line) as evaluable_region.
template <class T>
Box default_box(const LatticeVolume<T>& volume, const SplineFilter& f);

// Geometry of a Cartesian grid (a CartesianVolume without its values): point (i, j, k) at
// origin + (i, j, k) * spacing in the grid's frame. `to_volume`, when set, maps the grid's frame
// to the volume's (an oblique grid or volume: the volume's frame after the inverse of its
// affine, SourceSamples::frame); unset, the two frames are one and points are used as they are.
struct CartesianGrid {
  Sizes sizes{};
  Vec3 spacing{};
  Vec3 origin{};
  std::optional<Affine> to_volume{};
};

// Largest number of grid points per axis and in total: keeps the sample count far from overflow
// (memory runs out before the second limit; the allocation then throws std::bad_alloc).
inline constexpr int kMaxGridSize = 1 << 16;
inline constexpr std::uint64_t kMaxGridPoints = std::uint64_t{1} << 34;

// n[a] points from box.min[a] to box.max[a] (both included): spacing (max - min) / (n - 1),
// origin box.min. Throws std::invalid_argument (one line) for a non-finite, empty or degenerate
// box (max <= min on some axis) or a size outside [2, kMaxGridSize] or above kMaxGridPoints.
CartesianGrid grid_over(const Box& box, Sizes n);

// The values of the spline of f on `volume` (prefilter it first for quasi-interpolation) at the
// grid points (mapped by grid.to_volume: reconstruction in the volume's own frame, its index space
// scaled by its voxel sizes), evaluated on all cores (Reconstructor::evaluate). Throws
// std::invalid_argument (one line) for an invalid grid (sizes as in grid_over, spacing not finite
// and > 0, origin not finite), a volume of another lattice or one too small for the stencil,
// std::out_of_range (one line) when a grid point lies outside evaluable_region(volume, f): the
// volume never invents data, and std::domain_error (one line) when the spline's value is not finite
// at a grid point (finite samples whose sum overflows, or non-finite samples the reader was told to
// allow).
template <class T>
CartesianVolume<T> resample(const LatticeVolume<T>& volume, const SplineFilter& f,
                            const CartesianGrid& grid);

// A block of a grid's points, begin <= (i, j, k) < end, for chunked work (the Python module's
// dask resampling evaluates one block per task).
struct GridBlock {
  Sizes begin{}, end{};
};
// resample() at the points of one block only: each value bit for bit the one the whole grid
// gets (the point is the grid's origin + index * spacing with the grid's own index), as a
// CartesianVolume of the block's sizes whose origin is the block's first point. Throws as
// resample(), and std::invalid_argument (one line) for a block that is empty or not inside the
// grid.
template <class T>
CartesianVolume<T> resample(const LatticeVolume<T>& volume, const SplineFilter& f,
                            const CartesianGrid& grid, const GridBlock& block);
// resample() with another evaluator of the same spline on many points (the GL device's,
// runtime/gl): it fills values for points as Reconstructor::evaluate does, and throws as it.
template <class T>
using BatchEvaluate = std::function<void(std::span<const Vec3> points, std::span<T> values)>;
template <class T>
CartesianVolume<T> resample(const LatticeVolume<T>& volume, const SplineFilter& f,
                            const CartesianGrid& grid, const GridBlock& block,
                            const BatchEvaluate<T>& evaluate);
// Subsampling onto another lattice (boxrecon subsample: a Cartesian scan onto BCC, as in the
// paper's Fig. 10). The grid of `lattice` at spacing h (sample (c, i, j, k) at
// o + h (d i + off_c)) with as many coset cells per axis as fit in `box`, centred in it. Throws
// std::invalid_argument (one line) for h not finite and > 0, a box that is not finite or holds no
// sample on some axis, or more samples than a LatticeVolume holds.
LatticeGrid lattice_grid_in(const CosetLattice& lattice, const Box& box, double h);
// The number of samples of lattice_grid_in(lattice, box, h).
std::uint64_t lattice_grid_count(const CosetLattice& lattice, const Box& box, double h);
// The spacing h whose lattice_grid_in(lattice, box, h) holds the sample count nearest `count`
// (ties: the larger count). Throws std::invalid_argument for count < 1 or not finite.
double spacing_for_count(const CosetLattice& lattice, const Box& box, double count);

// How much of a long evaluation is done, in [0, 1], after each batch (apps show it on a terminal).
using ProgressReport = std::function<void(double done)>;

// The spline of f on `volume` (prefilter it first for quasi-interpolation) at every sample of
// `grid`, evaluated on all cores, or by `evaluate` when it is set (as resample's): a volume on the
// grid's lattice. The grid lies in the volume's world frame (no to_volume: lattice volumes are
// axis-aligned). Throws as resample does: std::out_of_range (one line, naming both boxes) when a
// sample lies outside evaluable_region(volume, f), before any evaluation. `progress`, when set,
// is called after each batch of whole k-slabs.
template <class T>
LatticeVolume<T> resample_to_lattice(const LatticeVolume<T>& volume, const SplineFilter& f,
                                     const LatticeGrid& grid,
                                     const BatchEvaluate<T>& evaluate = BatchEvaluate<T>{},
                                     const ProgressReport& progress = ProgressReport{});

extern template Box evaluable_region<float>(const LatticeVolume<float>&, const SplineFilter&);
extern template Box evaluable_region<double>(const LatticeVolume<double>&, const SplineFilter&);
extern template Box default_box<float>(const LatticeVolume<float>&, const SplineFilter&);
extern template Box default_box<double>(const LatticeVolume<double>&, const SplineFilter&);
extern template CartesianVolume<float> resample<float>(const LatticeVolume<float>&,
                                                       const SplineFilter&, const CartesianGrid&);
extern template CartesianVolume<double> resample<double>(const LatticeVolume<double>&,
                                                         const SplineFilter&, const CartesianGrid&);
extern template CartesianVolume<float> resample<float>(const LatticeVolume<float>&,
                                                       const SplineFilter&, const CartesianGrid&,
                                                       const GridBlock&);
extern template CartesianVolume<double> resample<double>(const LatticeVolume<double>&,
                                                         const SplineFilter&, const CartesianGrid&,
                                                         const GridBlock&);
extern template CartesianVolume<float> resample<float>(const LatticeVolume<float>&,
                                                       const SplineFilter&, const CartesianGrid&,
                                                       const GridBlock&,
                                                       const BatchEvaluate<float>&);
extern template CartesianVolume<double> resample<double>(const LatticeVolume<double>&,
                                                         const SplineFilter&, const CartesianGrid&,
                                                         const GridBlock&,
                                                         const BatchEvaluate<double>&);
extern template LatticeVolume<float> resample_to_lattice<float>(const LatticeVolume<float>&,
                                                                const SplineFilter&,
                                                                const LatticeGrid&,
                                                                const BatchEvaluate<float>&,
                                                                const ProgressReport&);
extern template LatticeVolume<double> resample_to_lattice<double>(const LatticeVolume<double>&,
                                                                  const SplineFilter&,
                                                                  const LatticeGrid&,
                                                                  const BatchEvaluate<double>&,
                                                                  const ProgressReport&);

}  // namespace boxgen::runtime
