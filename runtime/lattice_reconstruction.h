// Reconstruction with ANY emitted evaluator on a volume of its lattice: the filters of
// generated/registry.hpp and a user's own `boxgen emit` / boxgen_emit() header alike. The class is
// a template on the evaluator's Traits (the struct every emitted header defines, see
// generated/evaluator_support.hpp), so nothing here lists filters or knows a coefficient.
//
//   #include "my_filter.hpp"              // boxgen emit "<your matrix>" --name my_filter
//   #include "my_filter_prefilters.hpp"
//   LatticeVolume<double> v = sample_lattice<double>(f,
//   cube_lattice_grid(filter_lattice<my_filter::Traits>(), 33, 4)); v = prefilter(v,
//   prefilter_from(my_filter::q1)); LatticeReconstructor<my_filter::Traits, double> r(v); double s
//   = r.value({0.1, 0.2, 0.3});
//
// The filter's lattice is read from the evaluator's Hermite basis (Traits::kHermite); a volume
// on another lattice is refused with one line (std::invalid_argument). Border policy as
// Reconstructor (reconstruction.h): a point whose stencil leaves the volume is
// std::out_of_range (one line), a non-finite coordinate std::invalid_argument; the whole stencil
// box is checked once per point, then fetched without further checks.
#pragma once
#include <fmt/format.h>

#include <array>
#include <cmath>
#include <cstddef>
#include <span>
#include <stdexcept>

#include "generated/evaluator_support.hpp"
#include "runtime/coset_lattice.h"
#include "runtime/lattice_volume.h"
#include "runtime/prefilter.h"

namespace boxgen::runtime {

// The lattice an emitted evaluator was derived on: its Hermite basis holds the columns of G.
template <class Tr>
CosetLattice filter_lattice() {
  static_assert(Tr::kDimension == 3, "volumes are 3-D");
  IntRows rows{};
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c) rows[r][c] = Tr::kHermite[c][r];
  return CosetLattice::from_rows(rows);
}

// An emitted prefilter table (q1 or q2 of a *_prefilters.hpp) as taps for prefilter().
template <class Tap, std::size_t N>
DiscreteFilter prefilter_from(const Tap (&table)[N]) {
  DiscreteFilter out;
  for (const auto& t : table) out.push_back({{t.offset[0], t.offset[1], t.offset[2]}, t.weight});
  return out;
}

// Do two lattices hold the same points (whatever the order of their cosets)?
inline bool same_points(const CosetLattice& a, const CosetLattice& b) {
  if (a.period() != b.period() || a.determinant() != b.determinant()) return false;
  for (const Offset& o : a.offsets())
    if (!b.contains(o[0], o[1], o[2])) return false;
  return true;
}

template <class Tr, class T>
class LatticeReconstructor {
  static_assert(Tr::kDimension == 3, "volumes are 3-D");
  static constexpr int kStencil = Tr::kStencilSize;

 public:
  // Throws std::invalid_argument (one line) if the volume is not on the filter's lattice.
  explicit LatticeReconstructor(const LatticeVolume<T>& volume) : volume_(volume) {
    const CosetLattice lattice = filter_lattice<Tr>();
    if (!same_points(lattice, volume.lattice()))
      throw std::invalid_argument(
          fmt::format("filter {} is for the {} lattice, but the volume is on the {} lattice",
                      Tr::kName, lattice.name(), volume.lattice().name()));
  }

  // The spline at a world point; with `gradient` its gradient and with `hessian` its second
  // derivatives {xx, xy, xz, yy, yz, zz}, in world units.
  T value(const Vec3& world, Vec3* gradient = nullptr,
          std::array<double, 6>* hessian = nullptr) const {
    if (hessian) return point<generated::support::kHessian>(world, gradient, hessian);
    if (gradient) return point<generated::support::kGradient>(world, gradient, nullptr);
    return point<generated::support::kValue>(world, nullptr, nullptr);
  }

  // value() for many points (`gradients` empty: values only). Throws the first error.
  void evaluate(std::span<const Vec3> points, std::span<T> values,
                std::span<Vec3> gradients = {}) const {
    if (values.size() != points.size() || (!gradients.empty() && gradients.size() != points.size()))
      throw std::invalid_argument("evaluate: values and gradients must be as long as points");
    for (std::size_t i = 0; i < points.size(); ++i)
      values[i] = value(points[i], gradients.empty() ? nullptr : &gradients[i]);
  }

 private:
  template <int Order>
  T point(const Vec3& world, Vec3* gradient, std::array<double, 6>* hessian) const {
    namespace support = generated::support;
    for (double c : world)
      if (!std::isfinite(c)) throw std::invalid_argument("point has a non-finite coordinate");
    const Vec3 lattice = volume_.to_lattice(world);
    // Far outside, stop before floor(x) becomes an integer that could overflow.
    constexpr double kFar = 64;
    for (int a = 0; a < 3; ++a)
      if (!(lattice[a] > -kFar &&
            lattice[a] < static_cast<double>(volume_.period()) * (volume_.sizes()[a] + 1) + kFar))
        throw std::out_of_range(fmt::format("world point ({}, {}, {}) is outside the volume",
                                            world[0], world[1], world[2]));
    const std::array<T, 3> x{static_cast<T>(lattice[0]), static_cast<T>(lattice[1]),
                             static_cast<T>(lattice[2])};
    const support::Located<3, T> located = support::locate<Tr>(x);
    const int size = Tr::kOrbitStencilSize[Tr::kCells[located.cell].orbit];
    T v[kStencil];
    LatticePoint lo, hi;
    for (int a = 0; a < 3; ++a) {
      lo[a] = located.corner[a] + Tr::kStencilReachLo[a];
      hi[a] = located.corner[a] + Tr::kStencilReachHi[a];
    }
    const bool inside = volume_.contains_box(lo, hi);
    try {
      for (int k = 0; k < size; ++k) {
        LatticePoint j;
        for (int a = 0; a < 3; ++a) j[a] = located.corner[a] + Tr::kOffsets[located.cell][k][a];
        v[k] = inside ? volume_.value_unchecked(j) : volume_.value(j);
      }
    } catch (const std::out_of_range& e) {  // name the point the user asked for, then the sample
      throw std::out_of_range(
          fmt::format("world point ({}, {}, {}) needs a sample outside the volume: {}", world[0],
                      world[1], world[2], e.what()));
    }
    T d[3 + 6] = {};
    const T value = support::evaluate_located<Order, Tr>(located, v, d);
    const double h = volume_.spacing();
    if constexpr (Order >= support::kGradient)
      if (gradient)
        for (int i = 0; i < 3; ++i) (*gradient)[i] = static_cast<double>(d[i]) / h;
    if constexpr (Order >= support::kHessian)
      for (int i = 0; i < 6; ++i) (*hessian)[i] = static_cast<double>(d[3 + i]) / (h * h);
    return value;
  }

  const LatticeVolume<T>& volume_;
};

}  // namespace boxgen::runtime
