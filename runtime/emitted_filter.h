// An emitted evaluator (the Traits of a `boxgen emit` / boxgen_emit() header, see
// support/evaluator_support.hpp) as a SplineFilter: the registry's filters are these, and so is
// a user's own header. Nothing here lists filters or knows a coefficient.
//
// Example (a header from `boxgen emit "<your matrix>" --name my_filter`, and its prefilters):
//   const SplineFilter f = emitted_filter<my_filter::Traits>(my_filter::q1, my_filter::q2,
//                                                            my_filter::kApproximationOrder);
//   auto v = sample_lattice<double>(fn, cube_lattice_grid(f.lattice(), 33,
//                                                         f.required_margin(PrefilterChoice::Q1)));
//   v = prefilter(v, f.prefilter(PrefilterChoice::Q1));
//   const Reconstructor<double> r(v, f);
//   double s = r.value({0.1, 0.2, 0.3});
#pragma once
#include <fmt/format.h>

#include <cstddef>
#include <cstdint>
#include <memory>
#include <stdexcept>
#include <string>
#include <string_view>
#include <utility>

#include "runtime/emitted_spline.h"
#include "runtime/spline_filter.h"
#include "runtime/stencils.h"
#include "support/evaluator_support.hpp"

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

// The reach an emitted evaluator's traits type publishes.
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

// An emitted prefilter table (q1, q2, q1opt or q2opt of a *_prefilters.hpp) as taps for
// prefilter().
template <class Tap, std::size_t N>
PrefilterTaps prefilter_from(const Tap (&table)[N]) {
  PrefilterTaps out;
  for (const auto& t : table) out.push_back({{t.offset[0], t.offset[1], t.offset[2]}, t.weight});
  return out;
}

// The stencil policies of the engine (runtime/stencils.h) an emitted evaluator can take.
enum class StencilPolicy {
  kBcc32,    // BccStencils with 32-bit offsets
  kBcc64,    // BccStencils with 64-bit offsets
  kLattice,  // LatticeStencils
};

// The policy an emitted evaluator takes on a volume of this lattice and these sizes: BCC's parity
// tables where they apply (the fast path, 32-bit offsets where they fit, else 64-bit ones), the
// general lattice tables everywhere else. Without kBccWideOffsets a BCC volume too large for
// 32-bit offsets (N0 N1 over 2^31 / (reach + 1) samples per coset and z) takes the general tables
// too: a compiled filter (loader/filter_loader.cpp) drops the 64-bit policy, which costs about an
// eighth of each half's compile and serves only such volumes.
template <class Tr, bool kBccWideOffsets = true>
StencilPolicy stencil_policy(const CosetLattice& lattice, const Sizes& sizes) {
  if constexpr (std::string_view(Tr::kLattice) == "bcc") {
    if (lattice == CosetLattice::bcc()) {
      if (BccStencils<Tr, float, std::int32_t>::fits(sizes)) return StencilPolicy::kBcc32;
      if (kBccWideOffsets) return StencilPolicy::kBcc64;
    }
  }
  return StencilPolicy::kLattice;
}

// The evaluation path of an emitted evaluator on `volume`, with the policy stencil_policy()
// picks; only the policies the evaluator's lattice (and kBccWideOffsets) can take are
// instantiated. A function of its own (not inline) so that a compiled filter can instantiate its
// two precisions in two translation units compiled at once, declaring the other one `extern
// template` (loader/filter_loader.cpp).
template <class Tr, class T, bool kBccWideOffsets = true>
std::shared_ptr<const EvaluationPath<T>> emitted_path(const LatticeVolume<T>& volume,
                                                      int registry_index,
                                                      const simd::Kernels* kernels) {
  const StencilPolicy policy =
      stencil_policy<Tr, kBccWideOffsets>(volume.lattice(), volume.sizes());
  if constexpr (std::string_view(Tr::kLattice) == "bcc") {
    if (policy == StencilPolicy::kBcc32)
      return std::make_shared<EmittedSplinePath<Tr, BccStencils<Tr, T, std::int32_t>>>(
          BccStencils<Tr, T, std::int32_t>(volume), registry_index, kernels);
    if constexpr (kBccWideOffsets) {
      if (policy == StencilPolicy::kBcc64)
        return std::make_shared<EmittedSplinePath<Tr, BccStencils<Tr, T, std::int64_t>>>(
            BccStencils<Tr, T, std::int64_t>(volume), registry_index, kernels);
    }
  }
  return std::make_shared<EmittedSplinePath<Tr, LatticeStencils<Tr, T>>>(
      LatticeStencils<Tr, T>(volume), registry_index, kernels);
}

// The tables of a *_prefilters.hpp; an empty one: the filter was given none.
struct GeneratedPrefilters {
  PrefilterTaps q1, q2, q1opt, q2opt;
};

// The FilterSource of an emitted evaluator. registry_index: its position in
// generated/registry.hpp, whose filters have SIMD kernels (simd_batch.cpp); -1 for any other
// header (which this one must not clash with: it includes no registry), which takes the scalar
// batch path. kBccWideOffsets: see stencil_policy().
template <class Tr, bool kBccWideOffsets = true>
class EmittedFilter final : public FilterSource {
 public:
  // kernels: SIMD kernels compiled with the filter (simd_batch.h), for one outside the registry.
  EmittedFilter(GeneratedPrefilters taps, int approximation_order, int registry_index,
                const simd::Kernels* kernels = nullptr)
      : taps_(std::move(taps)),
        order_(approximation_order),
        registry_index_(registry_index),
        kernels_(kernels),
        lattice_(filter_lattice<Tr>()) {}

  std::string name() const override { return Tr::kName; }
  CosetLattice lattice() const override { return lattice_; }
  StencilReach reach() const override { return published_reach<Tr>(); }
  PrefilterTaps prefilter(PrefilterChoice q) const override {
    // Named here, not by q.text(): a compiled filter (loader/) links only what this header uses.
    const PrefilterTaps* taps = nullptr;
    const char* name = "";
    if (q == PrefilterChoice::Q1) taps = &taps_.q1, name = "q1";
    if (q == PrefilterChoice::Q2) taps = &taps_.q2, name = "q2";
    if (q == PrefilterChoice::Q1Opt) taps = &taps_.q1opt, name = "q1opt";
    if (q == PrefilterChoice::Q2Opt) taps = &taps_.q2opt, name = "q2opt";
    if (!taps)
      throw std::invalid_argument(
          fmt::format("filter {} has no generated table for this prefilter", Tr::kName));
    if (taps->empty())
      throw std::invalid_argument(fmt::format(
          "filter {} was given no prefilter {} (pass the tables of its _prefilters.hpp)", Tr::kName,
          name));
    return *taps;
  }
  int approximation_order() const override { return order_; }
  std::shared_ptr<const EvaluationPath<float>> path(
      const LatticeVolume<float>& volume) const override {
    return make_path(volume);
  }
  std::shared_ptr<const EvaluationPath<double>> path(
      const LatticeVolume<double>& volume) const override {
    return make_path(volume);
  }

 private:
  template <class T>
  std::shared_ptr<const EvaluationPath<T>> make_path(const LatticeVolume<T>& volume) const {
    return emitted_path<Tr, T, kBccWideOffsets>(volume, registry_index_, kernels_);
  }

  GeneratedPrefilters taps_;
  int order_;
  int registry_index_;
  const simd::Kernels* kernels_;
  CosetLattice lattice_;
};

// A user's emitted header as a SplineFilter, without prefilters (prefilter(q1 or q2) then throws)
// or with the tables of its _prefilters.hpp (q1, q2, kApproximationOrder; q1opt and q2opt are
// then not given).
template <class Tr>
SplineFilter emitted_filter() {
  return SplineFilter(std::make_shared<EmittedFilter<Tr>>(GeneratedPrefilters{}, 0, -1));
}
template <class Tr, class Tap, std::size_t N1, std::size_t N2>
SplineFilter emitted_filter(const Tap (&q1)[N1], const Tap (&q2)[N2], int approximation_order) {
  return SplineFilter(std::make_shared<EmittedFilter<Tr>>(
      GeneratedPrefilters{prefilter_from(q1), prefilter_from(q2), {}, {}}, approximation_order,
      -1));
}

}  // namespace boxgen::runtime
