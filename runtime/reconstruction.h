// Reconstruction of BCC volumes with the generated evaluators (generated/m7.hpp, m8.hpp,
// m12.hpp) and their generated prefilters. Nothing here knows a polynomial coefficient or a
// prefilter weight: both come from generated/.
#pragma once
#include <array>
#include <span>
#include <string_view>
#include <vector>

#include "runtime/bcc_volume.h"
#include "runtime/prefilter.h"

namespace boxgen::runtime {

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

// The generated quasi-interpolation prefilter (Q^I on shells 0,1; Q^II on shells 0,1,2).
DiscreteFilter prefilter_taps(Filter f, PrefilterChoice q);
// Samples beyond [-1,1]^3 (in coset cells) that reconstruction with f, after prefilter q, needs.
int required_margin(Filter f, PrefilterChoice q);

template <class T>
class Reconstructor {
 public:
  Reconstructor(const BccVolume<T>& volume, Filter filter)
      : volume_(volume), filter_(filter), reach_(stencil_reach(filter)) {}

  // The spline at a world point; with `gradient` also its gradient in world units. Throws
  // std::invalid_argument for a non-finite coordinate and std::out_of_range (one line) when the
  // stencil leaves the volume: the volume never invents data.
  T value(const Vec3& world, Vec3* gradient = nullptr) const;

  // value() for many points on all cores. Throws the first error, naming the point's index.
  void evaluate(std::span<const Vec3> points, std::span<T> values, std::span<Vec3> gradients = {}) const;

 private:
  const BccVolume<T>& volume_;
  Filter filter_;
  StencilReach reach_;  // a point whose whole reach box is inside is fetched without checks
};

extern template class Reconstructor<float>;
extern template class Reconstructor<double>;

}  // namespace boxgen::runtime
