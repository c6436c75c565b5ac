// A reconstruction filter as the runtime sees it, whoever provides it: a filter of
// generated/registry.hpp chosen by name (m7, m8, m12 on BCC, fcc6 on FCC, tricubic and cart7 on
// the Cartesian lattice, ...), a user's own emitted header (emitted_filter<Traits>() of
// runtime/emitted_filter.h), or any other FilterSource, such as one loaded at run time. A
// SplineFilter is a cheap handle (copies share the source). Reconstructor (reconstruction.h)
// evaluates it on a volume of its lattice; resample, evaluable_region and default_box
// (resample.h) take it too.
#pragma once
#include <array>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "runtime/coset_lattice.h"
#include "runtime/prefilter.h"
#include "runtime/prefilter_choice.h"

namespace boxgen::runtime {

// Offsets j_a - floor(x_a + centre_a) of every lattice point the evaluator of a filter may fetch,
// per axis, and the centre shift c: published by the generator with each evaluator
// (kStencilReachLo/Hi, kCentre). runtime/resample.h explains the region this gives.
struct StencilReach {
  std::array<int, 3> lo{}, hi{};
  Vec3 centre{};
};

template <class T>
class EvaluationPath;

// An emitted GLSL evaluator for the GL device (runtime/gl/gl_spline.h): the prefix of its
// functions (NAME_value, ...) and its text (NAME.glsl, tables `const`); and, as data from the
// generator's emission beside the text, the same evaluator with its run-time-indexed tables in
// the storage block NAME_Tables and the block's contents (runtime/gl/glsl_tables.h). Those two
// are empty for a text read from a file.
struct GlslEvaluator {
  std::string name;
  std::string text;
  std::string buffered = {};
  std::vector<int> block = {};
};

// What the runtime needs from a filter. Implement it to plug in a filter from elsewhere: the
// evaluation paths come from the runtime's engine (EmittedSplinePath of emitted_spline.h) or
// from your own code.
class FilterSource {
 public:
  virtual ~FilterSource() = default;
  virtual std::string name() const = 0;
  // The lattice the filter was derived on; a volume must hold the same points.
  virtual CosetLattice lattice() const = 0;
  virtual StencilReach reach() const = 0;
  // The FIR prefilter q (Q^I for q1, Q^II for q2); std::invalid_argument (one line) when there
  // is none.
  virtual PrefilterTaps prefilter(PrefilterChoice q) const = 0;
  // k: q1 and q2 reproduce every polynomial of degree < k.
  virtual int approximation_order() const = 0;
  // Evaluation on `volume` (already checked to be on the filter's lattice); the path may keep a
  // pointer to the volume, which outlives it.
  virtual std::shared_ptr<const EvaluationPath<float>> path(
      const LatticeVolume<float>& volume) const = 0;
  virtual std::shared_ptr<const EvaluationPath<double>> path(
      const LatticeVolume<double>& volume) const = 0;
  // The filter's own GLSL evaluator (float, or double precision) for the GL device, when it
  // carries one: a SPEC compiled by the loader does (loader/filter_loader.h). The registry's
  // come from the GL device's build (gl::filter_glsl); an emitted header's from its NAME.glsl.
  virtual std::optional<GlslEvaluator> glsl(bool /*double_precision*/) const {
    return std::nullopt;
  }
};

class SplineFilter {
 public:
  // The registry's filters: by name (generated::kFilterNames; anything else is
  // std::invalid_argument, one line naming them), by position (0 <= index < count()).
  static SplineFilter parse(std::string_view name);
  static SplineFilter at(int index);
  static int count();
  // "m7, m8, m12, fcc6, tricubic or cart7": the registry's names, for messages and help texts.
  static std::string names();

  explicit SplineFilter(std::shared_ptr<const FilterSource> source);

  const std::string& name() const noexcept { return name_; }
  // The position in generated/registry.hpp (whose filters have SIMD kernels), or -1.
  int registry_index() const noexcept { return registry_index_; }
  const CosetLattice& lattice() const noexcept { return lattice_; }
  StencilReach reach() const { return source_->reach(); }
  // The taps of a FIR prefilter: Q^I or Q^II, qfir:K (fir_interpolation.h); none: the identity
  // {(0,0,0), 1}. Any other choice (interp) is std::invalid_argument, one line.
  PrefilterTaps prefilter(PrefilterChoice q) const;
  int approximation_order() const { return source_->approximation_order(); }
  // Coset cells of margin beyond [-1,1]^3 that cube_lattice_grid needs for reconstruction with
  // this filter after prefilter q under the strict boundary (the one formula of the runtime:
  // spline_filter.cpp); for interp, the margin after which the faces' influence has decayed below
  // 1e-6 of the data (interpolation_margin in interpolation.h).
  int required_margin(PrefilterChoice q) const;
  // Throws std::invalid_argument (one line) unless the volume holds the points of the filter's
  // lattice: "filter fcc6 is for the fcc lattice, but the volume is on the bcc lattice".
  void check_lattice(const CosetLattice& volume_lattice) const;
  const FilterSource& source() const noexcept { return *source_; }

  bool operator==(const SplineFilter& other) const noexcept { return source_ == other.source_; }

 private:
  SplineFilter(std::shared_ptr<const FilterSource> source, int registry_index);
  std::shared_ptr<const FilterSource> source_;
  std::string name_;
  CosetLattice lattice_;
  int registry_index_ = -1;
};

}  // namespace boxgen::runtime
