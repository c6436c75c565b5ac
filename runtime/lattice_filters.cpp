#include "runtime/lattice_filters.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <exception>
#include <limits>
#include <stdexcept>
#include <string>
#include <vector>

#include "generated/registry.hpp"
#include "runtime/lattice_reconstruction.h"

namespace boxgen::runtime {

namespace generated = boxgen::generated;

// ---------------------------------------------------------------------------------------------
// RegistryFilter

RegistryFilter RegistryFilter::parse(std::string_view name) {
  for (int i = 0; i < generated::kFilterCount; ++i)
    if (name == generated::kFilterNames[i]) return RegistryFilter(i);
  throw std::invalid_argument(
      fmt::format("unknown filter '{}': expected {}", name.substr(0, 40), names()));
}

int RegistryFilter::count() { return generated::kFilterCount; }

RegistryFilter RegistryFilter::at(int index) {
  if (index < 0 || index >= generated::kFilterCount)
    throw std::invalid_argument(fmt::format("no registry filter {}", index));
  return RegistryFilter(index);
}

std::string RegistryFilter::names() {
  std::string out;
  for (int i = 0; i < generated::kFilterCount; ++i) {
    if (i > 0) out += i + 1 == generated::kFilterCount ? " or " : ", ";
    out += generated::kFilterNames[i];
  }
  return out;
}

const char* RegistryFilter::name() const { return generated::kFilterNames[index_]; }

CosetLattice RegistryFilter::lattice() const {
  return generated::with_filter(
      index_, [](auto entry) { return filter_lattice<typename decltype(entry)::Traits>(); });
}

StencilReach RegistryFilter::reach() const {
  return generated::with_filter(
      index_, [](auto entry) { return published_reach<typename decltype(entry)::Traits>(); });
}

DiscreteFilter RegistryFilter::prefilter(PrefilterChoice q) const {
  if (q == PrefilterChoice::None) return {{{0, 0, 0}, 1.0}};
  return generated::with_filter(index_, [&](auto entry) {
    return q == PrefilterChoice::Q1 ? prefilter_from(entry.q1) : prefilter_from(entry.q2);
  });
}

int RegistryFilter::approximation_order() const {
  return generated::with_filter(index_, [](auto entry) { return entry.approximation_order; });
}

int RegistryFilter::required_margin(PrefilterChoice q) const {
  // A margin of m coset cells puts [-1,1] at lattice coordinates [d m, d (m + N - 1)] in a volume
  // of N + 2m cells per coset: evaluation (the region in the header) needs d m >= -lo - c and
  // d m > hi + c - d; half a coset cell of slack for rounding at the faces (on BCC this is
  // required_margin of reconstruction.cpp exactly). Then the prefilter's own reach.
  const CosetLattice l = lattice();
  const StencilReach r = reach();
  const int d = l.period();
  double need = 0;
  for (int a = 0; a < 3; ++a)
    need = std::max({need, -r.lo[a] - r.centre[a], r.hi[a] + r.centre[a] - d});
  const int reconstruction = static_cast<int>(std::ceil(need / d + 0.5));
  if (q == PrefilterChoice::None) return reconstruction;
  const PrefilterShrink s = prefilter_shrink(prefilter(q), l);
  int shrink = 0;
  for (int a = 0; a < 3; ++a) shrink = std::max({shrink, s.lower[a], s.upper[a]});
  return reconstruction + shrink;
}

bool RegistryFilter::has_bcc_filter() const noexcept {
  for (const Filter f : {Filter::M7, Filter::M8, Filter::M12})
    if (static_cast<int>(f) == index_) return true;
  return false;
}

Filter RegistryFilter::bcc_filter() const {
  if (!has_bcc_filter())
    throw std::invalid_argument(fmt::format("filter {} has no BCC Reconstructor", name()));
  const auto f = static_cast<Filter>(index_);
  if (std::strcmp(filter_name(f), name()) != 0) throw std::logic_error("registry order");
  return f;
}

void RegistryFilter::check_lattice(const CosetLattice& volume_lattice) const {
  generated::with_filter(index_, [&](auto entry) {
    require_filter_lattice<typename decltype(entry)::Traits>(volume_lattice);
  });
}

// ---------------------------------------------------------------------------------------------
// Regions

namespace {

struct LatticeRegion {
  Vec3 lo, hi;
};

template <class T>
LatticeRegion lattice_region(const LatticeVolume<T>& volume, RegistryFilter f) {
  f.check_lattice(volume.lattice());
  const StencilReach reach = f.reach();
  const int d = volume.period();
  LatticeRegion region;
  for (int a = 0; a < 3; ++a) {
    region.lo[a] = -reach.lo[a] - reach.centre[a];
    region.hi[a] = static_cast<double>(d) * volume.sizes()[a] - reach.hi[a] - reach.centre[a];
    if (region.hi[a] <= region.lo[a])
      throw std::invalid_argument(fmt::format(
          "{} volume of {} x {} x {} x {} samples is too small for the {} stencil on axis {}",
          volume.lattice().name(), volume.coset_count(), volume.sizes()[0], volume.sizes()[1],
          volume.sizes()[2], f.name(), a));
  }
  return region;
}

}  // namespace

template <class T>
Box evaluable_region(const LatticeVolume<T>& volume, RegistryFilter f) {
  const LatticeRegion r = lattice_region(volume, f);
  return {volume.to_world(r.lo), volume.to_world(r.hi)};
}

template <class T>
Box default_box(const LatticeVolume<T>& volume, RegistryFilter f) {
  const LatticeRegion region = lattice_region(volume, f);
  const double guard = rounding_guard<T>(region.lo, region.hi, volume.origin(), volume.spacing());
  Vec3 lo, hi;
  for (int a = 0; a < 3; ++a) {
    lo[a] = region.lo[a] + guard;
    hi[a] = region.hi[a] - guard;
    if (!(lo[a] < hi[a]))
      throw std::invalid_argument(
          fmt::format("{} volume is too small for the {} stencil on axis {}",
                      volume.lattice().name(), f.name(), a));
  }
  return {volume.to_world(lo), volume.to_world(hi)};
}

// ---------------------------------------------------------------------------------------------
// RegistryReconstructor

template <class T>
RegistryReconstructor<T>::RegistryReconstructor(const LatticeVolume<T>& volume, RegistryFilter f) {
  f.check_lattice(volume.lattice());
  // The registry's filters have SIMD kernels: the batch path uses them (emitted_spline.h).
  path_ = generated::with_filter(
      f.index(), [&](auto entry) -> std::shared_ptr<const EvaluationPath<T>> {
        using Tr = typename decltype(entry)::Traits;
        return std::make_shared<EmittedSplinePath<Tr, LatticeStencils<Tr, T>>>(
            LatticeStencils<Tr, T>(volume), f.index());
      });
}

template <class T>
T RegistryReconstructor<T>::value(const Vec3& world, Vec3* gradient, Hessian* hessian) const {
  return path_->at(world, gradient, hessian);
}

template <class T>
void RegistryReconstructor<T>::evaluate(std::span<const Vec3> points, std::span<T> values,
                                        std::span<Vec3> gradients,
                                        std::span<Hessian> hessians) const {
  path_->batch(points, values, gradients, hessians);
}

// ---------------------------------------------------------------------------------------------
// Resampling

template <class T>
CartesianVolume<T> resample(const LatticeVolume<T>& volume, RegistryFilter f,
                            const CartesianGrid& grid) {
  CartesianVolume<T> out = empty_grid_volume<T>(grid);
  // First and last grid points inside the evaluable region: then every point between them is.
  const LatticeRegion region = lattice_region(volume, f);
  const Box corners = grid_corners(out);
  require_grid_in_region(corners, volume.to_lattice(corners.min), volume.to_lattice(corners.max),
                         region.lo, region.hi, std::string(f.name()),
                         {volume.to_world(region.lo), volume.to_world(region.hi)});
  fill_by_slices(out, RegistryReconstructor<T>(volume, f));
  return out;
}

template Box evaluable_region<float>(const LatticeVolume<float>&, RegistryFilter);
template Box evaluable_region<double>(const LatticeVolume<double>&, RegistryFilter);
template Box default_box<float>(const LatticeVolume<float>&, RegistryFilter);
template Box default_box<double>(const LatticeVolume<double>&, RegistryFilter);
template class RegistryReconstructor<float>;
template class RegistryReconstructor<double>;
template CartesianVolume<float> resample<float>(const LatticeVolume<float>&, RegistryFilter,
                                                const CartesianGrid&);
template CartesianVolume<double> resample<double>(const LatticeVolume<double>&, RegistryFilter,
                                                  const CartesianGrid&);

}  // namespace boxgen::runtime
