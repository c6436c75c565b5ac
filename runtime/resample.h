// Resampling a BCC volume onto a Cartesian grid (for 3D Slicer, ParaView, unu: nrrd_io.h writes
// the result), and the default grid: the largest box in which the chosen filter can be evaluated.
//
// Where a filter can be evaluated: the generated evaluator of a filter with centre shift c
// (kCentre: the uncentred frame u = x + c has its knot planes at integer levels) fetches, for a
// point x in lattice coordinates, a stencil that depends only on the unit cube k = floor(x + c)
// holding x and on the cell of that cube. Over all cells of all cubes the fetched lattice points
// j satisfy  k_a + lo_a <= j_a <= k_a + hi_a  (StencilReach: the generator publishes lo and hi
// with each evaluator as kStencilReachLo/Hi, and tests/runtime checks them against the fetches).
// The volume holds 0 <= j_a <= 2 N_a - 1, and every cube type occurs on every face of a box at
// least two units wide, so the exact region where every point evaluates is the half-open box
//   -lo_a - c_a  <=  x_a  <  2 N_a - hi_a - c_a        (lattice coordinates, per axis a).
// The default box is that region, closed, and pulled in on each side by a rounding guard g (a few
// ulps of the coordinates, in T and in double: see default_box) so that a grid point on its faces
// still lands in the right unit cube after world -> lattice conversion. Growing it by one grid
// step (anything more than g) on any side leaves the region.
#pragma once
#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <span>
#include <stdexcept>
#include <string>
#include <vector>

#include <fmt/format.h>

#include "runtime/bcc_volume.h"
#include "runtime/cartesian_volume.h"
#include "runtime/reconstruction.h"

namespace boxgen::runtime {

// An axis-aligned box of world points, min <= x <= max.
struct Box {
  Vec3 min{}, max{};
};

// The region where f can be evaluated on `volume` (the half-open box above), in world
// coordinates: every point with min <= x < max (componentwise) evaluates. Throws
// std::invalid_argument (one line) when the volume is too small for the stencil (empty region).
template <class T>
Box evaluable_region(const BccVolume<T>& volume, Filter f);
// The default resampling box: evaluable_region closed and pulled in by the rounding guard.
// Throws std::invalid_argument (one line) when the volume is too small for the stencil.
template <class T>
Box default_box(const BccVolume<T>& volume, Filter f);

// Geometry of a Cartesian grid (a CartesianVolume without its values).
struct CartesianGrid {
  Sizes sizes{};
  Vec3 spacing{};
  Vec3 origin{};
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
// grid points, evaluated on all cores (Reconstructor::evaluate). Throws std::invalid_argument
// (one line) for an invalid grid (sizes as in grid_over, spacing not finite and > 0, origin not
// finite) or a volume too small for the stencil, and std::out_of_range (one line) when a grid
// point lies outside evaluable_region(volume, f): the volume never invents data.
template <class T>
CartesianVolume<T> resample(const BccVolume<T>& volume, Filter f, const CartesianGrid& grid);

// Shared by every resample(): the BCC one below and lattice_filters.h's for any registry filter.
// "[x0, x1] x [y0, y1] x [z0, z1]", for messages.
std::string describe(const Box& b);
// A volume with the grid's geometry, its values not yet allocated. Throws std::invalid_argument
// (one line) for sizes outside [2, kMaxGridSize] or above kMaxGridPoints in all, a non-finite
// origin, or a spacing that is not finite and > 0.
template <class T>
CartesianVolume<T> empty_grid_volume(const CartesianGrid& grid);
// The rounding guard of default_box, in lattice units, for the lattice box [lo, hi] of a volume
// with this origin and spacing. A grid point on a face reaches the evaluator through
// world = origin + i * spacing, lattice = (world - o) / h (double), a cast to T and + c (in T):
// each step errs by a few ulps of the magnitudes involved. 16 ulps of each bound them all.
template <class T>
double rounding_guard(const Vec3& lo, const Vec3& hi, const Vec3& origin, double spacing) {
  double lattice_extent = 0, world_extent = 0;
  for (int a = 0; a < 3; ++a) {
    lattice_extent = std::max({lattice_extent, std::abs(lo[a]), std::abs(hi[a])});
    world_extent = std::max(world_extent, std::abs(origin[a]) / spacing);
  }
  return 16 * (std::numeric_limits<T>::epsilon() * (lattice_extent + 2) +
               std::numeric_limits<double>::epsilon() * (world_extent + lattice_extent + 2));
}

// Throws std::out_of_range (one line) unless the grid's first and last points (`corners`, world),
// at the lattice coordinates `first` and `last` that evaluation sees, lie in [lo, hi), the lattice
// box where the stencil of `filter` fits (`region` in world coordinates).
void require_grid_in_region(const Box& corners, const Vec3& first, const Vec3& last, const Vec3& lo,
                            const Vec3& hi, const std::string& filter, const Box& region);

// The grid's first and last points in world coordinates.
template <class T>
Box grid_corners(const CartesianVolume<T>& out) {
  const Sizes& n = out.sizes;
  return {out.position(0, 0, 0), out.position(n[0] - 1, n[1] - 1, n[2] - 1)};
}

// out.values (allocated here) from spline.evaluate(points, values), whole z-slices per batch (about
// 2^16 points): all cores at work, bounded scratch memory. A point within rounding of the region's
// face that still fails names its slices.
template <class T, class Spline>
void fill_by_slices(CartesianVolume<T>& out, const Spline& spline) {
  const Sizes& n = out.sizes;
  const std::size_t slice = static_cast<std::size_t>(n[0]) * static_cast<std::size_t>(n[1]);
  out.values.resize(slice * static_cast<std::size_t>(n[2]));
  const int slices_per_batch =
      static_cast<int>(std::max<std::size_t>(1, (std::size_t{1} << 16) / slice));
  std::vector<Vec3> points;
  for (int k0 = 0; k0 < n[2]; k0 += slices_per_batch) {
    const int k1 = std::min(n[2], k0 + slices_per_batch);
    points.clear();
    for (int k = k0; k < k1; ++k)
      for (int j = 0; j < n[1]; ++j)
        for (int i = 0; i < n[0]; ++i) points.push_back(out.position(i, j, k));
    const std::span<T> values(out.values.data() + out.index(0, 0, k0), points.size());
    try {
      spline.evaluate(points, values);
    } catch (const std::out_of_range& e) {
      throw std::out_of_range(
          fmt::format("resampling grid slices z = {}..{}: {}", k0, k1 - 1, e.what()));
    }
  }
}

extern template CartesianVolume<float> empty_grid_volume<float>(const CartesianGrid&);
extern template CartesianVolume<double> empty_grid_volume<double>(const CartesianGrid&);
extern template Box evaluable_region<float>(const BccVolume<float>&, Filter);
extern template Box evaluable_region<double>(const BccVolume<double>&, Filter);
extern template Box default_box<float>(const BccVolume<float>&, Filter);
extern template Box default_box<double>(const BccVolume<double>&, Filter);
extern template CartesianVolume<float> resample<float>(const BccVolume<float>&, Filter,
                                                       const CartesianGrid&);
extern template CartesianVolume<double> resample<double>(const BccVolume<double>&, Filter,
                                                         const CartesianGrid&);

}  // namespace boxgen::runtime
