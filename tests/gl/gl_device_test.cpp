// The GL device (runtime/gl) against the CPU path, on Mesa's llvmpipe in CI: every registry
// filter's emitted GLSL evaluates as the CPU's Reconstructor (values, gradients, Hessians, within
// the float and double tolerances of tests/emitted relative to max|V|), resample fills the same
// grid, the GL ray caster draws the CPU renderer's picture, and each error is the one promised
// (the CPU's message for a point outside, the driver's log for a bad shader, a clear refusal of a
// volume beyond the device's storage). Small sizes: these run under ASan too.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <memory>
#include <optional>
#include <random>
#include <string>
#include <vector>

#include "runtime/coefficients.h"
#include "runtime/gl/gl_render.h"
#include "runtime/gl/gl_spline.h"
#include "runtime/prefilter.h"
#include "runtime/reconstruction.h"
#include "runtime/render.h"
#include "runtime/resample.h"
#include "runtime/sampling.h"
#include "runtime/test_functions.h"

namespace boxgen::runtime::gl {
namespace {

// The tolerances of tests/emitted relative to max|V| (second derivatives 4x these).
constexpr double kFloatTolerance = 2e-6;
constexpr double kDoubleTolerance = 1e-13;

// Every test needs the context: without EGL it fails with the one line naming what to install.
class GlTest : public ::testing::Test {
 protected:
  void SetUp() override {
    try {
      (void)device();
    } catch (const GlError& e) {
      FAIL() << e.what();
    }
  }
};

// Random samples in [-1, 1] on the filter's lattice, unit spacing at the origin (lattice = world
// coordinates, so derivatives need no scaling), `cells` coset cells per axis.
template <class T>
LatticeVolume<T> random_volume(const SplineFilter& f, int cells) {
  LatticeVolume<T> v(f.lattice(), {cells, cells, cells}, 1.0, {0, 0, 0});
  std::mt19937_64 rng(static_cast<std::uint64_t>(cells));
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (T& s : v.samples()) s = static_cast<T>(u(rng));
  return v;
}

std::vector<Vec3> points_in(const Box& box, int count) {
  std::mt19937_64 rng(3);
  std::vector<Vec3> out(static_cast<std::size_t>(count));
  for (Vec3& p : out)
    for (int a = 0; a < 3; ++a)
      p[a] = std::uniform_real_distribution<double>(box.min[a], box.max[a])(rng);
  return out;
}

// GL in precision T against the CPU in double at `count` points of the default box.
template <class T>
void expect_gl_equals_cpu(const std::string& name, int count, double tolerance,
                          TableStorage tables = TableStorage::buffer) {
  const SplineFilter f = SplineFilter::parse(name);
  const LatticeVolume<double> reference = random_volume<double>(f, 14);
  LatticeVolume<T> volume(reference.lattice(), reference.sizes(), 1.0, {0, 0, 0});
  std::transform(reference.samples().begin(), reference.samples().end(), volume.samples().begin(),
                 [](double s) { return static_cast<T>(s); });
  const std::vector<Vec3> points = points_in(default_box(volume, f), count);
  const std::size_t n = points.size();
  std::vector<double> values(n);
  std::vector<Vec3> gradients(n);
  std::vector<Hessian> hessians(n);
  Reconstructor<double>(reference, f).evaluate(points, values, gradients, hessians);
  std::vector<T> gl_values(n);
  std::vector<Vec3> gl_gradients(n);
  std::vector<Hessian> gl_hessians(n);
  const GlSpline<T> gpu(volume, f, registry_glsl(name, sizeof(T) == 8), tables);
  gpu.evaluate(points, gl_values, gl_gradients, gl_hessians);
  std::vector<T> only_values(n);
  gpu.evaluate(points, only_values);  // the value kernel: another program
  double value = 0, gradient = 0, hessian = 0;
  for (std::size_t i = 0; i < n; ++i) {
    value =
        std::max({value, std::abs(gl_values[i] - values[i]), std::abs(only_values[i] - values[i])});
    for (int a = 0; a < 3; ++a)
      gradient = std::max(gradient, std::abs(gl_gradients[i][a] - gradients[i][a]));
    for (int a = 0; a < 6; ++a)
      hessian = std::max(hessian, std::abs(gl_hessians[i][a] - hessians[i][a]));
  }
  EXPECT_LE(value, tolerance) << name;  // max|V| = 1
  EXPECT_LE(gradient, tolerance) << name;
  EXPECT_LE(hessian, 4 * tolerance) << name;
}

// A text read from a file (read_glsl) carries no tables as data: the device compiles its `const`
// tables as they are, and evaluates as with the generator's block.
TEST_F(GlTest, ATextReadFromAFileKeepsItsConstTables) {
  const SplineFilter f = SplineFilter::parse("fcc6");
  const LatticeVolume<float> v = random_volume<float>(f, 12);
  const GlSpline<float> from_file(v, f, {"fcc6", registry_glsl("fcc6", false).text});
  const GlSpline<float> with_data(v, f, registry_glsl("fcc6", false));
  EXPECT_NE(from_file.kernel_source(0).find("const int fcc6_kLookup["), std::string::npos);
  EXPECT_EQ(with_data.kernel_source(0).find("const int fcc6_kLookup["), std::string::npos);
  const std::vector<Vec3> points = points_in(default_box(v, f), 200);
  std::vector<float> a(points.size()), b(points.size());
  from_file.evaluate(points, a);
  with_data.evaluate(points, b);
  for (std::size_t i = 0; i < points.size(); ++i) EXPECT_NEAR(a[i], b[i], kFloatTolerance) << i;
}

// A filter outside the registry, as the loader makes one: m8's source, carrying `glsl` (or none).
class CarriedGlsl final : public FilterSource {
 public:
  explicit CarriedGlsl(std::optional<GlslEvaluator> glsl) : glsl_(std::move(glsl)) {}
  std::string name() const override { return "carried"; }
  CosetLattice lattice() const override { return m8_.lattice(); }
  StencilReach reach() const override { return m8_.reach(); }
  PrefilterTaps prefilter(PrefilterChoice q) const override { return m8_.prefilter(q); }
  int approximation_order() const override { return m8_.approximation_order(); }
  std::shared_ptr<const EvaluationPath<float>> path(const LatticeVolume<float>& v) const override {
    return m8_.source().path(v);
  }
  std::shared_ptr<const EvaluationPath<double>> path(
      const LatticeVolume<double>& v) const override {
    return m8_.source().path(v);
  }
  std::optional<GlslEvaluator> glsl(bool) const override { return glsl_; }

 private:
  SplineFilter m8_ = SplineFilter::parse("m8");
  std::optional<GlslEvaluator> glsl_;
};

// The device takes a filter's GLSL from the filter: the registry's, or the one its source
// carries; a filter without one is refused, naming it.
TEST_F(GlTest, AFilterCarriesItsGlsl) {
  EXPECT_EQ(filter_glsl(SplineFilter::parse("m12"), true).text, registry_glsl("m12", true).text);
  const SplineFilter f(std::make_shared<CarriedGlsl>(registry_glsl("m8", false)));
  ASSERT_EQ(f.registry_index(), -1);
  const LatticeVolume<float> v = random_volume<float>(f, 12);
  const GlSpline<float> gpu(v, f, filter_glsl(f, false));
  const std::vector<Vec3> points = points_in(default_box(v, f), 200);
  std::vector<float> on_gpu(points.size()), on_cpu(points.size());
  gpu.evaluate(points, on_gpu);
  Reconstructor<float>(v, f).evaluate(points, on_cpu);
  for (std::size_t i = 0; i < points.size(); ++i)
    EXPECT_NEAR(on_gpu[i], on_cpu[i], kFloatTolerance) << i;
  try {
    (void)filter_glsl(SplineFilter(std::make_shared<CarriedGlsl>(std::nullopt)), false);
    ADD_FAILURE() << "no GlError";
  } catch (const GlError& e) {
    EXPECT_NE(std::string(e.what()).find("filter carried carries no GLSL"), std::string::npos)
        << e.what();
  }
}

class GlEveryFilter : public GlTest, public ::testing::WithParamInterface<const char*> {};

#ifndef BOXGEN_GL_POINTS
#define BOXGEN_GL_POINTS 300
#endif

TEST_P(GlEveryFilter, FloatEvaluationEqualsTheCpu) {
  expect_gl_equals_cpu<float>(GetParam(), BOXGEN_GL_POINTS, kFloatTolerance);
}

INSTANTIATE_TEST_SUITE_P(Registry, GlEveryFilter,
                         ::testing::Values("m7", "m8", "m12", "fcc6", "tricubic", "cart7"),
                         [](const auto& p) { return std::string(p.param); });

TEST_F(GlTest, DoubleEvaluationEqualsTheCpu) {
  expect_gl_equals_cpu<double>("m7", BOXGEN_GL_POINTS, kDoubleTolerance);
}

// The emitted text's `const` tables, as they are (the device's default moves them to a buffer):
// one orbit (m7) and two (fcc6, whose orbit tables move too).
TEST_F(GlTest, ConstTablesEvaluateAsTheCpu) {
  expect_gl_equals_cpu<float>("m7", BOXGEN_GL_POINTS, kFloatTolerance, TableStorage::constant);
  expect_gl_equals_cpu<float>("fcc6", BOXGEN_GL_POINTS, kFloatTolerance, TableStorage::constant);
}

TEST_F(GlTest, AnisotropicCartesianVolumeScalesDerivatives) {
  const SplineFilter f = SplineFilter::parse("tricubic");
  LatticeVolume<double> v(f.lattice(), {10, 10, 10}, Vec3{0.5, 1.0, 2.0}, {-1, 0, 3},
                          std::vector<double>(1000));
  std::mt19937_64 rng(5);
  for (double& s : v.samples()) s = std::uniform_real_distribution<double>(-1, 1)(rng);
  const std::vector<Vec3> points = points_in(default_box(v, f), 50);
  std::vector<double> cpu(points.size()), gpu(points.size());
  std::vector<Vec3> cg(points.size()), gg(points.size());
  std::vector<Hessian> ch(points.size()), gh(points.size());
  Reconstructor<double>(v, f).evaluate(points, cpu, cg, ch);
  GlSpline<double>(v, f, registry_glsl("tricubic", true)).evaluate(points, gpu, gg, gh);
  for (std::size_t i = 0; i < points.size(); ++i) {
    EXPECT_NEAR(gpu[i], cpu[i], 1e-12);
    for (int a = 0; a < 3; ++a) EXPECT_NEAR(gg[i][a], cg[i][a], 1e-11);
    for (int a = 0; a < 6; ++a) EXPECT_NEAR(gh[i][a], ch[i][a], 1e-10);
  }
}

TEST_F(GlTest, InterpolationRunsBeforeTheUploadAndPassesThroughTheSamples) {
  // The GL device evaluates interp's coefficients (made on the CPU, runtime/coefficients.h): at
  // the samples, up to the faces (mirror boundary), it gives the samples back.
  const SplineFilter f = SplineFilter::parse("m8");
  LatticeVolume<double> v(f.lattice(), {6, 7, 5}, 0.25, {-1, 0, 2});
  std::mt19937_64 rng(8);
  for (double& s : v.samples()) s = std::uniform_real_distribution<double>(-1, 1)(rng);
  const LatticeVolume<double> c = spline_coefficients(v, f, PrefilterChoice::interp());
  std::vector<Vec3> points;
  std::vector<double> expected;
  for (int k = 0; k < 5; ++k)
    for (int j = 0; j < 7; ++j)
      for (int i = 0; i < 6; ++i)
        for (int q = 0; q < 2; ++q) {
          points.push_back(v.sample_position(q, i, j, k));
          expected.push_back(v(q, i, j, k));
        }
  std::vector<double> gpu(points.size());
  GlSpline<double>(c, f, registry_glsl("m8", true)).evaluate(points, gpu);
  for (std::size_t i = 0; i < points.size(); ++i) EXPECT_NEAR(gpu[i], expected[i], 1e-12) << i;
}

TEST_F(GlTest, ResampleFillsTheCpuGrid) {
  const SplineFilter f = SplineFilter::parse("m7");
  const LatticeVolume<float> v = random_volume<float>(f, 12);
  const CartesianGrid grid = grid_over(default_box(v, f), {9, 8, 7});
  const GridBlock all{{0, 0, 0}, grid.sizes};
  const CartesianVolume<float> cpu = resample(v, f, grid, all);
  const GlSpline<float> gpu(v, f, registry_glsl("m7", false));
  const CartesianVolume<float> gl = resample(
      v, f, grid, all, BatchEvaluate<float>([&gpu](std::span<const Vec3> p, std::span<float> out) {
        gpu.evaluate(p, out);
      }));
  ASSERT_EQ(gl.values.size(), cpu.values.size());
  EXPECT_EQ(gl.sizes, cpu.sizes);
  for (std::size_t i = 0; i < cpu.values.size(); ++i)
    EXPECT_NEAR(gl.values[i], cpu.values[i], 4 * kFloatTolerance) << i;
}

// The share of pixels whose channels all differ by at most 3/255.
double agreement(const RgbBuffer& a, const RgbBuffer& b) {
  int close = 0;
  const std::size_t pixels = a.pixels.size() / 3;
  for (std::size_t i = 0; i < pixels; ++i) {
    int worst = 0;
    for (int c = 0; c < 3; ++c)
      worst = std::max(worst, std::abs(a.pixels[3 * i + c] - b.pixels[3 * i + c]));
    close += worst <= 3;
  }
  return static_cast<double>(close) / static_cast<double>(pixels);
}

// The Marschner-Lobb volume of Fig. 8 (small), M7 after Q^II.
LatticeVolume<double> ml_volume(const SplineFilter& f, int n) {
  const LatticeGrid grid =
      cube_lattice_grid(f.lattice(), n, f.required_margin(PrefilterChoice::Q2));
  return prefilter(sample_lattice<double>(find_test_function("ml").value, grid),
                   f.prefilter(PrefilterChoice::Q2));
}

TEST_F(GlTest, RenderAgreesWithTheCpuRenderer) {
  const SplineFilter m7 = SplineFilter::parse("m7");
  const LatticeVolume<double> v = ml_volume(m7, 20);
  const Box cube{{-1, -1, -1}, {1, 1, 1}};
  for (const bool curvature : {false, true}) {
    RenderOptions o;
    o.width = 48;
    o.height = 40;
    o.cutaway = true;
    o.shading = curvature ? Shading::Curvature : Shading::Normal;
    const RgbBuffer cpu = runtime::render_isosurface(v, m7, cube, o);
    const RgbBuffer single =
        gl::render_isosurface(v, m7, cube, o, registry_glsl("m7", false), false);
    ASSERT_EQ(single.pixels.size(), cpu.pixels.size());
    EXPECT_GE(agreement(cpu, single), 0.98) << "curvature " << curvature;
    if (curvature) {  // double on the GPU: the CPU's arithmetic, the same picture
      const RgbBuffer dbl = gl::render_isosurface(v, m7, cube, o, registry_glsl("m7", true), true);
      EXPECT_GE(agreement(cpu, dbl), 0.999);
    }
  }
}

TEST_F(GlTest, RenderRefusesWhatTheCpuRendererRefuses) {
  const SplineFilter m7 = SplineFilter::parse("m7");
  const LatticeVolume<double> v = ml_volume(m7, 8);
  const Box cube{{-1, -1, -1}, {1, 1, 1}};
  RenderOptions o;
  o.width = 0;
  const GlslEvaluator glsl = registry_glsl("m7", false);
  EXPECT_THROW(gl::render_isosurface(v, m7, cube, o, glsl, false), std::invalid_argument);
  o.width = 8;
  o.iso = std::nan("");
  EXPECT_THROW(gl::render_isosurface(v, m7, cube, o, glsl, false), std::invalid_argument);
}

// The CPU path's message for a point it cannot evaluate, or "" when it can.
std::string cpu_error(const Reconstructor<float>& cpu, const std::vector<Vec3>& points) {
  std::vector<float> values(points.size());
  try {
    cpu.evaluate(points, values);
  } catch (const std::exception& e) {
    return e.what();
  }
  return "";
}

TEST_F(GlTest, PointsOutsideTheVolumeGiveTheCpuPathsError) {
  const SplineFilter f = SplineFilter::parse("m7");
  const LatticeVolume<float> v = random_volume<float>(f, 10);
  const Reconstructor<float> cpu(v, f);
  const GlSpline<float> gpu(v, f, registry_glsl("m7", false));
  const Box inside = default_box(v, f);
  for (const Vec3& bad :
       {Vec3{inside.min[0] - 3, 5, 5}, Vec3{1e30, 5, 5}, Vec3{std::nan(""), 5, 5}}) {
    const std::vector<Vec3> points{{5, 5, 5}, {6, 6, 6}, bad, {7, 7, 7}};
    const std::string expected = cpu_error(cpu, points);
    ASSERT_NE(expected, "");
    std::vector<float> values(points.size());
    try {
      gpu.evaluate(points, values);
      ADD_FAILURE() << "no error for " << bad[0];
    } catch (const std::exception& e) {
      EXPECT_EQ(std::string(e.what()), expected);
    }
  }
}

TEST_F(GlTest, ABadShaderGivesTheDriversLog) {
  const SplineFilter f = SplineFilter::parse("m7");
  const LatticeVolume<float> v = random_volume<float>(f, 10);
  {  // not an evaluator at all: its compile fails on first use
    const GlSpline<float> bad(v, f, {"m7", "not an evaluator"});
    std::vector<float> one(1);
    EXPECT_THROW(bad.evaluate(std::vector<Vec3>{{5, 5, 5}}, one), GlError);
  }
  // An emitted file broken by hand (read as read_glsl reads it, text only): the compile fails,
  // and the message carries the driver's log.
  const GlslEvaluator broken{
      "m7", registry_glsl("m7", false).text + "\nfloat m7_broken() { return undeclared_name; }\n"};
  const GlSpline<float> gpu(v, f, broken);
  std::vector<float> values(1);
  try {
    gpu.evaluate(std::vector<Vec3>{{5, 5, 5}}, values);
    ADD_FAILURE() << "the broken shader compiled";
  } catch (const GlError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("does not compile"), std::string::npos) << what;
    EXPECT_NE(what.find("undeclared_name"), std::string::npos) << what;
    EXPECT_EQ(what.find('\n'), std::string::npos) << what;
  }
}

TEST_F(GlTest, AVolumeBeyondTheDevicesStorageIsRefused) {
  const SplineFilter f = SplineFilter::parse("m7");
  const LatticeVolume<float> v = random_volume<float>(f, 10);  // 2000 samples, 8000 bytes
  set_storage_limit_for_testing(4096);
  try {
    const GlSpline<float> gpu(v, f, registry_glsl("m7", false));
    ADD_FAILURE() << "a volume beyond the storage limit was uploaded";
  } catch (const GlError& e) {
    EXPECT_NE(std::string(e.what()).find("exceeds the largest storage buffer"), std::string::npos)
        << e.what();
  }
  set_storage_limit_for_testing(0);
}

TEST_F(GlTest, TheRegistryHasEveryFilterAndNothingElse) {
  for (int i = 0; i < SplineFilter::count(); ++i) {
    const std::string name = SplineFilter::at(i).name();
    EXPECT_NE(registry_glsl(name, false).text.find(name + "_value_gradient_hessian"),
              std::string::npos);
    EXPECT_NE(registry_glsl(name, true).text.find("double"), std::string::npos);
  }
  EXPECT_THROW(registry_glsl("m9", false), GlError);
}

}  // namespace
}  // namespace boxgen::runtime::gl
