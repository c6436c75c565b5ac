// The GL device (docs/gpu.md "The GL device", docs/design.md §16): a volume of any lattice in a
// shader storage buffer (all cosets, the storage order of lattice_volume.h) and an emitted GLSL
// evaluator (`boxgen emit --target glsl`) compiled at run time into compute shaders that evaluate
// batches of points (one invocation per point) and render isosurfaces (one per pixel). Float or
// double as the volume's T. The contract is Reconstructor's (reconstruction.h): the same values
// within the precision's rounding, the same errors (a point whose stencil leaves the volume is
// std::out_of_range naming it; the message comes from the CPU path, which re-evaluates only the
// failing point). No GL type appears here.
#pragma once
#include <memory>
#include <span>
#include <string>
#include <vector>

#include "runtime/gl/gl_context.h"
#include "runtime/gl/glsl_tables.h"
#include "runtime/reconstruction.h"
#include "runtime/render.h"
#include "runtime/resample.h"

namespace boxgen::runtime::gl {

// The GLSL evaluator (runtime::GlslEvaluator, spline_filter.h) of a registry filter as this build
// emitted it (float, or double precision), with its tables as data; GlError for a name outside
// the registry.
GlslEvaluator registry_glsl(const std::string& name, bool double_precision);
// The GLSL evaluator of any filter that has one: a registry filter's (registry_glsl), or the one
// its source carries (a SPEC from loader::load_filter). GlError for a filter without one (an
// emitted header's: read_glsl its NAME.glsl).
GlslEvaluator filter_glsl(const SplineFilter& filter, bool double_precision);
// A user's emitted NAME.glsl: the name is the file's stem; text only, so the device uses its
// tables as the file declares them (`const`). GlError if it cannot be read.
GlslEvaluator read_glsl(const std::string& path);

// A picture's parameters for the GPU's renderer: render.h's camera, the caster's march
// (RayCaster) and shade_pixels' colours.
struct FrameOptions {
  Camera camera;
  int width = 0, height = 0;
  Box box;
  double iso = 0.5, step = 0;
  bool cutaway = false, curvature = false;
  double value_lo = 0, value_hi = 1;  // RenderOptions' cut-face colour map
  double curvature_scale = 0;         // shading_curvature_scale
  Vec3 light{};                       // shading_light
};

// Where a frame's time goes (boxrecon bench, render), in seconds: the dispatch waited for, and the
// rest on the CPU (the caller's set-up, the read back, the unpacking of the pixels; not the
// compile of the kernel on its first use).
struct FrameTimes {
  double gpu = 0, cpu = 0;
};

template <class T>
class GlSpline {
 public:
  // Compiles nothing yet (each kernel on first use) but uploads the volume. Throws GlError when
  // there is no GL context or the volume exceeds the device's storage block (or 2^31 samples),
  // std::invalid_argument when the volume is not on the filter's lattice. The volume must outlive
  // this object. `tables`: where the evaluator's run-time-indexed tables live (glsl_tables.h);
  // `buffer` needs the evaluator's block (not in a text read from a file: then `const`).
  GlSpline(const LatticeVolume<T>& volume, const SplineFilter& filter, GlslEvaluator glsl,
           TableStorage tables = TableStorage::buffer);
  ~GlSpline();
  GlSpline(const GlSpline&) = delete;
  GlSpline& operator=(const GlSpline&) = delete;

  // Reconstructor::evaluate on the GPU: gradients and hessians empty (not computed) or as long as
  // points (hessians need gradients).
  void evaluate(std::span<const Vec3> points, std::span<T> values, std::span<Vec3> gradients = {},
                std::span<Hessian> hessians = {}) const;

  // For timing (boxrecon bench): the points uploaded once, then the kernel of the given order
  // (0 value, 1 + gradient, 2 + Hessian; kFetchFloor: the same number of samples read and summed
  // per point with no arithmetic) run and waited for, the results left on the device.
  static constexpr int kFetchFloor = -1;
  void upload(std::span<const Vec3> points) const;
  void run(int order) const;

  // The picture as render_isosurface (render.h) draws it, one invocation per pixel: the camera's
  // ray marched to the first crossing into the solid {s >= iso} (minus the cut-away), the hit's
  // normal and principal curvatures from the emitted gradient and Hessian, the colours of
  // shade_pixels. std::out_of_range when a ray reads samples outside the volume.
  // `times`, where given, receives the time of the dispatch (gpu) and adds the rest to cpu.
  RgbBuffer render(const FrameOptions& options, FrameTimes* times = nullptr) const;

  // The compute shader of a kernel as the device compiles it (kind: an order 0-2 of run,
  // kFetchFloor, or kFrame for render), for inspection: tests/gl reads its syntax tree.
  static constexpr int kFrame = 3;
  std::string kernel_source(int kind) const;

  const LatticeVolume<T>& volume() const noexcept { return *volume_; }
  const GlslEvaluator& evaluator() const noexcept { return glsl_; }

 private:
  unsigned program(int kind) const;
  void dispatch(unsigned program, std::size_t count) const;
  [[noreturn]] void throw_point_error(std::span<const Vec3> points, std::size_t index) const;

  const LatticeVolume<T>* volume_;
  Reconstructor<T> cpu_;  // the errors' messages, and the filter's lattice check
  GlslEvaluator glsl_;
  std::string shader_text_;  // glsl_.text, its tables moved as `tables` says
  unsigned samples_ = 0, lattice_table_ = 0, tables_ = 0;
  // Scratch buffers of the batches and pictures (const calls reuse them; one thread uses the
  // device).
  mutable unsigned points_ = 0, results_ = 0, status_ = 0;
  mutable std::size_t uploaded_ = 0;
  mutable std::vector<unsigned> programs_;
};

extern template class GlSpline<float>;
extern template class GlSpline<double>;

}  // namespace boxgen::runtime::gl
