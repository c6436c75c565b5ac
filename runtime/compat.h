// The names of the BCC-only runtime and of the first lattice runtime, kept so that code written
// against them (and the installed example, examples/consumer) still compiles. Each is a thin
// alias or adapter over the one API; nothing in boxgen itself uses them. docs/runtime.md maps
// every old name to the new one.
//
//   BccVolume<T>                  LatticeVolume<T> on CosetLattice::bcc()
//   Filter::M7, M8, M12           SplineFilter::parse("m7") ... (a Filter converts implicitly)
//   RegistryFilter                SplineFilter
//   RegistryReconstructor<T>      Reconstructor<T>
//   LatticeReconstructor<Tr, T>   Reconstructor<T> with emitted_filter<Tr>()
//   BccGrid, cube_grid, sample_bcc, sample_cube   LatticeGrid, cube_lattice_grid, sample_lattice
//   read_bcc_nrrd, write_bcc_nrrd                 read_lattice_nrrd, write_lattice_nrrd
//   parse_filter, filter_name, stencil_reach, prefilter_taps, required_margin
//                                 SplineFilter::parse, name, reach, prefilter, required_margin
#pragma once
#include <filesystem>
#include <stdexcept>
#include <string_view>
#include <utility>
#include <vector>

#include "runtime/emitted_filter.h"
#include "runtime/nrrd_io.h"
#include "runtime/prefilter.h"
#include "runtime/reconstruction.h"
#include "runtime/resample.h"
#include "runtime/sampling.h"

namespace boxgen::runtime {

// A LatticeVolume on the BCC lattice with the offsets (0,0,0) (1,1,1): sample (c, i, j, k) at
// o + h (2i + c, 2j + c, 2k + c).
template <class T>
class BccVolume : public LatticeVolume<T> {
 public:
  BccVolume(Sizes sizes, double h, Vec3 origin)
      : LatticeVolume<T>(CosetLattice::bcc(), sizes, h, origin) {}
  BccVolume(Sizes sizes, double h, Vec3 origin, std::vector<T>&& samples)
      : LatticeVolume<T>(CosetLattice::bcc(), sizes, h, origin, std::move(samples)) {}
  // A lattice volume that is one (prefilter's and read_lattice_nrrd's results); anything else is
  // std::invalid_argument (one line).
  BccVolume(LatticeVolume<T>&& volume)  // NOLINT(google-explicit-constructor)
      : LatticeVolume<T>(checked(std::move(volume))) {}

  static bool is_lattice_point(std::int64_t x, std::int64_t y, std::int64_t z) noexcept {
    return CosetLattice::bcc().contains(x, y, z);
  }

 private:
  static LatticeVolume<T>&& checked(LatticeVolume<T>&& volume) {
    if (!(volume.lattice() == CosetLattice::bcc()))
      throw std::invalid_argument("the volume is on the " + volume.lattice().name() +
                                  " lattice (offsets " + volume.lattice().offsets_text() +
                                  "), not on BCC with offsets (0,0,0) (1,1,1)");
    return std::move(volume);
  }
};

template <class T>
LatticeVolume<T> to_lattice_volume(BccVolume<T>&& volume) {
  return LatticeVolume<T>(std::move(volume));
}
template <class T>
BccVolume<T> to_bcc_volume(LatticeVolume<T>&& volume) {
  return BccVolume<T>(std::move(volume));
}

using RegistryFilter = SplineFilter;
template <class T>
using RegistryReconstructor = Reconstructor<T>;

template <class Tr, class T>
class LatticeReconstructor : public Reconstructor<T> {
 public:
  explicit LatticeReconstructor(const LatticeVolume<T>& volume)
      : Reconstructor<T>(volume, emitted_filter<Tr>()) {}
};

inline Filter parse_filter(std::string_view name) {
  for (const Filter f : {Filter::M7, Filter::M8, Filter::M12})
    if (SplineFilter(f).name() == name) return f;
  throw std::invalid_argument("unknown filter '" + std::string(name.substr(0, 40)) +
                              "': expected m7, m8 or m12");
}
inline const char* filter_name(Filter f) {
  static const SplineFilter filters[] = {Filter::M7, Filter::M8, Filter::M12};
  const auto index = static_cast<std::size_t>(f);
  return index < std::size(filters) ? filters[index].name().c_str() : "?";
}
inline StencilReach stencil_reach(Filter f) { return SplineFilter(f).reach(); }
inline DiscreteFilter prefilter_taps(Filter f, PrefilterChoice q) {
  return SplineFilter(f).prefilter(q);
}
inline int required_margin(Filter f, PrefilterChoice q) {
  return SplineFilter(f).required_margin(q);
}
inline PrefilterShrink prefilter_shrink(const DiscreteFilter& q) {
  return prefilter_shrink(q, CosetLattice::bcc());
}
inline int prefilter_margin(const DiscreteFilter& q) {
  return prefilter_margin(q, CosetLattice::bcc());
}

struct BccGrid {
  Sizes sizes;
  double h;
  Vec3 origin;
};
inline BccGrid cube_grid(int n, int margin) {
  const LatticeGrid g = cube_lattice_grid(CosetLattice::bcc(), n, margin);
  return {g.sizes, g.h, g.origin};
}
template <class T>
BccVolume<T> sample_bcc(const ScalarFunction& f, const BccGrid& grid) {
  return sample_lattice<T>(f, {CosetLattice::bcc(), grid.sizes, grid.h, grid.origin});
}
template <class T>
BccVolume<T> sample_cube(const ScalarFunction& f, int n, int margin) {
  return sample_bcc<T>(f, cube_grid(n, margin));
}

template <class T>
BccVolume<T> read_bcc_nrrd(const std::filesystem::path& path, const NrrdReadLimits& limits = {}) {
  LatticeVolume<T> volume = read_lattice_nrrd<T>(path, limits);
  if (!(volume.lattice() == CosetLattice::bcc()))
    throw NrrdError("cannot read BCC volume '" + path.string() + "': it is on the " +
                    volume.lattice().name() + " lattice (offsets " +
                    volume.lattice().offsets_text() + ")");
  return BccVolume<T>(std::move(volume));
}
template <class T>
void write_bcc_nrrd(const std::filesystem::path& path, const LatticeVolume<T>& volume) {
  write_lattice_nrrd(path, volume);
}

}  // namespace boxgen::runtime
