// Reconstruction of BCC volumes with the generated evaluators and their generated prefilters,
// for every filter of generated/registry.hpp (M7, M8, M12). Nothing here knows a polynomial
// coefficient or a prefilter weight: both come from generated/.
#pragma once
#include <array>
#include <memory>
#include <span>
#include <string_view>
#include <vector>

#include "runtime/bcc_volume.h"
#include "runtime/prefilter.h"

namespace boxgen::runtime {

// A filter of generated/registry.hpp, by its position there (reconstruction.cpp checks the names).
enum class Filter { M7, M8, M12 };
enum class PrefilterChoice { None, Q1, Q2 };

// "m7" | "m8" | "m12" and "none" | "q1" | "q2"; anything else: std::invalid_argument, one line.
Filter parse_filter(std::string_view name);
PrefilterChoice parse_prefilter(std::string_view name);
const char* filter_name(Filter f);

// Offsets j_a - floor(x_a + centre_a) of every lattice point the generated evaluator of a filter
// may fetch, per axis, and the centre shift c: published by the generator with each evaluator
// (kStencilReachLo/Hi, kCentre). runtime/resample.h explains the box this gives.
struct StencilReach {
  std::array<int, 3> lo{}, hi{};
  Vec3 centre{};
};
StencilReach stencil_reach(Filter f);
// The reach an emitted evaluator's traits type publishes (any filter, any lattice).
template <class Tr>
StencilReach published_reach() {
  StencilReach reach;
  for (int a = 0; a < 3; ++a) {
    reach.lo[a] = Tr::kStencilReachLo[a];
    reach.hi[a] = Tr::kStencilReachHi[a];
    reach.centre[a] = Tr::kCentre[a];
  }
  return reach;
}

// The generated quasi-interpolation prefilter (Q^I on shells 0,1; Q^II on shells 0,1,2).
DiscreteFilter prefilter_taps(Filter f, PrefilterChoice q);
// Samples beyond [-1,1]^3 (in coset cells) that reconstruction with f, after prefilter q, needs.
int required_margin(Filter f, PrefilterChoice q);

// How the chosen filter evaluates on a volume: runtime/emitted_spline.h (the runtime's one engine,
// with the BCC volume's offset tables of reconstruction.cpp).
template <class T>
class EvaluationPath;

template <class T>
class Reconstructor {
 public:
  Reconstructor(const BccVolume<T>& volume, Filter filter);

  // The spline at a world point; with `gradient` also its gradient in world units. Throws
  // std::invalid_argument for a non-finite coordinate and std::out_of_range (one line) when the
  // stencil leaves the volume: the volume never invents data.
  T value(const Vec3& world, Vec3* gradient = nullptr) const;
  // value() with the exact gradient and second derivatives (world units) of the spline.
  T value_gradient_hessian(const Vec3& world, Vec3& gradient, Hessian& hessian) const;

  // value() for many points on up to batch_threads() threads (runtime/batch_threads.h). Throws
  // the first error, naming the point's index. `gradients` may be empty (values only).
  void evaluate(std::span<const Vec3> points, std::span<T> values,
                std::span<Vec3> gradients = {}) const;
  // The same with second derivatives; `hessians` (and `gradients`) as long as `points`.
  void evaluate(std::span<const Vec3> points, std::span<T> values, std::span<Vec3> gradients,
                std::span<Hessian> hessians) const;

 private:
  std::shared_ptr<const EvaluationPath<T>> path_;
};

extern template class Reconstructor<float>;
extern template class Reconstructor<double>;

}  // namespace boxgen::runtime
