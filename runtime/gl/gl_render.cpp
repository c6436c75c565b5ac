#include "runtime/gl/gl_render.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <type_traits>
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
  if constexpr (std::is_same_v<T, float>) {
    // Float rays: a march's point and its lattice coordinates carry float rounding of the
    // magnitudes involved (eye, box, origin), which at a face of a box that touches the evaluable
    // region (default_box: 16 double ulps inside it) can reach a sample outside the volume (the
    // 3% BCC MRI volume with m7 at 512 x 512). 64 float ulps of those magnitudes
    // inside the box (the camera stays the box's) cannot: far below a pixel.
    double magnitude = 0;
    for (int a = 0; a < 3; ++a)
      magnitude = std::max({magnitude, std::abs(f.camera.eye[a]), std::abs(box.min[a]),
                            std::abs(box.max[a]), std::abs(volume.origin()[a])});
    const double guard = 64 * std::numeric_limits<float>::epsilon() * magnitude;
    for (int a = 0; a < 3; ++a) {
      if (box.max[a] - box.min[a] > 4 * guard) {
        f.box.min[a] += guard;
        f.box.max[a] -= guard;
      }
    }
  }
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
