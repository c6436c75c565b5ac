// The renderer's ray caster (runtime/render.h) on a reconstructed Gaussian, whose isosurface
// s = 1/2 is close to the sphere |p| = 0.4 sqrt(2 ln 2): the hit lies on the spline's isosurface
// (s = iso to rounding), near the exact sphere (within the reconstruction error), with the
// normal of the analytic gradient; the cut-away turns the same ray into a hit on the cut face.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <vector>

#include "runtime/percentiles.h"
#include "runtime/render.h"
#include "runtime/sampling.h"
#include "runtime/test_functions.h"
#include "tests/support/bcc_volumes.h"

namespace boxgen::runtime {
namespace {

struct Scene {
  LatticeVolume<double> volume =
      prefilter(test::sample_bcc_cube<double>(
                    gaussian, 33, SplineFilter::parse("m7").required_margin(PrefilterChoice::Q1)),
                SplineFilter::parse("m7").prefilter(PrefilterChoice::Q1));
  Reconstructor<double> spline{volume, SplineFilter::parse("m7")};
  Box box{{-1, -1, -1}, {1, 1, 1}};
  double radius = kGaussianWidth * std::sqrt(2 * std::log(2.0));
};

TEST(RayCaster, HitsTheIsosurfaceWithTheGradientsNormal) {
  Scene s;
  const RayCaster caster(s.spline, s.box, 0.5, 0.5 * s.volume.spacing(), false);
  const RayHit h = caster.cast({3, 0.1, 0.05}, {-1, 0, 0});
  ASSERT_TRUE(h.hit);
  EXPECT_FALSE(h.on_cut);
  EXPECT_NEAR(h.value, 0.5, 1e-7);  // the root is on the spline itself
  EXPECT_NEAR(h.point[0], std::sqrt(s.radius * s.radius - 0.0125), 2e-3);  // reconstruction error
  EXPECT_DOUBLE_EQ(h.point[1], 0.1);
  Vec3 g{};
  s.spline.value(h.point, &g);
  const double norm = std::sqrt(g[0] * g[0] + g[1] * g[1] + g[2] * g[2]);
  for (int i = 0; i < 3; ++i)
    EXPECT_NEAR(h.normal[i], -g[i] / norm, 1e-12);  // the analytic gradient
  const double r =
      std::sqrt(h.point[0] * h.point[0] + h.point[1] * h.point[1] + h.point[2] * h.point[2]);
  EXPECT_GT(
      h.normal[0] * h.point[0] / r + h.normal[1] * h.point[1] / r + h.normal[2] * h.point[2] / r,
      0.999);
}

TEST(RayCaster, PrincipalCurvaturesOfTheBallAreOneOverItsRadius) {
  Scene s;
  const RayCaster caster(s.spline, s.box, 0.5, 0.5 * s.volume.spacing(), false, true);
  for (const Vec3& from : {Vec3{3, 0.1, 0.05}, Vec3{-2, 2.5, 1}, Vec3{0.2, -0.1, 3}}) {
    const RayHit h = caster.cast(from, {-from[0], -from[1], -from[2]});
    ASSERT_TRUE(h.hit && !h.on_cut);
    // The reconstructed Gaussian's level set is a ball up to the reconstruction error (N = 33).
    EXPECT_NEAR(h.k1, 1 / s.radius, 0.03 / s.radius);
    EXPECT_NEAR(h.k2, 1 / s.radius, 0.03 / s.radius);
    EXPECT_GE(h.k1, h.k2);
  }
}

TEST(RayCaster, MissesWhenTheRayPassesBesideTheSurface) {
  Scene s;
  const RayCaster caster(s.spline, s.box, 0.5, 0.5 * s.volume.spacing(), false);
  EXPECT_FALSE(caster.cast({3, 0.8, 0.0}, {-1, 0, 0}).hit);
  EXPECT_FALSE(caster.cast({3, 3, 3}, {1, 0, 0}).hit);  // away from the box
}

TEST(RayCaster, CutAwayShowsTheCrossSection) {
  Scene s;
  const RayCaster whole(s.spline, s.box, 0.5, 0.5 * s.volume.spacing(), false);
  const RayCaster cut(s.spline, s.box, 0.5, 0.5 * s.volume.spacing(), true);
  const RayHit a = whole.cast({0.1, 0.1, 3}, {0, 0, -1});
  const RayHit b = cut.cast({0.1, 0.1, 3}, {0, 0, -1});
  ASSERT_TRUE(a.hit && b.hit);
  EXPECT_NEAR(a.point[2], std::sqrt(s.radius * s.radius - 0.02), 2e-3);
  EXPECT_TRUE(b.on_cut);
  EXPECT_NEAR(b.point[2], 0, 1e-8);  // the plane z = 0 bounds the removed 3/8
  EXPECT_NEAR(b.normal[2], 1, 1e-12);
  EXPECT_GT(b.value, 0.5);
}

TEST(Render, ImageHasTheRequestedSizeAndBadOptionsAreRefused) {
  Scene s;
  RenderOptions o;
  o.width = 24;
  o.height = 16;
  const RgbBuffer img = render_isosurface(s.volume, SplineFilter::parse("m7"), s.box, o);
  EXPECT_EQ(img.pixels.size(), 24u * 16u * 3u);
  o.width = 0;
  EXPECT_THROW(render_isosurface(s.volume, SplineFilter::parse("m7"), s.box, o),
               std::invalid_argument);
  o.width = 8;
  o.iso = std::nan("");
  EXPECT_THROW(render_isosurface(s.volume, SplineFilter::parse("m7"), s.box, o),
               std::invalid_argument);
}

// The default camera is the one every figure was rendered with (docs/fig8_*.png, fig9_*.png): the
// eye 3.2 half-diagonals from the box's centre along (1, 0.78, 0.82), looking at the centre
// lowered by 0.08 half-diagonals, a 36 degree field of view: written out here as it was before
// the camera could move.
TEST(Camera, TheDefaultIsTheFiguresCamera) {
  const Box box{{-1, -2, 0}, {3, 2, 1}};
  const Camera c = camera_for(box, {});
  const double radius = 0.5 * std::sqrt(16.0 + 16.0 + 1.0);
  const double len = std::sqrt(1.0 + 0.78 * 0.78 + 0.82 * 0.82);
  const Vec3 eye{1 + 3.2 * radius / len, 3.2 * radius * 0.78 / len,
                 0.5 + 3.2 * radius * 0.82 / len};
  for (int i = 0; i < 3; ++i) EXPECT_NEAR(c.eye[i], eye[i], 1e-12) << i;
  const Vec3 to{1 - eye[0], -eye[1], 0.5 - 0.08 * radius - eye[2]};
  const double d = std::sqrt(to[0] * to[0] + to[1] * to[1] + to[2] * to[2]);
  for (int i = 0; i < 3; ++i) EXPECT_NEAR(c.forward[i], to[i] / d, 1e-12) << i;
  EXPECT_NEAR(c.tan_half, std::tan(18 * std::numbers::pi / 180), 1e-12);
  // The centre of an odd image looks straight ahead.
  const Vec3 ahead = c.ray(2, 2, 5, 5);
  for (int i = 0; i < 3; ++i) EXPECT_NEAR(ahead[i], c.forward[i], 1e-15) << i;
  // Azimuth and elevation 0 put the eye on +x, level with the centre, at 1.6 diagonals.
  CameraView level;
  level.azimuth = 0;
  level.elevation = 0;
  const Camera l = camera_for(box, level);
  EXPECT_NEAR(l.eye[0], 1 + 3.2 * radius, 1e-12);
  EXPECT_NEAR(l.eye[1], 0, 1e-12);
  EXPECT_NEAR(l.eye[2], 0.5, 1e-12);
  CameraView bad;
  bad.closeup = true;
  bad.distance = 2;
  EXPECT_THROW(camera_for(box, bad), std::invalid_argument);
}

// NumPy's percentile (linear between ranks) of 0, 1, ..., 100: the 1st is 1, the 99th 99.
TEST(PercentileIso, IsTheMidpointOfThe1stAnd99thPercentiles) {
  std::vector<double> v;
  for (int i = 100; i >= 0; --i) v.push_back(i);
  const IsoChoice c = percentile_iso(v);
  EXPECT_DOUBLE_EQ(c.p1, 1);
  EXPECT_DOUBLE_EQ(c.p99, 99);
  EXPECT_DOUBLE_EQ(c.iso, 50);
  // Four values: h = 0.03 and 2.97 between ranks, 0 + 0.03 (10 - 0) and 20 + 0.97 (40 - 20).
  const IsoChoice f = percentile_iso(std::vector<double>{40, 0, 20, 10});
  EXPECT_NEAR(f.p1, 0.3, 1e-12);
  EXPECT_NEAR(f.p99, 39.4, 1e-12);
  EXPECT_THROW(percentile_iso(std::vector<double>{}), std::invalid_argument);
}

// The percentiles behind it (and behind slice's window) on float samples: NaN is skipped (the
// three others are 40, 0, 20: the 50th is 20, the 25th 0 + 0.5 (20 - 0)), 0 and 100 are the
// extremes, and only NaN is no sample at all.
TEST(Percentiles, SkipNanAndMatchNumpyOnFloats) {
  const std::vector<float> v{40, NAN, 0, 20};
  const std::vector<double> p = percentiles(std::span<const float>(v), {0.5, 0.25, 0, 1});
  ASSERT_EQ(p.size(), 4U);
  EXPECT_DOUBLE_EQ(p[0], 20);
  EXPECT_DOUBLE_EQ(p[1], 10);
  EXPECT_DOUBLE_EQ(p[2], 0);
  EXPECT_DOUBLE_EQ(p[3], 40);
  const std::vector<float> none{NAN};
  EXPECT_THROW(percentiles(std::span<const float>(none), {0.5}), std::invalid_argument);
}

}  // namespace
}  // namespace boxgen::runtime
