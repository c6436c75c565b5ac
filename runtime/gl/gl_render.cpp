#include "runtime/gl/gl_render.h"

#include <algorithm>
#include <chrono>
#include <stdexcept>
#include <vector>

namespace boxgen::runtime::gl {

template <class T>
RgbBuffer render_isosurface(const GlSpline<T>& spline, const Box& box, const RenderOptions& o,
                            FrameTimes* times) {
  using Clock = std::chrono::steady_clock;
  const Clock::time_point start = Clock::now();
  const LatticeVolume<T>& volume = spline.volume();
  const double spacing =
      *std::min_element(volume.axis_spacing().begin(), volume.axis_spacing().end());
  FrameOptions f;
  f.step = render_step(o, spacing);
  f.curvature = o.shading == Shading::Curvature;
  // The CPU caster checks the iso, step and box as the CPU renderer does; it never evaluates.
  (void)RayCaster(
      [](const Vec3&, Vec3*, Hessian*) -> double {
        throw std::logic_error("the GL render evaluates on the GPU");
      },
      box, o.iso, f.step, o.cutaway, f.curvature);
  f.camera = camera_for(box, o.camera);
  f.width = o.width;
  f.height = o.height;
  f.box = box;
  f.iso = o.iso;
  f.cutaway = o.cutaway;
  f.value_lo = o.value_lo;
  f.value_hi = o.value_hi;
  f.curvature_scale = shading_curvature_scale(spacing);
  f.light = shading_light(f.camera);
  if (times) times->cpu = std::chrono::duration<double>(Clock::now() - start).count();
  return spline.render(f, times);
}

LatticeVolume<float> float_volume(const LatticeVolume<double>& volume) {
  std::vector<float> samples(volume.sample_count());
  std::transform(volume.samples().begin(), volume.samples().end(), samples.begin(),
                 [](double s) { return to_sample<float>(s); });
  return LatticeVolume<float>(volume.lattice(), volume.sizes(), volume.axis_spacing(),
                              volume.origin(), std::move(samples));
}

RgbBuffer render_isosurface(const LatticeVolume<double>& volume, const SplineFilter& f,
                            const Box& box, const RenderOptions& o, const GlslEvaluator& glsl,
                            bool double_precision, FrameTimes* times) {
  if (double_precision) {
    const GlSpline<double> spline(volume, f, glsl);
    return render_isosurface(spline, box, o, times);
  }
  const LatticeVolume<float> single = float_volume(volume);
  const GlSpline<float> spline(single, f, glsl);
  return render_isosurface(spline, box, o, times);
}

template RgbBuffer render_isosurface(const GlSpline<float>&, const Box&, const RenderOptions&,
                                     FrameTimes*);
template RgbBuffer render_isosurface(const GlSpline<double>&, const Box&, const RenderOptions&,
                                     FrameTimes*);

}  // namespace boxgen::runtime::gl
