// The filters of generated/registry.hpp (M7, M8, M12 on BCC, fcc6 on FCC, tricubic and cart7 on
// the Cartesian lattice, ...) chosen by name at run time, on volumes of their own lattice
// (lattice_volume.h): what boxrecon's --filter needs. Each filter is the generic
// LatticeReconstructor (lattice_reconstruction.h) of its emitted Traits, reached through
// generated::with_filter; nothing here lists a filter or knows a coefficient, so a filter added
// to the registry is picked up here without a change.
//
// Border policy as the BCC runtime (reconstruction.h, resample.h): nothing outside the stored
// samples is invented. A volume of K cosets of N_a samples per axis holds every lattice point of
// the box [0, d N_a - 1]^3 (lattice coordinates; the coset offsets lie in [0, d)^3), so the
// region where a filter evaluates is, per axis, -lo_a - c_a <= x_a < d N_a - hi_a - c_a: BCC's
// region of resample.h with d = 2.
#pragma once
#include <memory>
#include <span>
#include <string>
#include <string_view>

#include "runtime/cartesian_volume.h"
#include "runtime/coset_lattice.h"
#include "runtime/lattice_volume.h"
#include "runtime/prefilter.h"
#include "runtime/reconstruction.h"
#include "runtime/resample.h"

namespace boxgen::runtime {

// A filter of generated/registry.hpp, by its position there.
class RegistryFilter {
 public:
  // By name (generated::kFilterNames); anything else: std::invalid_argument, one line naming the
  // registry's filters.
  static RegistryFilter parse(std::string_view name);
  static int count();
  // 0 <= index < count(), else std::invalid_argument.
  static RegistryFilter at(int index);
  // "m7, m8, m12, fcc6, tricubic or cart7": the names, for messages and help texts.
  static std::string names();

  int index() const noexcept { return index_; }
  const char* name() const;
  // The lattice the filter was derived on (its Traits' Hermite basis, filter_lattice<Tr>()).
  CosetLattice lattice() const;
  // The generator's published stencil reach and centre shift (kStencilReachLo/Hi, kCentre).
  StencilReach reach() const;
  // Its generated prefilter Q^I (q1) or Q^II (q2); none: the identity {(0,0,0), 1}.
  DiscreteFilter prefilter(PrefilterChoice q) const;
  // The generator's approximation order k of the filter: q1 and q2 reproduce every polynomial of
  // degree < k (4 for M7, M8, M12, tricubic and cart7, 3 for fcc6).
  int approximation_order() const;
  // Coset cells of margin beyond [-1,1]^3 that cube_lattice_grid needs for reconstruction with
  // this filter after prefilter q (as required_margin in reconstruction.h, for period d).
  int required_margin(PrefilterChoice q) const;
  // The BCC Reconstructor's Filter when this is one of the first kFilterCount entries it knows
  // (m7, m8, m12), so that their BCC volumes keep the Reconstructor path.
  bool has_bcc_filter() const noexcept;
  Filter bcc_filter() const;

  // Throws std::invalid_argument (one line) unless the volume is on the filter's lattice:
  // "filter fcc6 is for the fcc lattice, but the volume is on the bcc lattice".
  void check_lattice(const CosetLattice& volume_lattice) const;

 private:
  explicit RegistryFilter(int index) : index_(index) {}
  int index_ = 0;
};

// The region where f evaluates on `volume` (above), in world coordinates, and the default
// resampling box: that region closed and pulled in by a rounding guard (as default_box in
// resample.h). Throw std::invalid_argument (one line) for a volume of another lattice or one too
// small for the stencil.
template <class T>
Box evaluable_region(const LatticeVolume<T>& volume, RegistryFilter f);
template <class T>
Box default_box(const LatticeVolume<T>& volume, RegistryFilter f);

// Any registry filter on a volume of its lattice: LatticeReconstructor<Traits, T> chosen at run
// time, with batches on up to batch_threads() threads.
template <class T>
class RegistryReconstructor {
 public:
  // Throws std::invalid_argument (one line) if the volume is not on the filter's lattice.
  RegistryReconstructor(const LatticeVolume<T>& volume, RegistryFilter f);

  // The spline at a world point, with its gradient and second derivatives {xx, xy, xz, yy, yz,
  // zz} (world units) when asked. Errors as LatticeReconstructor.
  T value(const Vec3& world, Vec3* gradient = nullptr, Hessian* hessian = nullptr) const;
  // value() for many points; `gradients` and `hessians` empty or as long as `points` (hessians
  // need gradients). Throws the first error, naming the point's index (from 1).
  void evaluate(std::span<const Vec3> points, std::span<T> values, std::span<Vec3> gradients = {},
                std::span<Hessian> hessians = {}) const;

 private:
  std::shared_ptr<const EvaluationPath<T>> path_;  // the chosen filter (emitted_spline.h)
};

// resample() of resample.h for any registry filter on its lattice: the spline's values at the
// grid points. Errors as there (std::out_of_range for a grid point outside evaluable_region).
template <class T>
CartesianVolume<T> resample(const LatticeVolume<T>& volume, RegistryFilter f,
                            const CartesianGrid& grid);

extern template Box evaluable_region<float>(const LatticeVolume<float>&, RegistryFilter);
extern template Box evaluable_region<double>(const LatticeVolume<double>&, RegistryFilter);
extern template Box default_box<float>(const LatticeVolume<float>&, RegistryFilter);
extern template Box default_box<double>(const LatticeVolume<double>&, RegistryFilter);
extern template class RegistryReconstructor<float>;
extern template class RegistryReconstructor<double>;
extern template CartesianVolume<float> resample<float>(const LatticeVolume<float>&, RegistryFilter,
                                                       const CartesianGrid&);
extern template CartesianVolume<double> resample<double>(const LatticeVolume<double>&,
                                                         RegistryFilter, const CartesianGrid&);

}  // namespace boxgen::runtime
