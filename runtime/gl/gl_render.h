// render_isosurface (runtime/render.h) on the GL device: the rays marched on the GPU, one
// invocation per pixel (GlSpline::march), each hit finished (normal, principal curvatures) and
// shaded by the CPU renderer's own code (RayCaster::hit_at, shade_pixels), so the camera, the
// step, the refinement, the cut-away and the colours have one implementation.
#pragma once
#include "runtime/gl/gl_spline.h"
#include "runtime/render.h"

namespace boxgen::runtime::gl {

// The picture of `spline`'s volume; throws as render_isosurface (bad size, iso or step) and
// GlError.
template <class T>
RgbBuffer render_isosurface(const GlSpline<T>& spline, const Box& box,
                            const RenderOptions& options);

// The volume rendered with `glsl` (f's evaluator, emitted in double precision when
// double_precision, else in float: the volume's samples are rounded to float first).
RgbBuffer render_isosurface(const LatticeVolume<double>& volume, const SplineFilter& f,
                            const Box& box, const RenderOptions& options, const GlslEvaluator& glsl,
                            bool double_precision);

// A double volume as float (samples rounded as to_sample does).
LatticeVolume<float> float_volume(const LatticeVolume<double>& volume);

}  // namespace boxgen::runtime::gl
