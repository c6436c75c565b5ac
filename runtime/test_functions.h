// Analytic test functions on R^3 with exact gradients, for sampling, reconstruction error and
// `boxrecon sample --function NAME`.
#pragma once
#include <array>
#include <span>
#include <string>
#include <string_view>

namespace boxgen::runtime {

using Vec3 = std::array<double, 3>;

// The Marschner-Lobb function (docs/design.md §13):
//   rho(x,y,z) = (1 - sin(pi z/2) + a (1 + cos(2 pi fM cos(pi r/2)))) / (2 (1 + a)),
//   r = sqrt(x^2 + y^2), fM = 6, a = 0.25.
inline constexpr double kMarschnerLobbFrequency = 6.0;  // fM
inline constexpr double kMarschnerLobbAlpha = 0.25;     // a
double marschner_lobb(const Vec3& p);
Vec3 marschner_lobb_gradient(const Vec3& p);  // exact; smooth through the axis r = 0

// x^3 - 2xyz + 3y^2 - z + 1: a cubic, so prefiltered order-4 splines reproduce it.
double cubic(const Vec3& p);
Vec3 cubic_gradient(const Vec3& p);

// Distance from the origin. Its gradient p/|p| is undefined at the origin; we return 0 there.
double sphere(const Vec3& p);
Vec3 sphere_gradient(const Vec3& p);

// exp(-|p|^2 / (2 s^2)) with s = kGaussianWidth.
inline constexpr double kGaussianWidth = 0.4;
double gaussian(const Vec3& p);
Vec3 gaussian_gradient(const Vec3& p);

struct TestFunction {
  std::string_view name;         // the CLI name: ml, cubic, sphere, gaussian
  std::string_view description;  // one line for help texts
  double (*value)(const Vec3&);
  Vec3 (*gradient)(const Vec3&);
};

// Every registered function, in a fixed order.
std::span<const TestFunction> test_functions();
// The function called `name`; throws std::invalid_argument (one line, listing the names) if
// there is none.
const TestFunction& find_test_function(std::string_view name);
// The names joined with '|', e.g. "ml|cubic|sphere|gaussian".
std::string test_function_names();

}  // namespace boxgen::runtime
