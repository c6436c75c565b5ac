#include "runtime/resample.h"

#include <fmt/format.h>

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

#include "runtime/reconstruction.h"

namespace boxgen::runtime {

namespace {

// "[x0, x1] x [y0, y1] x [z0, z1]", for messages.
std::string describe(const Box& b) {
  return fmt::format("[{}, {}] x [{}, {}] x [{}, {}]", b.min[0], b.max[0], b.min[1], b.max[1],
                     b.min[2], b.max[2]);
}

// The evaluable region in lattice coordinates: lo <= x < hi per axis (may be empty).
struct LatticeRegion {
  Vec3 lo, hi;
};

template <class T>
LatticeRegion lattice_region(const LatticeVolume<T>& volume, const SplineFilter& f) {
  f.check_lattice(volume.lattice());
  const StencilReach reach = f.reach();
  const int d = volume.period();
  LatticeRegion region;
  for (int a = 0; a < 3; ++a) {
    // floor(x + c) + lo >= 0 and floor(x + c) + hi <= d N - 1, with floor(x + c) an integer.
    region.lo[a] = -reach.lo[a] - reach.centre[a];
    region.hi[a] = static_cast<double>(d) * volume.sizes()[a] - reach.hi[a] - reach.centre[a];
    if (region.hi[a] <= region.lo[a]) {
      const int needed = (reach.hi[a] - reach.lo[a]) / d + 1;  // smallest N with d N > hi - lo
      throw std::invalid_argument(fmt::format(
          "{} volume of {} x {} x {} x {} samples is too small for the {} stencil (it needs at "
          "least {} samples per coset on axis {})",
          volume.lattice().label(), volume.coset_count(), volume.sizes()[0], volume.sizes()[1],
          volume.sizes()[2], f.name(), needed, a));
    }
  }
  return region;
}

// The rounding guard of default_box, in lattice units, for the lattice box [lo, hi] of a volume
// with this origin and spacing. A grid point on a face reaches the evaluator through
// world = origin + i * spacing, lattice = (world - o) / h (double), a cast to T and + c (in T):
// each step errs by a few ulps of the magnitudes involved. 16 ulps of each bound them all.
template <class T>
double rounding_guard(const Vec3& lo, const Vec3& hi, const Vec3& origin, const Vec3& spacing) {
  double lattice_extent = 0, world_extent = 0;
  for (int a = 0; a < 3; ++a) {
    lattice_extent = std::max({lattice_extent, std::abs(lo[a]), std::abs(hi[a])});
    world_extent = std::max(world_extent, std::abs(origin[a]) / spacing[a]);
  }
  return 16 * (std::numeric_limits<T>::epsilon() * (lattice_extent + 2) +
               std::numeric_limits<double>::epsilon() * (world_extent + lattice_extent + 2));
}

// A volume with the grid's geometry, its values not yet allocated. Throws std::invalid_argument
// (one line) for sizes outside [2, kMaxGridSize] or above kMaxGridPoints in all, a non-finite
// origin, or a spacing that is not finite and > 0.
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

// Grid point (i, j, k) of the whole grid (the one formula: a block's points are the grid's).
Vec3 grid_point(const CartesianGrid& grid, int i, int j, int k) noexcept {
  return {grid.origin[0] + i * grid.spacing[0], grid.origin[1] + j * grid.spacing[1],
          grid.origin[2] + k * grid.spacing[2]};
}

// The grid point (i, j, k) in the volume's frame, where it is evaluated.
Vec3 volume_point(const CartesianGrid& grid, int i, int j, int k) noexcept {
  const Vec3 p = grid_point(grid, i, j, k);
  return grid.to_volume ? grid.to_volume->apply(p) : p;
}

// out.values (allocated here) from the spline at the block's grid points, whole z-slices of the
// block per batch (about 2^16 points): all cores at work, bounded scratch memory. A point within
// rounding of the region's face that still fails names its slices; a value that is not finite is
// an error naming its point.
template <class T>
void fill_by_slices(CartesianVolume<T>& out, const CartesianGrid& grid, const GridBlock& block,
                    const Reconstructor<T>& spline, const BatchEvaluate<T>& evaluate) {
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
        for (int i = 0; i < n[0]; ++i)
          points.push_back(
              volume_point(grid, block.begin[0] + i, block.begin[1] + j, block.begin[2] + k));
    const std::span<T> values(out.values.data() + out.index(0, 0, k0), points.size());
    try {
      if (evaluate)
        evaluate(points, values);
      else
        spline.evaluate(points, values);
    } catch (const std::out_of_range& e) {
      throw std::out_of_range(fmt::format("resampling grid slices z = {}..{}: {}",
                                          block.begin[2] + k0, block.begin[2] + k1 - 1, e.what()));
    }
    spline.require_finite(points, values);
  }
}

}  // namespace

template <class T>
Box evaluable_region(const LatticeVolume<T>& volume, const SplineFilter& f) {
  const LatticeRegion region = lattice_region(volume, f);
  return {volume.to_world(region.lo), volume.to_world(region.hi)};
}

template <class T>
Box default_box(const LatticeVolume<T>& volume, const SplineFilter& f) {
  const LatticeRegion region = lattice_region(volume, f);
  const double guard =
      rounding_guard<T>(region.lo, region.hi, volume.origin(), volume.axis_spacing());
  Vec3 lo, hi;
  for (int a = 0; a < 3; ++a) {
    lo[a] = region.lo[a] + guard;
    hi[a] = region.hi[a] - guard;
    if (!(lo[a] < hi[a]))
      throw std::invalid_argument(fmt::format(
          "{} volume of {} x {} x {} x {} samples is too small for the {} stencil on axis {}",
          volume.lattice().label(), volume.coset_count(), volume.sizes()[0], volume.sizes()[1],
          volume.sizes()[2], f.name(), a));
  }
  return {volume.to_world(lo), volume.to_world(hi)};
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
CartesianVolume<T> resample(const LatticeVolume<T>& volume, const SplineFilter& f,
                            const CartesianGrid& grid) {
  return resample(volume, f, grid, GridBlock{{0, 0, 0}, grid.sizes});
}

template <class T>
CartesianVolume<T> resample(const LatticeVolume<T>& volume, const SplineFilter& f,
                            const CartesianGrid& grid, const GridBlock& block) {
  return resample(volume, f, grid, block, BatchEvaluate<T>{});
}

template <class T>
CartesianVolume<T> resample(const LatticeVolume<T>& volume, const SplineFilter& f,
                            const CartesianGrid& grid, const GridBlock& block,
                            const BatchEvaluate<T>& evaluate) {
  CartesianVolume<T> out = empty_grid_volume<T>(grid);
  for (int a = 0; a < 3; ++a)
    if (!(0 <= block.begin[a] && block.begin[a] < block.end[a] && block.end[a] <= grid.sizes[a]))
      throw std::invalid_argument(
          fmt::format("grid block [{}, {}) on axis {} is empty or outside the grid's {} points",
                      block.begin[a], block.end[a], a, grid.sizes[a]));
  for (int a = 0; a < 3; ++a) out.sizes[a] = block.end[a] - block.begin[a];
  out.origin = grid_point(grid, block.begin[0], block.begin[1], block.begin[2]);
  // The eight corners of the block, computed as the evaluation will see them, must lie in the
  // evaluable region; then every point between them does (the region is a box, the block's image
  // in the volume's frame a parallelepiped spanned by its corners).
  const LatticeRegion region = lattice_region(volume, f);
  Box corners{};
  bool inside = true;
  for (int corner = 0; corner < 8; ++corner) {
    const Sizes at{(corner & 1) ? block.end[0] - 1 : block.begin[0],
                   (corner & 2) ? block.end[1] - 1 : block.begin[1],
                   (corner & 4) ? block.end[2] - 1 : block.begin[2]};
    const Vec3 p = volume_point(grid, at[0], at[1], at[2]);
    const Vec3 x = volume.to_lattice(p);
    for (int a = 0; a < 3; ++a) {
      corners.min[a] = corner == 0 ? p[a] : std::min(corners.min[a], p[a]);
      corners.max[a] = corner == 0 ? p[a] : std::max(corners.max[a], p[a]);
      inside = inside && x[a] >= region.lo[a] && x[a] < region.hi[a];
    }
  }
  if (!inside)
    throw std::out_of_range(fmt::format(
        "resampling grid {} leaves the region where the {} stencil lies inside the volume, {}",
        describe(corners), f.name(),
        describe({volume.to_world(region.lo), volume.to_world(region.hi)})));
  fill_by_slices(out, grid, block, Reconstructor<T>(volume, f), evaluate);
  return out;
}

namespace {

// Coset cells per axis of lattice_grid_in, and the lowest and highest offset on each axis.
struct FittedAxes {
  std::array<std::int64_t, 3> cells;
  Vec3 lowest, highest;
};

FittedAxes fit_axes(const CosetLattice& lattice, const Box& box, double h) {
  if (!std::isfinite(h) || h <= 0)
    throw std::invalid_argument(fmt::format("lattice spacing {} must be finite and > 0", h));
  FittedAxes fit{};
  const double d = lattice.period();
  for (int a = 0; a < 3; ++a) {
    if (!std::isfinite(box.min[a]) || !std::isfinite(box.max[a]) || !(box.min[a] <= box.max[a]))
      throw std::invalid_argument(fmt::format("box {} is not finite or empty", describe(box)));
    fit.lowest[a] = d;
    fit.highest[a] = 0;
    for (const Offset& o : lattice.offsets()) {
      fit.lowest[a] = std::min(fit.lowest[a], static_cast<double>(o[a]));
      fit.highest[a] = std::max(fit.highest[a], static_cast<double>(o[a]));
    }
    // Every coset's N cells span h (highest - lowest + d (N - 1)) <= the box's width.
    const double room = (box.max[a] - box.min[a]) / h - (fit.highest[a] - fit.lowest[a]);
    const double cells = room < 0 ? 0 : std::floor(room / d) + 1;
    if (cells < 1)
      throw std::invalid_argument(
          fmt::format("no {} sample at spacing {} fits in the box {} on axis {}", lattice.label(),
                      h, describe(box), a));
    fit.cells[a] = cells > 1e12 ? std::int64_t{1} << 40 : static_cast<std::int64_t>(cells);
  }
  return fit;
}

}  // namespace

std::uint64_t lattice_grid_count(const CosetLattice& lattice, const Box& box, double h) {
  const FittedAxes fit = fit_axes(lattice, box, h);
  double count = lattice.coset_count();
  for (std::int64_t n : fit.cells) count *= static_cast<double>(n);
  return count > 1e18 ? std::uint64_t{1} << 60 : static_cast<std::uint64_t>(count);
}

LatticeGrid lattice_grid_in(const CosetLattice& lattice, const Box& box, double h) {
  const FittedAxes fit = fit_axes(lattice, box, h);
  LatticeGrid grid{lattice, {}, h, {}};
  const double d = lattice.period();
  for (int a = 0; a < 3; ++a) {
    if (fit.cells[a] > LatticeVolume<double>::kMaxSize)
      throw std::invalid_argument(
          fmt::format("spacing {} gives {} samples per coset on axis {} (at most {})", h,
                      fit.cells[a], a, LatticeVolume<double>::kMaxSize));
    grid.sizes[a] = static_cast<int>(fit.cells[a]);
    const double span = h * (fit.highest[a] - fit.lowest[a] + d * (grid.sizes[a] - 1));
    // Centred: the slack is split between the two sides; lattice point 0 sits `lowest` below the
    // first sample.
    grid.origin[a] = box.min[a] + 0.5 * ((box.max[a] - box.min[a]) - span) - h * fit.lowest[a];
  }
  if (lattice_grid_count(lattice, box, h) > LatticeVolume<double>::kMaxSamples)
    throw std::invalid_argument(fmt::format("spacing {} gives too many samples", h));
  return grid;
}

double spacing_for_count(const CosetLattice& lattice, const Box& box, double count) {
  if (!std::isfinite(count) || count < 1)
    throw std::invalid_argument(fmt::format("sample count {} must be finite and >= 1", count));
  double volume = 1;
  for (int a = 0; a < 3; ++a) volume *= box.max[a] - box.min[a];
  // K samples per cube of side d h: the estimate, then bisection on the monotone count.
  const double d = lattice.period();
  const double guess = std::cbrt(lattice.coset_count() * volume / count) / d;
  double more = guess / 8, fewer = guess * 8;  // count(more) > count >= count(fewer)
  const auto fits = [&](double h) {
    try {
      return static_cast<double>(lattice_grid_count(lattice, box, h));
    } catch (const std::invalid_argument&) {
      return 0.0;
    }
  };
  while (fits(more) <= count && more > 1e-300) more /= 2;
  while (fits(fewer) > count) fewer *= 2;
  for (int i = 0; i < 200 && fewer - more > 1e-15 * fewer; ++i) {
    const double mid = 0.5 * (more + fewer);
    (fits(mid) > count ? more : fewer) = mid;
  }
  return count - fits(fewer) <= fits(more) - count ? fewer : more;
}

template <class T>
LatticeVolume<T> resample_to_lattice(const LatticeVolume<T>& volume, const SplineFilter& f,
                                     const LatticeGrid& grid, const BatchEvaluate<T>& evaluate,
                                     const ProgressReport& progress) {
  LatticeVolume<T> out(grid.lattice, grid.sizes, grid.h, grid.origin);
  const Sizes& n = grid.sizes;
  const int k_count = out.coset_count();
  // The samples' bounding box (each coset's corner samples), as the evaluation will see them,
  // must lie in the evaluable region: one clear line before any work, as resample's.
  const LatticeRegion region = lattice_region(volume, f);
  Box extent{};
  bool inside = true;
  for (int c = 0; c < k_count; ++c)
    for (int corner = 0; corner < 8; ++corner) {
      const Vec3 p = out.sample_position(c, (corner & 1) ? n[0] - 1 : 0,
                                         (corner & 2) ? n[1] - 1 : 0, (corner & 4) ? n[2] - 1 : 0);
      const Vec3 x = volume.to_lattice(p);
      const bool first = c == 0 && corner == 0;
      for (int a = 0; a < 3; ++a) {
        extent.min[a] = first ? p[a] : std::min(extent.min[a], p[a]);
        extent.max[a] = first ? p[a] : std::max(extent.max[a], p[a]);
        inside = inside && x[a] >= region.lo[a] && x[a] < region.hi[a];
      }
    }
  if (!inside)
    throw std::out_of_range(fmt::format(
        "the {} samples {} leave the region where the {} stencil lies inside the volume, {}",
        grid.lattice.label(), describe(extent), f.name(),
        describe({volume.to_world(region.lo), volume.to_world(region.hi)})));
  const Reconstructor<T> spline(volume, f);
  std::vector<Vec3> points;
  // Whole k-slabs of about 2^16 samples per batch: all cores at work, bounded scratch memory.
  const std::size_t slab = static_cast<std::size_t>(k_count) * static_cast<std::size_t>(n[0]) *
                           static_cast<std::size_t>(n[1]);
  const int per_batch = static_cast<int>(std::max<std::size_t>(1, (std::size_t{1} << 16) / slab));
  for (int k0 = 0; k0 < n[2]; k0 += per_batch) {
    const int k1 = std::min(n[2], k0 + per_batch);
    points.clear();
    for (int k = k0; k < k1; ++k)
      for (int j = 0; j < n[1]; ++j)
        for (int i = 0; i < n[0]; ++i)
          for (int c = 0; c < k_count; ++c) points.push_back(out.sample_position(c, i, j, k));
    const std::span<T> values(out.samples().data() + out.index(0, 0, 0, k0), points.size());
    if (evaluate)
      evaluate(points, values);
    else
      spline.evaluate(points, values);
    spline.require_finite(points, values);
    if (progress) progress(static_cast<double>(k1) / n[2]);
  }
  return out;
}

template Box evaluable_region<float>(const LatticeVolume<float>&, const SplineFilter&);
template Box evaluable_region<double>(const LatticeVolume<double>&, const SplineFilter&);
template Box default_box<float>(const LatticeVolume<float>&, const SplineFilter&);
template Box default_box<double>(const LatticeVolume<double>&, const SplineFilter&);
template CartesianVolume<float> resample<float>(const LatticeVolume<float>&, const SplineFilter&,
                                                const CartesianGrid&);
template CartesianVolume<double> resample<double>(const LatticeVolume<double>&, const SplineFilter&,
                                                  const CartesianGrid&);
template CartesianVolume<float> resample<float>(const LatticeVolume<float>&, const SplineFilter&,
                                                const CartesianGrid&, const GridBlock&);
template CartesianVolume<double> resample<double>(const LatticeVolume<double>&, const SplineFilter&,
                                                  const CartesianGrid&, const GridBlock&);
template CartesianVolume<float> resample<float>(const LatticeVolume<float>&, const SplineFilter&,
                                                const CartesianGrid&, const GridBlock&,
                                                const BatchEvaluate<float>&);
template CartesianVolume<double> resample<double>(const LatticeVolume<double>&, const SplineFilter&,
                                                  const CartesianGrid&, const GridBlock&,
                                                  const BatchEvaluate<double>&);
template LatticeVolume<float> resample_to_lattice<float>(const LatticeVolume<float>&,
                                                         const SplineFilter&, const LatticeGrid&,
                                                         const BatchEvaluate<float>&,
                                                         const ProgressReport&);
template LatticeVolume<double> resample_to_lattice<double>(const LatticeVolume<double>&,
                                                           const SplineFilter&, const LatticeGrid&,
                                                           const BatchEvaluate<double>&,
                                                           const ProgressReport&);

}  // namespace boxgen::runtime
