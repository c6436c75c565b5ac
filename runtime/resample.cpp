#include "runtime/resample.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <limits>
#include <span>
#include <stdexcept>
#include <vector>

namespace boxgen::runtime {

namespace {

// The evaluable region in lattice coordinates: lo <= x < hi per axis (may be empty).
struct LatticeRegion {
  Vec3 lo, hi;
};

template <class T>
LatticeRegion lattice_region(const BccVolume<T>& volume, Filter f) {
  const StencilReach reach = stencil_reach(f);
  LatticeRegion region;
  for (int a = 0; a < 3; ++a) {
    // floor(x + c) + lo >= 0 and floor(x + c) + hi <= 2N - 1, with floor(x + c) an integer.
    region.lo[a] = -reach.lo[a] - reach.centre[a];
    region.hi[a] = 2.0 * volume.sizes()[a] - reach.hi[a] - reach.centre[a];
    if (region.hi[a] <= region.lo[a]) {
      const int needed = (reach.hi[a] - reach.lo[a]) / 2 + 1;  // smallest N with 2N > hi - lo
      throw std::invalid_argument(fmt::format(
          "BCC volume of 2 x {} x {} x {} samples is too small for the {} stencil (it needs at "
          "least {} samples per coset on axis {})",
          volume.sizes()[0], volume.sizes()[1], volume.sizes()[2], filter_name(f), needed, a));
    }
  }
  return region;
}

template <class T>
Box to_world(const BccVolume<T>& volume, const Vec3& lo, const Vec3& hi) {
  return {volume.to_world(lo), volume.to_world(hi)};
}

}  // namespace

std::string describe(const Box& b) {
  return fmt::format("[{}, {}] x [{}, {}] x [{}, {}]", b.min[0], b.max[0], b.min[1], b.max[1],
                     b.min[2], b.max[2]);
}

template <class T>
CartesianVolume<T> empty_grid_volume(const CartesianGrid& grid) {
  std::uint64_t count = 1;
  for (int a = 0; a < 3; ++a) {
    if (grid.sizes[a] < 2 || grid.sizes[a] > kMaxGridSize)
      throw std::invalid_argument(
          fmt::format("Cartesian grid of {} x {} x {} points: each size must be in 2..{}",
                      grid.sizes[0], grid.sizes[1], grid.sizes[2], kMaxGridSize));
    count *= static_cast<std::uint64_t>(grid.sizes[a]);
    if (!std::isfinite(grid.spacing[a]) || grid.spacing[a] <= 0 || !std::isfinite(grid.origin[a]))
      throw std::invalid_argument(fmt::format(
          "Cartesian grid spacing and origin must be finite (and spacing > 0) on axis {}", a));
  }
  if (count > kMaxGridPoints)
    throw std::invalid_argument(
        fmt::format("Cartesian grid of {} x {} x {} points is too large (at most {})",
                    grid.sizes[0], grid.sizes[1], grid.sizes[2], kMaxGridPoints));
  CartesianVolume<T> out;
  out.sizes = grid.sizes;
  out.spacing = grid.spacing;
  out.origin = grid.origin;
  return out;
}

void require_grid_in_region(const Box& corners, const Vec3& first, const Vec3& last, const Vec3& lo,
                            const Vec3& hi, const std::string& filter, const Box& region) {
  for (int a = 0; a < 3; ++a)
    if (!(first[a] >= lo[a] && last[a] < hi[a]))
      throw std::out_of_range(fmt::format(
          "resampling grid {} leaves the region where the {} stencil lies inside the volume, {}",
          describe(corners), filter, describe(region)));
}

template <class T>
Box evaluable_region(const BccVolume<T>& volume, Filter f) {
  const LatticeRegion region = lattice_region(volume, f);
  return to_world(volume, region.lo, region.hi);
}

template <class T>
Box default_box(const BccVolume<T>& volume, Filter f) {
  const LatticeRegion region = lattice_region(volume, f);
  const double guard = rounding_guard<T>(region.lo, region.hi, volume.origin(), volume.spacing());
  Vec3 lo, hi;
  for (int a = 0; a < 3; ++a) {
    lo[a] = region.lo[a] + guard;
    hi[a] = region.hi[a] - guard;
    if (!(lo[a] < hi[a]))
      throw std::invalid_argument(fmt::format(
          "BCC volume of 2 x {} x {} x {} samples is too small for the {} stencil on axis {}",
          volume.sizes()[0], volume.sizes()[1], volume.sizes()[2], filter_name(f), a));
  }
  return to_world(volume, lo, hi);
}

CartesianGrid grid_over(const Box& box, Sizes n) {
  std::uint64_t count = 1;
  for (int a = 0; a < 3; ++a) {
    if (n[a] < 2 || n[a] > kMaxGridSize)
      throw std::invalid_argument(
          fmt::format("Cartesian grid of {} x {} x {} points: each size must be in 2..{}", n[0],
                      n[1], n[2], kMaxGridSize));
    count *= static_cast<std::uint64_t>(n[a]);
  }
  if (count > kMaxGridPoints)
    throw std::invalid_argument(
        fmt::format("Cartesian grid of {} x {} x {} points is too large (at most {})", n[0], n[1],
                    n[2], kMaxGridPoints));
  CartesianGrid grid{n, {}, box.min};
  for (int a = 0; a < 3; ++a) {
    if (!std::isfinite(box.min[a]) || !std::isfinite(box.max[a]))
      throw std::invalid_argument(fmt::format("resampling box {} is not finite", describe(box)));
    if (!(box.min[a] < box.max[a]))
      throw std::invalid_argument(
          fmt::format("resampling box {} is empty or degenerate on axis {} (it needs min < max)",
                      describe(box), a));
    grid.spacing[a] = (box.max[a] - box.min[a]) / (n[a] - 1);
    if (!std::isfinite(grid.spacing[a]) || grid.spacing[a] <= 0)
      throw std::invalid_argument(
          fmt::format("resampling box {} gives no usable spacing on axis {}", describe(box), a));
  }
  return grid;
}

template <class T>
CartesianVolume<T> resample(const BccVolume<T>& volume, Filter f, const CartesianGrid& grid) {
  CartesianVolume<T> out = empty_grid_volume<T>(grid);
  // The first and last grid points, computed as the evaluation will see them, must lie in the
  // evaluable region; then every point between them does (the region is a box).
  const LatticeRegion region = lattice_region(volume, f);
  const Box corners = grid_corners(out);
  require_grid_in_region(corners, volume.to_lattice(corners.min), volume.to_lattice(corners.max),
                         region.lo, region.hi, filter_name(f),
                         to_world(volume, region.lo, region.hi));
  fill_by_slices(out, Reconstructor<T>(volume, f));
  return out;
}

template CartesianVolume<float> empty_grid_volume<float>(const CartesianGrid&);
template CartesianVolume<double> empty_grid_volume<double>(const CartesianGrid&);
template Box evaluable_region<float>(const BccVolume<float>&, Filter);
template Box evaluable_region<double>(const BccVolume<double>&, Filter);
template Box default_box<float>(const BccVolume<float>&, Filter);
template Box default_box<double>(const BccVolume<double>&, Filter);
template CartesianVolume<float> resample<float>(const BccVolume<float>&, Filter,
                                                const CartesianGrid&);
template CartesianVolume<double> resample<double>(const BccVolume<double>&, Filter,
                                                  const CartesianGrid&);

}  // namespace boxgen::runtime
