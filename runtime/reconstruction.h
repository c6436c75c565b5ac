// Reconstruction: the spline of a filter (spline_filter.h: a registry filter, a user's emitted
// header, any FilterSource) on a volume of that filter's lattice (lattice_volume.h), evaluated by
// the runtime's one engine (emitted_spline.h) with the stencil policy the filter picks for the
// volume (BCC's parity tables on BCC, the general lattice tables elsewhere), on up to
// batch_threads() threads and, for the registry's filters, in SIMD chunks. Nothing here knows a
// polynomial coefficient or a prefilter weight: both come from generated/.
//
//   const SplineFilter m7 = SplineFilter::parse("m7");
//   LatticeVolume<double> v = sample_lattice<double>(f, cube_lattice_grid(m7.lattice(), 33,
//                                                    m7.required_margin(PrefilterChoice::Q2)));
//   v = prefilter(v, m7.prefilter(PrefilterChoice::Q2));
//   const Reconstructor<double> r(v, m7);
//   double s = r.value({0.1, 0.2, 0.3});
//
// Border policy: nothing outside the stored samples is invented. A non-finite coordinate is
// std::invalid_argument; a point whose stencil leaves the volume is std::out_of_range (one line
// naming the point).
#pragma once
#include <memory>
#include <span>

#include "runtime/lattice_volume.h"
#include "runtime/spline_filter.h"

namespace boxgen::runtime {

template <class T>
class Reconstructor {
 public:
  // Throws std::invalid_argument (one line) if the volume is not on the filter's lattice. The
  // volume must outlive the reconstructor.
  Reconstructor(const LatticeVolume<T>& volume, const SplineFilter& filter);

  const SplineFilter& filter() const noexcept { return filter_; }

  // The spline at a world point; with `gradient` also its gradient and with `hessian` its second
  // derivatives {xx, xy, xz, yy, yz, zz}, in world units (hessian needs gradient).
  T value(const Vec3& world, Vec3* gradient = nullptr, Hessian* hessian = nullptr) const;
  T value_gradient_hessian(const Vec3& world, Vec3& gradient, Hessian& hessian) const {
    return value(world, &gradient, &hessian);
  }

  // value() for many points. `gradients` and `hessians` empty (not computed) or as long as
  // `points`; hessians need gradients. Throws the first error, naming the point's index (from 1).
  void evaluate(std::span<const Vec3> points, std::span<T> values, std::span<Vec3> gradients = {},
                std::span<Hessian> hessians = {}) const;

  // Throws std::domain_error (one line) naming the first point whose value or derivatives are not
  // finite, and why: the volume's samples are finite but too large for the spline's sums, or the
  // volume holds non-finite samples. A caller that prints or writes results calls it first.
  void require_finite(std::span<const Vec3> points, std::span<const T> values,
                      std::span<const Vec3> gradients = {},
                      std::span<const Hessian> hessians = {}) const;

 private:
  const LatticeVolume<T>* volume_;
  SplineFilter filter_;
  std::shared_ptr<const EvaluationPath<T>> path_;  // the filter on this volume (emitted_spline.h)
};

extern template class Reconstructor<float>;
extern template class Reconstructor<double>;

}  // namespace boxgen::runtime
