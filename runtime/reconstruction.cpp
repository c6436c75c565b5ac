#include "runtime/reconstruction.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <stdexcept>

#include "runtime/emitted_spline.h"

namespace boxgen::runtime {

template <class T>
Reconstructor<T>::Reconstructor(const LatticeVolume<T>& volume, const SplineFilter& filter)
    : volume_(&volume), filter_(filter) {
  filter_.check_lattice(volume.lattice());
  path_ = filter_.source().path(volume);
}

template <class T>
T Reconstructor<T>::value(const Vec3& world, Vec3* gradient, Hessian* hessian) const {
  return path_->at(world, gradient, hessian);
}

template <class T>
void Reconstructor<T>::evaluate(std::span<const Vec3> points, std::span<T> values,
                                std::span<Vec3> gradients, std::span<Hessian> hessians) const {
  path_->batch(points, values, gradients, hessians);
}

template <class T>
void Reconstructor<T>::require_finite(std::span<const Vec3> points, std::span<const T> values,
                                      std::span<const Vec3> gradients,
                                      std::span<const Hessian> hessians) const {
  const auto finite = [](const auto& xs) {
    return std::all_of(xs.begin(), xs.end(), [](double x) { return std::isfinite(x); });
  };
  for (std::size_t i = 0; i < values.size(); ++i) {
    if (std::isfinite(values[i]) && (gradients.empty() || finite(gradients[i])) &&
        (hessians.empty() || finite(hessians[i])))
      continue;
    const std::span<const T> samples = volume_->samples();
    double largest = 0;
    bool all_finite = true;
    for (const T s : samples) {
      all_finite = all_finite && std::isfinite(s);
      largest = std::max(largest, std::fabs(static_cast<double>(s)));
    }
    const Vec3& p = points[i];
    throw std::domain_error(fmt::format(
        "the {} spline at point {} ({}, {}, {}) is not finite ({}{}): {}", filter_.name(), i + 1,
        p[0], p[1], p[2], static_cast<double>(values[i]),
        std::isfinite(values[i]) ? " in its derivatives" : "",
        all_finite ? fmt::format("the volume's samples are finite, but as large as {:g}, too large "
                                 "for the spline's sums in {} precision",
                                 largest, sizeof(T) == 4 ? "float" : "double")
                   : "the volume holds non-finite samples"));
  }
}

template class Reconstructor<float>;
template class Reconstructor<double>;

}  // namespace boxgen::runtime
