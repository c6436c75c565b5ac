// Ray-cast isosurfaces of a reconstructed spline (the paper's Figs. 8-9, rendered in the paper
// with POV-Ray and finite-difference normals). Every ray is marched through the box in steps of
// a fraction of the lattice spacing; where the sign of s(x) - iso changes, the crossing is
// bracketed and refined by bisection on the spline itself until the bracket is below 1e-9 of the
// box's diagonal (the step is small enough for the ML surface's ripples; a feature thinner than
// the step can be stepped over). Normals come from the spline's analytic gradient. Optionally the
// 3/8 cut-away of Fig. 8 removes {z > 0 and (x > 0 or y > 0)}; the cut faces show the value of the
// spline as a colour (the cross-section view). With curvature shading the isosurface is coloured
// by its principal curvatures from the exact Hessian (as the paper's author does in his own ray
// caster): convex orange, concave blue, saddles green, flat grey, saturating at curvature radii of
// about five lattice spacings. The cut faces are coloured over a value range (the data's, for a
// volume). Rows are spread over all cores (OpenMP).
#pragma once
#include <cstdint>
#include <functional>
#include <optional>
#include <span>
#include <vector>

#include "runtime/affine.h"
#include "runtime/reconstruction.h"
#include "runtime/resample.h"

namespace boxgen::runtime {

enum class Shading { Normal, Curvature };

// Where the camera stands (docs/runtime.md, "Camera"). The default view: the eye at distance 1.6
// box diagonals from the box's centre in the direction (1, 0.78, 0.82) (azimuth 37.95 degrees,
// elevation 32.89 degrees), looking at the centre lowered by 0.04 diagonals, field of view 36
// degrees. Azimuth turns the eye about the z axis from +x towards +y, elevation lifts it above the
// xy plane; an angle left unset keeps the default view's.
struct CameraView {
  std::optional<double> azimuth, elevation;  // degrees; |elevation| < 90
  std::optional<double> distance;  // from the box's centre in box diagonals, > 0; default 1.6
  bool closeup = false;            // the fixed camera of Fig. 9, close to the top rims (no angles)
  // An oblique volume's map from its own frame (where the box and the volume lie) to world
  // (SourceSamples::frame; a rotation): the camera is then the world's, placed for the world's
  // box around the box's image, and given in the volume's frame.
  std::optional<Affine> frame;
};

// A pinhole camera: the eye, its unit frame and tan(field of view / 2). The one camera of every
// renderer (the CPU ray caster here, the GPU one): ray() is the direction through a pixel.
struct Camera {
  Vec3 eye{}, forward{}, right{}, up{};
  double tan_half = 0;
  // The unit direction through the centre of pixel (x, y) of a width x height image (y down).
  Vec3 ray(int x, int y, int width, int height) const;
};

// The camera of `view` for `box`. Throws std::invalid_argument for a non-finite angle, an
// elevation outside (-90, 90), a distance <= 0 or not finite, or angles with the close-up.
Camera camera_for(const Box& box, const CameraView& view);

struct RenderOptions {
  int width = 512, height = 512;
  Shading shading = Shading::Normal;  // Curvature: colour by the principal curvatures (k1, k2)
  double iso = 0.5;
  bool cutaway = false;
  CameraView camera;
  double value_lo = 0, value_hi = 1;  // the values the cut faces' colour map spans
  double step = 0;                    // marching step (world); 0: half the volume's spacing
  bool progress = false;              // a progress bar on stderr
};

// The default iso value of a volume: the midpoint of the 1st and 99th percentiles of its samples
// (each percentile interpolated linearly between the two nearest ranks, as NumPy's default).
// Throws std::invalid_argument for no samples.
struct IsoChoice {
  double iso, p1, p99;
};
IsoChoice percentile_iso(std::span<const double> samples);

struct RgbBuffer {
  int width = 0, height = 0;
  std::vector<std::uint8_t> pixels;  // row-major RGB, top row first
};

// The first boundary of the solid {s >= iso} (minus the cut-away) along a ray, inside the box.
struct RayHit {
  bool hit = false;
  bool on_cut = false;     // a cut-away or box face rather than the isosurface
  double t = 0;            // distance along the normalised direction
  Vec3 point{}, normal{};  // normal: unit, facing the ray; on the isosurface -grad s / |grad s|
  double value = 0;        // s at the point
  // Principal curvatures k1 >= k2 of the isosurface at the point (when the caster was asked for
  // them and the hit is on the isosurface), from the exact gradient g and Hessian H:
  // G = -P H P / |g| with P = I - n n^T, k = (tr G +- sqrt(2 |G|_F^2 - tr(G)^2)) / 2; positive
  // where the solid {s >= iso} is convex (a ball of radius r: k1 = k2 = 1/r).
  double k1 = 0, k2 = 0;
};

// The spline a caster marches, at a world point: its value, and its gradient and Hessian (world
// units) where the pointers are not null; a Reconstructor<double> gives one.
using SplineFunction = std::function<double(const Vec3&, Vec3*, Hessian*)>;

// The most samples a ray may take across the box (its diagonal divided by the step): 2^16, about
// 300 times the default step's count on a 64^3 volume.
inline constexpr std::int64_t kMaxStepsPerRay = std::int64_t{1} << 16;

class RayCaster {
 public:
  // Throws std::invalid_argument for a non-finite iso, a step <= 0, a step that gives more than
  // kMaxStepsPerRay samples across the box's diagonal, or an empty box.
  RayCaster(const Reconstructor<double>& spline, const Box& box, double iso, double step,
            bool cutaway, bool curvature = false);
  RayCaster(SplineFunction spline, const Box& box, double iso, double step, bool cutaway,
            bool curvature = false);
  RayHit cast(const Vec3& origin, const Vec3& direction) const;

 private:
  bool in_region(const Vec3& p) const;
  bool inside(const Vec3& p) const;
  bool first_crossing(const Vec3& o, const Vec3& d, double t0, double t1, double& t,
                      bool& entry_face) const;
  Vec3 face_normal(const Vec3& p, const Vec3& d) const;
  SplineFunction spline_;
  Box box_;
  double iso_, step_;
  bool cutaway_, curvature_;
  Vec3 mid_{};
  double size_ = 0;
};

// The marching step of the options for a volume of this spacing (half of it by default); throws
// std::invalid_argument for an image size outside 1..8192.
double render_step(const RenderOptions& options, double spacing);

// The shading's light (a unit vector, from the camera's frame) and the scale of the principal
// curvatures in the curvature colours (from the volume's spacing): the CPU renderer's and the GL
// device's.
Vec3 shading_light(const Camera& camera);
double shading_curvature_scale(double spacing);

// Renders the isosurface s = iso of the spline reconstructed from `volume` with filter f (the
// volume already prefiltered, as for Reconstructor) inside `box` (where the stencil fits, e.g.
// default_box). Throws std::invalid_argument for a bad size, iso or step, or a volume of another
// lattice than f's (one line).
RgbBuffer render_isosurface(const LatticeVolume<double>& volume, const SplineFilter& f,
                            const Box& box, const RenderOptions& options);

}  // namespace boxgen::runtime
