#include "runtime/reconstruction.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <exception>
#include <stdexcept>
#include <string>

#include "generated/registry.hpp"
#include "runtime/emitted_spline.h"
#include "runtime/lattice_reconstruction.h"

namespace boxgen::runtime {

namespace generated = boxgen::generated;
namespace support = boxgen::generated::support;

namespace {

// Filter::M7, M8, M12: the registry's first entries (its other filters are on other lattices and
// reach the apps through lattice_filters.h).
constexpr const char* kRegistryOrder[] = {"m7", "m8", "m12"};
static_assert(std::size(kRegistryOrder) <= generated::kFilterCount,
              "Filter must name the registry's first filters");
constexpr int kBccFilterCount = static_cast<int>(std::size(kRegistryOrder));

// The Filter enum is an index into the registry; its names must agree with it.
int registry_index(Filter f) {
  const int index = static_cast<int>(f);
  if (index < 0 || index >= kBccFilterCount) throw std::logic_error("unknown filter");
  return index;
}

}  // namespace

Filter parse_filter(std::string_view name) {
  for (int i = 0; i < kBccFilterCount; ++i)
    if (name == generated::kFilterNames[i]) return static_cast<Filter>(i);
  throw std::invalid_argument(
      fmt::format("unknown filter '{}': expected m7, m8 or m12", name.substr(0, 40)));
}

PrefilterChoice parse_prefilter(std::string_view name) {
  if (name == "none") return PrefilterChoice::None;
  if (name == "q1") return PrefilterChoice::Q1;
  if (name == "q2") return PrefilterChoice::Q2;
  throw std::invalid_argument(
      fmt::format("unknown prefilter '{}': expected none, q1 or q2", name.substr(0, 40)));
}

const char* filter_name(Filter f) {
  const int index = static_cast<int>(f);
  if (index < 0 || index >= kBccFilterCount) return "?";
  if (std::strcmp(generated::kFilterNames[index], kRegistryOrder[index]) != 0)
    throw std::logic_error("registry order");
  return generated::kFilterNames[index];
}

DiscreteFilter prefilter_taps(Filter f, PrefilterChoice q) {
  if (q == PrefilterChoice::None) return {{{0, 0, 0}, 1.0}};
  return generated::with_filter(registry_index(f), [&](auto entry) {
    return q == PrefilterChoice::Q1 ? prefilter_from(entry.q1) : prefilter_from(entry.q2);
  });
}

StencilReach stencil_reach(Filter f) {
  return generated::with_filter(registry_index(f), [](auto entry) {
    return published_reach<typename decltype(entry)::Traits>();
  });
}

int required_margin(Filter f, PrefilterChoice q) {
  // Evaluation needs -lo - c <= x < 2N - hi - c in the volume's lattice coordinates (resample.h).
  // A margin of m coset cells puts [-1,1] at [2m, 2N - 2m - 2], so it needs 2m >= -lo - c and
  // 2m > hi + c - 2; we add one unit of slack to each for rounding at the faces. Then the
  // prefilter's own reach.
  const StencilReach r = stencil_reach(f);
  double need = 0;
  for (int a = 0; a < 3; ++a)
    need = std::max({need, -r.lo[a] - r.centre[a], r.hi[a] + r.centre[a] - 2});
  const int reconstruction = static_cast<int>(std::ceil((need + 1) / 2));
  return reconstruction + (q == PrefilterChoice::None ? 0 : prefilter_margin(prefilter_taps(f, q)));
}

namespace {

// Where the stencil of a point lies in a BccVolume (emitted_spline.h says what a Stencils
// provides): offsets into samples() precomputed per cell and per parity of the corner's x.
// Offset is std::int32_t where every offset fits (a smaller table stays in the L1 cache), else
// std::int64_t.
template <class Tr, class T, class O>
class BccStencils {
 public:
  using Sample = T;
  using Index = O;

  explicit BccStencils(const BccVolume<T>& volume) : volume_(&volume) {
    // Sample (x, y, z) sits at x + N0 y + N0 N1 z - c (N0 + N0 N1), c = x & 1 its coset
    // (bcc_volume.h): linear in the point apart from the coset term. For j = corner + d the
    // coset is (corner_x & 1) ^ (d_x & 1), so one table per corner parity.
    const std::int64_t n0 = volume.sizes()[0], n1 = volume.sizes()[1];
    stride_ = {1, n0, n0 * n1};
    const std::int64_t coset_shift = n0 + n0 * n1;
    offsets_.resize(2 * Tr::kCellCount * Tr::kStencilSize);
    for (int parity = 0; parity < 2; ++parity)
      for (int cell = 0; cell < Tr::kCellCount; ++cell)
        for (int k = 0; k < Tr::kStencilSize; ++k) {
          const auto& d = Tr::kOffsets[cell][k];
          const int coset = parity ^ (d[0] & 1);
          offsets_[(parity * Tr::kCellCount + cell) * Tr::kStencilSize + k] =
              static_cast<O>(d[0] + n0 * d[1] + n0 * n1 * d[2] - coset * coset_shift);
        }
  }

  const BccVolume<T>& volume() const { return *volume_; }
  double extent(int a) const { return 2.0 * volume_->sizes()[a]; }
  double last(int a) const { return 2.0 * volume_->sizes()[a] - 1; }
  bool has_offsets() const { return true; }
  const T* samples() const { return volume_->samples().data(); }
  Fetch<O> fetch(const std::int64_t* corner, int cell) const {
    return {corner[0] * stride_[0] + corner[1] * stride_[1] + corner[2] * stride_[2],
            &offsets_[((corner[0] & 1) * Tr::kCellCount + cell) * Tr::kStencilSize]};
  }
  T sample(const LatticePoint& j, bool inside) const {
    return inside ? volume_->value_unchecked(j) : volume_->value(j);
  }

 private:
  const BccVolume<T>* volume_;
  std::array<std::int64_t, 3> stride_{};
  std::vector<O> offsets_;  // [corner parity][cell][k]
};

}  // namespace

template <class T>
Reconstructor<T>::Reconstructor(const BccVolume<T>& volume, Filter filter)
    : path_(generated::with_filter(
          registry_index(filter),
          [&,
           index = registry_index(filter)](auto entry) -> std::shared_ptr<const EvaluationPath<T>> {
            using Tr = typename decltype(entry)::Traits;
            if constexpr (std::string_view(Tr::kLattice) != "bcc") {
              throw std::logic_error("not a BCC filter");  // registry_index() excludes it
            } else {
              // |offset| <= (max reach + 1) (1 + N0 + N0 N1): 32 bits suffice for all but huge
              // slabs.
              int reach = 0;
              for (int a = 0; a < 3; ++a)
                reach = std::max({reach, -Tr::kStencilReachLo[a], Tr::kStencilReachHi[a]});
              const double n0 = volume.sizes()[0], n1 = volume.sizes()[1];
              if ((reach + 1.0) * (1.0 + n0 + n0 * n1) < 2147483647.0)
                return std::make_shared<EmittedSplinePath<Tr, BccStencils<Tr, T, std::int32_t>>>(
                    BccStencils<Tr, T, std::int32_t>(volume), index);
              return std::make_shared<EmittedSplinePath<Tr, BccStencils<Tr, T, std::int64_t>>>(
                  BccStencils<Tr, T, std::int64_t>(volume), index);
            }
          })) {}

template <class T>
T Reconstructor<T>::value(const Vec3& world, Vec3* gradient) const {
  return path_->at(world, gradient, nullptr);
}

template <class T>
T Reconstructor<T>::value_gradient_hessian(const Vec3& world, Vec3& gradient,
                                           Hessian& hessian) const {
  return path_->at(world, &gradient, &hessian);
}

template <class T>
void Reconstructor<T>::evaluate(std::span<const Vec3> points, std::span<T> values,
                                std::span<Vec3> gradients) const {
  evaluate(points, values, gradients, {});
}

template <class T>
void Reconstructor<T>::evaluate(std::span<const Vec3> points, std::span<T> values,
                                std::span<Vec3> gradients, std::span<Hessian> hessians) const {
  path_->batch(points, values, gradients, hessians);
}

template class Reconstructor<float>;
template class Reconstructor<double>;

}  // namespace boxgen::runtime
