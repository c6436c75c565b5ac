// boxgen from a user's point of view (see CMakeLists.txt next to this file):
//  (a) boxgen::runtime and boxgen::generated: sample a cubic on a BCC grid, prefilter it with
//      Q^I and reconstruct it with M7. M7 has approximation order 4, so every cubic comes back
//      exactly up to rounding; the checked-in evaluator, called directly on the same samples,
//      agrees with the runtime.
//  (b) a header that `boxgen emit` wrote at build time for our own direction matrix, evaluated
//      on our own image storage through a fetch functor: constant data give 1 (partition of
//      unity) and linear data are reproduced with their gradient (the spline is centred and its
//      approximation order is 4 >= 2).
//  (c) a 3-D box spline of our own matrix (six directions on the FCC lattice), emitted at build
//      time, through the runtime: sampled on FCC (LatticeVolume), prefiltered with its own
//      generated Q^I and reconstructed with Reconstructor. Its approximation order is 3,
//      so every quadratic comes back exactly up to rounding; an FCC filter on a BCC volume is
//      refused.
//  (d) the same filter on the GL device (boxgen::gl): the GLSL that boxgen_emit wrote for it,
//      compiled into an OpenGL compute shader at run time (a GPU's driver, else Mesa's
//      llvmpipe), gives the CPU's values within float rounding (2e-6 of the largest sample).
// Every check prints one line; the first failure goes to stderr as one line, exit code 1.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <exception>
#include <stdexcept>
#include <vector>

#include "fcc_six.hpp"  // emitted by boxgen_emit() at build time
#include "fcc_six_prefilters.hpp"
#include "generated/m7.hpp"  // boxgen::generated
#include "runtime/emitted_filter.h"
#include "runtime/gl/gl_render.h"  // boxgen::gl
#include "runtime/gl/gl_spline.h"
#include "runtime/reconstruction.h"  // boxgen::runtime
#include "runtime/sampling.h"
#include "runtime/test_functions.h"
#include "three_direction.hpp"  // emitted by boxgen_emit() at build time

namespace rt = boxgen::runtime;
namespace tri = boxgen::generated::three_direction;

namespace {

struct CheckFailed : std::runtime_error {
  using std::runtime_error::runtime_error;
};

void check(const char* what, double error, double tolerance) {
  std::printf("%-58s error %.3g (tolerance %.0e)\n", what, error, tolerance);
  if (!(error <= tolerance)) {  // also fails for NaN
    char line[160];
    std::snprintf(line, sizeof line, "%s: error %.3g exceeds %.0e", what, error, tolerance);
    throw CheckFailed(line);
  }
}

// (a) A cubic on BCC, reconstructed with M7 after the prefilter Q^I.
void bcc_reconstruction() {
  const rt::SplineFilter filter = rt::SplineFilter::parse("m7");
  const rt::PrefilterChoice q = rt::PrefilterChoice::Q1;
  const int n = 9;  // 9^3 x 2 samples over [-1,1]^3, plus the margin M7 and Q^I need
  const rt::LatticeVolume<double> samples = rt::sample_lattice<double>(
      rt::cubic, rt::cube_lattice_grid(filter.lattice(), n, filter.required_margin(q)));
  const rt::LatticeVolume<double> volume = rt::prefilter(samples, filter.prefilter(q));
  const rt::Reconstructor<double> m7(volume, filter);

  double value_error = 0, direct_error = 0;
  for (int i = 0; i < 5; ++i)
    for (int j = 0; j < 5; ++j)
      for (int k = 0; k < 5; ++k) {
        const rt::Vec3 p{-0.89 + 0.45 * i, -0.93 + 0.45 * j, -0.91 + 0.45 * k};  // inside [-1,1]^3
        const double v = m7.value(p);
        value_error = std::max(value_error, std::abs(v - rt::cubic(p)));
        // The generated evaluator takes lattice coordinates and any fetch(lattice point).
        const rt::Vec3 x = volume.to_lattice(p);
        const double direct = boxgen::generated::m7::evaluate<double>(
            {x[0], x[1], x[2]}, [&](const rt::LatticePoint& lp) { return volume.value(lp); });
        direct_error = std::max(direct_error, std::abs(direct - v));
      }
  check("M7 + Q^I reproduces a cubic on BCC (125 points)", value_error, 1e-10);
  check("generated::m7::evaluate agrees with the runtime", direct_error, 1e-12);
}

// (b) The user's storage: a size x size image whose pixel (0, 0) sits at lattice point (first,
// first).
struct Image {
  int size;
  std::int64_t first;
  std::vector<double> pixels;

  template <class F>
  Image(int n, std::int64_t origin, F f)
      : size(n), first(origin), pixels(static_cast<std::size_t>(n) * n) {
    for (int y = 0; y < n; ++y)
      for (int x = 0; x < n; ++x)
        pixels[static_cast<std::size_t>(y) * n + x] = f(double(x + first), double(y + first));
  }
  // The fetch policy of the emitted evaluator: the sample at lattice point j.
  double operator()(const tri::Point& j) const {
    const std::int64_t x = j[0] - first, y = j[1] - first;
    if (x < 0 || y < 0 || x >= size || y >= size)
      throw std::out_of_range("stencil leaves the image");
    return pixels[static_cast<std::size_t>(y * size + x)];
  }
};

void own_box_spline() {
  const Image ones(17, -8, [](double, double) { return 1.0; });
  const Image linear(17, -8, [](double x, double y) { return 0.5 + 2 * x - 3 * y; });
  double unity_error = 0, value_error = 0, gradient_error = 0;
  for (int i = 0; i <= 12; ++i)
    for (int j = 0; j <= 12; ++j) {
      const std::array<double, 2> x{-3.01 + 0.5 * i,
                                    -2.97 + 0.5 * j};  // stencils stay in the image
      unity_error = std::max(unity_error, std::abs(tri::evaluate<double>(x, ones) - 1));
      std::array<double, 2> g{};
      const double v = tri::evaluate<double>(x, linear, &g);
      value_error = std::max(value_error, std::abs(v - (0.5 + 2 * x[0] - 3 * x[1])));
      gradient_error = std::max({gradient_error, std::abs(g[0] - 2), std::abs(g[1] + 3)});
    }
  check("three_direction: constant data give 1 (169 points)", unity_error, 1e-13);
  check("three_direction: linear data reproduced", value_error, 1e-12);
  check("three_direction: gradient of linear data reproduced", gradient_error, 1e-12);
}

}  // namespace

// (c) Our own 3-D filter on its lattice, through the runtime's volumes, sampling and prefilters.
void own_filter_through_the_runtime() {
  namespace six = boxgen::generated::fcc_six;
  const rt::CosetLattice lattice = rt::filter_lattice<six::Traits>();  // FCC, read from the header
  const auto quadratic = [](const rt::Vec3& p) {
    return 2 * p[0] * p[0] - p[0] * p[1] + 3 * p[2] * p[2] - p[1] + 0.5;
  };
  rt::LatticeVolume<double> volume =
      rt::sample_lattice<double>(quadratic, rt::cube_lattice_grid(lattice, 9, 4));
  volume = rt::prefilter(volume, rt::prefilter_from(six::q1));
  const rt::Reconstructor<double> spline(volume, rt::emitted_filter<six::Traits>());
  double error = 0;
  for (int i = 0; i < 5; ++i)
    for (int j = 0; j < 5; ++j)
      for (int k = 0; k < 5; ++k) {
        const rt::Vec3 p{-0.89 + 0.45 * i, -0.93 + 0.45 * j, -0.91 + 0.45 * k};
        error = std::max(error, std::abs(spline.value(p) - quadratic(p)));
      }
  check("own FCC filter + its Q^I reproduces a quadratic (125 points)", error, 1e-10);
  const rt::LatticeVolume<double> bcc =
      rt::sample_lattice<double>(quadratic, rt::cube_lattice_grid(rt::CosetLattice::bcc(), 5, 4));
  bool refused = false;
  try {
    const rt::Reconstructor<double> wrong(bcc, rt::emitted_filter<six::Traits>());
  } catch (const std::invalid_argument&) {
    refused = true;
  }
  check("own FCC filter on a BCC volume is refused", refused ? 0 : 1, 0);
}

// (d) Our own filter on the GL device, from the GLSL file boxgen_emit wrote (FCC_SIX_GLSL).
void own_filter_on_the_gl_device() {
  namespace six = boxgen::generated::fcc_six;
  const rt::SplineFilter filter = rt::emitted_filter<six::Traits>();
  const auto quadratic = [](const rt::Vec3& p) {
    return 2 * p[0] * p[0] - p[0] * p[1] + 3 * p[2] * p[2] - p[1] + 0.5;
  };
  const rt::LatticeVolume<double> volume = rt::prefilter(
      rt::sample_lattice<double>(quadratic, rt::cube_lattice_grid(filter.lattice(), 9, 4)),
      rt::prefilter_from(six::q1));
  const rt::LatticeVolume<float> single = rt::gl::float_volume(volume);
  const rt::gl::GlSpline<float> gpu(single, filter, rt::gl::read_glsl(FCC_SIX_GLSL));
  std::vector<rt::Vec3> points;
  for (int i = 0; i < 125; ++i)
    points.push_back({-0.89 + 0.45 * (i % 5), -0.93 + 0.45 * (i / 5 % 5), -0.91 + 0.45 * (i / 25)});
  std::vector<float> on_gpu(points.size());
  std::vector<double> on_cpu(points.size());
  gpu.evaluate(points, on_gpu);
  rt::Reconstructor<double>(volume, filter).evaluate(points, on_cpu);
  // Relative to the largest sample, as boxgen's own float tests (2e-6 of max|V|).
  double error = 0, largest = 0;
  for (std::size_t i = 0; i < points.size(); ++i)
    error = std::max(error, std::abs(static_cast<double>(on_gpu[i]) - on_cpu[i]));
  for (double s : volume.samples()) largest = std::max(largest, std::abs(s));
  std::printf("GL device: %s\n", rt::gl::device().renderer.c_str());
  check("own FCC filter's GLSL on the GL device, as the CPU (float)", error / largest, 2e-6);
}

int main() {
  try {
    bcc_reconstruction();
    own_box_spline();
    own_filter_through_the_runtime();
    own_filter_on_the_gl_device();
  } catch (const std::exception& e) {
    std::fprintf(stderr, "boxgen_consumer: %s\n", e.what());
    return 1;
  }
  return 0;
}
