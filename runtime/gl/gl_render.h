// render_isosurface (runtime/render.h) on the GL device: the whole frame on the GPU, one
// invocation per pixel (GlSpline::render): the camera's ray, the march, the hit's normal and
// principal curvatures, the colours. The options are checked, and the camera, step, light and
// curvature scale chosen, by the CPU renderer's own functions; the GPU's march and shading are a
// transcription of render.cpp's, held to the same picture by the render agreement test.
#pragma once
#include "runtime/gl/gl_spline.h"
#include "runtime/render.h"

namespace boxgen::runtime::gl {

// The picture of `spline`'s volume; throws as render_isosurface (bad size, iso or step) and
// GlError. `times`, where given, receives the frame's split (GlSpline::render).
template <class T>
RgbBuffer render_isosurface(const GlSpline<T>& spline, const Box& box, const RenderOptions& options,
                            FrameTimes* times = nullptr);

// The volume rendered with `glsl` (f's evaluator, emitted in double precision when
// double_precision, else in float: the volume's samples are rounded to float first).
RgbBuffer render_isosurface(const LatticeVolume<double>& volume, const SplineFilter& f,
                            const Box& box, const RenderOptions& options, const GlslEvaluator& glsl,
                            bool double_precision, FrameTimes* times = nullptr);

// A double volume as float (samples rounded as to_sample does).
LatticeVolume<float> float_volume(const LatticeVolume<double>& volume);

}  // namespace boxgen::runtime::gl
