#include "runtime/render.h"

#include <fmt/format.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdio>
#include <stdexcept>
#include <utility>
#include <vector>

#include "runtime/frame_box.h"
#include "runtime/percentiles.h"

namespace boxgen::runtime {

namespace {

Vec3 add(const Vec3& a, const Vec3& b) { return {a[0] + b[0], a[1] + b[1], a[2] + b[2]}; }
Vec3 scale(const Vec3& a, double s) { return {a[0] * s, a[1] * s, a[2] * s}; }
double dot(const Vec3& a, const Vec3& b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }
Vec3 cross(const Vec3& a, const Vec3& b) {
  return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
}
Vec3 normalise(const Vec3& a) { return scale(a, 1 / std::sqrt(dot(a, a))); }

// A perceptual colour map (dark blue -> green -> yellow) for the cut faces.
Vec3 value_colour(double t) {
  static const double stops[5][3] = {{0.267, 0.005, 0.329},
                                     {0.230, 0.322, 0.546},
                                     {0.128, 0.567, 0.551},
                                     {0.369, 0.789, 0.383},
                                     {0.993, 0.906, 0.144}};
  t = std::clamp(std::isfinite(t) ? t : 0.0, 0.0, 1.0) * 4;
  const int i = std::min(3, static_cast<int>(t));
  const double f = t - i;
  return {(1 - f) * stops[i][0] + f * stops[i + 1][0], (1 - f) * stops[i][1] + f * stops[i + 1][1],
          (1 - f) * stops[i][2] + f * stops[i + 1][2]};
}

// Principal curvatures to a colour: u >= v in (-1, 1) after tanh(k * scale); their mean pulls
// grey towards orange (convex) or blue (concave), their difference towards green (saddles).
Vec3 curvature_colour(double k1, double k2, double scale_) {
  const double u = std::tanh(k1 * scale_), v = std::tanh(k2 * scale_);
  const double mean = 0.5 * (u + v), spread = std::clamp(0.5 * (u - v), 0.0, 1.0);
  Vec3 c{0.80, 0.80, 0.80};
  const Vec3 target = mean > 0 ? Vec3{1.0, 0.55, 0.15} : Vec3{0.2, 0.4, 1.0};
  for (int i = 0; i < 3; ++i) c[i] += std::abs(mean) * (target[i] - c[i]);
  const Vec3 saddle{0.25, 0.8, 0.3};
  const double w = spread * (1 - std::abs(mean));
  for (int i = 0; i < 3; ++i) c[i] += w * (saddle[i] - c[i]);
  return c;
}

constexpr double kPi = 3.14159265358979;

}  // namespace

Vec3 Camera::ray(int x, int y, int width, int height) const {
  const double sx = (2 * (x + 0.5) / width - 1) * tan_half * width / height;
  const double sy = (1 - 2 * (y + 0.5) / height) * tan_half;
  return normalise(add(forward, add(scale(right, sx), scale(up, sy))));
}

Camera camera_for(const Box& box, const CameraView& view) {
  if (view.frame) {  // the world's camera, its eye and axes taken into the volume's frame
    CameraView in_world = view;
    in_world.frame.reset();
    const Camera w = camera_for(world_box(box, view.frame), in_world);
    const Affine to_volume = view.frame->inverse();
    Affine turn = to_volume;
    turn.translation = {0, 0, 0};
    Camera c = w;
    c.eye = to_volume.apply(w.eye);
    c.forward = turn.apply(w.forward);
    c.right = turn.apply(w.right);
    c.up = turn.apply(w.up);
    return c;
  }
  const bool angles = view.azimuth || view.elevation;
  if (view.closeup && (angles || view.distance))
    throw std::invalid_argument(
        "--closeup is a fixed camera: leave out --azimuth, --elevation and --distance");
  if ((view.azimuth && !std::isfinite(*view.azimuth)) ||
      (view.elevation && !(std::abs(*view.elevation) < 90)))
    throw std::invalid_argument("--azimuth must be finite and --elevation between -90 and 90");
  const double distance = view.distance.value_or(1.6);
  if (!(distance > 0) || !std::isfinite(distance))
    throw std::invalid_argument("--distance must be > 0 (box diagonals from the centre)");
  const Vec3 centre = scale(add(box.min, box.max), 0.5);
  const double radius =
      0.5 * std::sqrt(dot(add(box.max, scale(box.min, -1)), add(box.max, scale(box.min, -1))));
  Vec3 eye, target;
  double fov;
  if (view.closeup) {  // Fig. 9: the first rims seen from above, at a grazing angle
    target = add(centre, scale(Vec3{-0.3, -0.3, -0.12}, radius));
    eye = add(centre, scale(Vec3{0.75, 0.55, 0.95}, radius));
    fov = 38;
  } else {  // Fig. 8: the whole cube from above one corner, looking into the cut-away
    const Vec3 fig8{1.0, 0.78, 0.82};
    Vec3 direction = normalise(fig8);
    if (angles) {  // the unset angle keeps Fig. 8's
      const double a = view.azimuth.value_or(std::atan2(fig8[1], fig8[0]) * 180 / kPi) * kPi / 180;
      const double e = view.elevation.value_or(std::asin(direction[2]) * 180 / kPi) * kPi / 180;
      direction = {std::cos(e) * std::cos(a), std::cos(e) * std::sin(a), std::sin(e)};
    }
    target = add(centre, Vec3{0, 0, -0.08 * radius});
    eye = add(centre, scale(direction, 2 * distance * radius));
    fov = 36;
  }
  Camera c;
  c.eye = eye;
  c.forward = normalise(add(target, scale(eye, -1)));
  c.right = normalise(cross(c.forward, Vec3{0, 0, 1}));
  c.up = cross(c.right, c.forward);
  c.tan_half = std::tan(fov * kPi / 360);
  return c;
}

namespace {

// [t0, t1] of the ray inside the box; false if it misses.
bool clip_to_box(const Vec3& o, const Vec3& d, const Box& box, double& t0, double& t1) {
  t0 = 0;
  t1 = 1e300;
  for (int i = 0; i < 3; ++i) {
    if (std::abs(d[i]) < 1e-300) {
      if (o[i] < box.min[i] || o[i] > box.max[i]) return false;
      continue;
    }
    double a = (box.min[i] - o[i]) / d[i], b = (box.max[i] - o[i]) / d[i];
    if (a > b) std::swap(a, b);
    t0 = std::max(t0, a);
    t1 = std::min(t1, b);
  }
  return t1 > t0;
}

}  // namespace

RayCaster::RayCaster(const Reconstructor<double>& spline, const Box& box, double iso, double step,
                     bool cutaway, bool curvature)
    : RayCaster([&spline](const Vec3& p, Vec3* gradient,
                          Hessian* hessian) { return spline.value(p, gradient, hessian); },
                box, iso, step, cutaway, curvature) {}

RayCaster::RayCaster(SplineFunction spline, const Box& box, double iso, double step, bool cutaway,
                     bool curvature)
    : spline_(std::move(spline)),
      box_(box),
      iso_(iso),
      step_(step),
      cutaway_(cutaway),
      curvature_(curvature) {
  if (!std::isfinite(iso)) throw std::invalid_argument("--iso must be finite");
  if (!(step > 0) || !std::isfinite(step))
    throw std::invalid_argument("the marching step must be > 0");
  for (int i = 0; i < 3; ++i)
    if (!(box.max[i] > box.min[i])) throw std::invalid_argument("the render box is empty");
  mid_ = scale(add(box.min, box.max), 0.5);
  size_ = std::sqrt(dot(add(box.max, scale(box.min, -1)), add(box.max, scale(box.min, -1))));
  // A ray crosses at most the box's diagonal: a step that gives more samples than the bound would
  // run for hours (or, below the coordinates' rounding, for ever).
  if (size_ / step > static_cast<double>(kMaxStepsPerRay))
    throw std::invalid_argument(fmt::format(
        "the marching step {:.3g} gives up to {:.3g} samples per ray across the box "
        "(diagonal {:.3g}); the limit is {}: use a step of at least {:.3g}",
        step, size_ / step, size_, kMaxStepsPerRay, size_ / static_cast<double>(kMaxStepsPerRay)));
}

bool RayCaster::in_region(const Vec3& p) const {
  if (!cutaway_) return true;
  return !(p[2] > mid_[2] && (p[0] > mid_[0] || p[1] > mid_[1]));
}

bool RayCaster::inside(const Vec3& p) const {
  return in_region(p) && spline_(p, nullptr, nullptr) >= iso_;
}

// Principal curvatures of the level set through a point from the spline's gradient and Hessian
// {xx, xy, xz, yy, yz, zz}: the eigenvalues of -P H P / |g| (P the projection onto the tangent
// plane, n = -g/|g|) from its trace and Frobenius norm (the third eigenvalue is 0).
static void principal_curvatures(const Vec3& gradient, const Hessian& hs, double& k1, double& k2) {
  const double H[3][3] = {{hs[0], hs[1], hs[2]}, {hs[1], hs[3], hs[4]}, {hs[2], hs[4], hs[5]}};
  const double glen = std::sqrt(dot(gradient, gradient));
  const Vec3 n = scale(gradient, -1 / glen);
  double P[3][3], PH[3][3];
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) P[i][j] = (i == j ? 1.0 : 0.0) - n[i] * n[j];
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) {
      PH[i][j] = 0;
      for (int k = 0; k < 3; ++k) PH[i][j] += P[i][k] * H[k][j];
    }
  double trace = 0, frob2 = 0;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) {
      double g = 0;
      for (int k = 0; k < 3; ++k) g -= PH[i][k] * P[k][j] / glen;
      frob2 += g * g;
      if (i == j) trace += g;
    }
  const double root = std::sqrt(std::max(0.0, 2 * frob2 - trace * trace));
  k1 = 0.5 * (trace + root);
  k2 = 0.5 * (trace - root);
}

// The first t in [t0, t1] where the ray enters the solid: marching by the step, then bisection
// on the spline between the last point outside and the first inside. entry_face: inside at t0.
bool RayCaster::first_crossing(const Vec3& o, const Vec3& d, double t0, double t1, double& t,
                               bool& entry_face) const {
  entry_face = inside(add(o, scale(d, t0)));
  if (entry_face) {
    t = t0;
    return true;
  }
  double prev = t0;
  // Steps counted, not accumulated: t0 + k step always moves on (the constructor bounds k).
  for (std::int64_t k = 1;; ++k) {
    const double ss = std::min(t0 + static_cast<double>(k) * step_, t1);
    if (inside(add(o, scale(d, ss)))) {
      double lo = prev, hi = ss;
      while (hi - lo > 1e-9 * size_) {
        const double m = 0.5 * (lo + hi);
        (inside(add(o, scale(d, m))) ? hi : lo) = m;
      }
      t = hi;
      return true;
    }
    prev = ss;
    if (ss >= t1) return false;
  }
}

// The outward normal of the cut or box face nearest to p, facing against the ray direction d.
Vec3 RayCaster::face_normal(const Vec3& p, const Vec3& d) const {
  int axis = 0;
  double best = 1e300;
  for (int i = 0; i < 3; ++i) {
    const double gap = std::min(
        {std::abs(p[i] - mid_[i]), std::abs(p[i] - box_.min[i]), std::abs(p[i] - box_.max[i])});
    if (gap < best) {
      best = gap;
      axis = i;
    }
  }
  Vec3 normal{0, 0, 0};
  normal[axis] = d[axis] > 0 ? -1 : 1;
  return normal;
}

RayHit RayCaster::cast(const Vec3& origin, const Vec3& direction) const {
  RayHit h;
  const Vec3 d = normalise(direction);
  double t0, t1;
  if (!clip_to_box(origin, d, box_, t0, t1)) return h;
  t0 += 1e-9 * size_;
  t1 -= 1e-9 * size_;
  bool entry_face = false;
  h.hit = first_crossing(origin, d, t0, t1, h.t, entry_face);
  if (!h.hit) return h;
  h.point = add(origin, scale(d, h.t));
  Vec3 gradient{};
  h.value = spline_(h.point, &gradient, nullptr);
  // The isosurface when the point just before the hit is still in the region, else a cut or box
  // face.
  h.on_cut = entry_face || !in_region(add(origin, scale(d, h.t - 2e-9 * size_)));
  if (!h.on_cut && dot(gradient, gradient) > 0) {
    h.normal = normalise(scale(gradient, -1));  // s grows into the solid
    if (curvature_) {
      Hessian hs{};
      spline_(h.point, &gradient, &hs);  // the gradient of the Hessian's path, with it
      principal_curvatures(gradient, hs, h.k1, h.k2);
    }
  } else {
    h.on_cut = true;
    h.normal = face_normal(h.point, d);
  }
  if (dot(h.normal, d) > 0) h.normal = scale(h.normal, -1);
  return h;
}

namespace {

// The picture from each pixel's hit: hit(x, y, direction) for the ray from the camera's eye
// through pixel (x, y), shaded (normal or curvature colours, cut faces by value), rows in
// parallel. runtime/gl's frame kernel transcribes it.
using PixelHit = std::function<RayHit(int x, int y, const Vec3& direction)>;
RgbBuffer shade_pixels(const RenderOptions& o, const Box& box, double spacing,
                       const PixelHit& hit) {
  const double curvature_scale = shading_curvature_scale(spacing);
  const Camera cam = camera_for(box, o.camera);
  const Vec3 light = shading_light(cam);
  RgbBuffer image{o.width, o.height,
                  std::vector<std::uint8_t>(static_cast<std::size_t>(o.width) * o.height * 3)};
  std::atomic<int> rows_done{0};
  const bool bar = o.progress && ::isatty(STDERR_FILENO);
#pragma omp parallel for schedule(dynamic, 1)
  for (int y = 0; y < o.height; ++y) {
    for (int x = 0; x < o.width; ++x) {
      const Vec3 d = cam.ray(x, y, o.width, o.height);
      // Background: a light vertical gradient.
      Vec3 colour{0.93 - 0.12 * (y / static_cast<double>(o.height)),
                  0.94 - 0.1 * (y / static_cast<double>(o.height)), 0.96};
      const RayHit h = hit(x, y, d);
      if (h.hit) {
        Vec3 base = h.on_cut ? value_colour((h.value - o.value_lo) / (o.value_hi - o.value_lo))
                             : Vec3{0.82, 0.80, 0.76};
        if (!h.on_cut && o.shading == Shading::Curvature)
          base = curvature_colour(h.k1, h.k2, curvature_scale);
        const double diffuse = std::max(0.0, dot(h.normal, light));
        const Vec3 half = normalise(add(light, scale(d, -1)));
        const double specular =
            h.on_cut ? 0 : 0.25 * std::pow(std::max(0.0, dot(h.normal, half)), 40);
        for (int c = 0; c < 3; ++c)
          colour[c] = std::min(1.0, base[c] * (0.28 + 0.72 * diffuse) + specular);
      }
      const std::size_t i = (static_cast<std::size_t>(y) * o.width + x) * 3;
      for (int c = 0; c < 3; ++c)
        image.pixels[i + c] =
            static_cast<std::uint8_t>(std::lround(255 * std::clamp(colour[c], 0.0, 1.0)));
    }
    const int done = ++rows_done;
    if (bar && (done % 8 == 0 || done == o.height)) {
#pragma omp critical
      std::fprintf(stderr, "\rrendering %3d%%", 100 * done / o.height);
    }
  }
  if (bar) std::fprintf(stderr, "\n");
  return image;
}

// The image of the caster's isosurface; `spacing` is the volume's (the default step, curvature
// scale).
RgbBuffer render_with(const SplineFunction& spline, double spacing, const Box& box,
                      const RenderOptions& o) {
  const RayCaster caster(spline, box, o.iso, render_step(o, spacing), o.cutaway,
                         o.shading == Shading::Curvature);
  const Vec3 eye = camera_for(box, o.camera).eye;
  return shade_pixels(o, box, spacing,
                      [&](int, int, const Vec3& d) { return caster.cast(eye, d); });
}

}  // namespace

double render_step(const RenderOptions& o, double spacing) {
  if (o.width < 1 || o.height < 1 || o.width > 8192 || o.height > 8192)
    throw std::invalid_argument(
        fmt::format("image size must be 1..8192 per side, got {} x {}", o.width, o.height));
  if (!(o.value_hi > o.value_lo) || !std::isfinite(o.value_lo) || !std::isfinite(o.value_hi))
    throw std::invalid_argument(
        fmt::format("the cut faces' value range [{}, {}] must be finite and not empty", o.value_lo,
                    o.value_hi));
  return o.step > 0 ? o.step : 0.5 * spacing;
}

Vec3 shading_light(const Camera& cam) {
  return normalise(add(scale(cam.forward, -1), add(scale(cam.up, 0.6), scale(cam.right, -0.3))));
}

double shading_curvature_scale(double spacing) { return 5 * spacing; }

RgbBuffer render_isosurface(const LatticeVolume<double>& volume, const SplineFilter& f,
                            const Box& box, const RenderOptions& o) {
  const Reconstructor<double> spline(volume, f);
  return render_with([&spline](const Vec3& p, Vec3* gradient,
                               Hessian* hessian) { return spline.value(p, gradient, hessian); },
                     *std::min_element(volume.axis_spacing().begin(), volume.axis_spacing().end()),
                     box, o);
}

IsoChoice percentile_iso(std::span<const double> samples) {
  const std::vector<double> p = percentiles(samples, {0.01, 0.99});
  return {0.5 * (p[0] + p[1]), p[0], p[1]};
}

}  // namespace boxgen::runtime
