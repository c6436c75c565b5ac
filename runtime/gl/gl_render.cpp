#include "runtime/gl/gl_render.h"

#include <algorithm>
#include <stdexcept>
#include <vector>

namespace boxgen::runtime::gl {

template <class T>
RgbBuffer render_isosurface(const GlSpline<T>& spline, const Box& box, const RenderOptions& o) {
  const LatticeVolume<T>& volume = spline.volume();
  const double spacing =
      *std::min_element(volume.axis_spacing().begin(), volume.axis_spacing().end());
  const double step = render_step(o, spacing);
  const bool curvature = o.shading == Shading::Curvature;
  // The CPU caster checks the iso, step and box and finishes the GPU's hits; it never evaluates.
  const RayCaster caster(
      [](const Vec3&, Vec3*, Hessian*) -> double {
        throw std::logic_error("the GL render evaluates on the GPU");
      },
      box, o.iso, step, o.cutaway, curvature);
  const Camera camera = camera_for(box, o.camera);
  std::vector<Vec3> directions(static_cast<std::size_t>(o.width) * o.height);
#pragma omp parallel for
  for (int y = 0; y < o.height; ++y)
    for (int x = 0; x < o.width; ++x)
      directions[static_cast<std::size_t>(y) * o.width + x] = camera.ray(x, y, o.width, o.height);
  const std::vector<MarchedRay> rays =
      spline.march(camera.eye, directions, {box, o.iso, step, o.cutaway});
  RenderOptions shading = o;
  shading.progress = false;  // the march is done: shading takes milliseconds
  return shade_pixels(shading, box, spacing, [&](int x, int y, const Vec3& d) {
    const MarchedRay& r = rays[static_cast<std::size_t>(y) * o.width + x];
    if (!r.hit) return RayHit{};
    return caster.hit_at(camera.eye, d, r.t, r.face, r.value, r.gradient,
                         [&r](Vec3&) { return r.hessian; });
  });
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
                            bool double_precision) {
  if (double_precision) {
    const GlSpline<double> spline(volume, f, glsl);
    return render_isosurface(spline, box, o);
  }
  const LatticeVolume<float> single = float_volume(volume);
  const GlSpline<float> spline(single, f, glsl);
  return render_isosurface(spline, box, o);
}

template RgbBuffer render_isosurface(const GlSpline<float>&, const Box&, const RenderOptions&);
template RgbBuffer render_isosurface(const GlSpline<double>&, const Box&, const RenderOptions&);

}  // namespace boxgen::runtime::gl
