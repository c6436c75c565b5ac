#include "runtime/test_functions.h"

#include <cmath>
#include <numbers>
#include <stdexcept>

namespace boxgen::runtime {

namespace {

constexpr double kPi = std::numbers::pi;

// sin(pi r / 2) / r, continued to pi/2 at r = 0 (Taylor series below 1e-4, where its error
// (pi r/2)^4/120 * pi/2 is below 1e-17).
double sin_half_pi_r_over_r(double r) {
  const double t = kPi * r / 2;
  if (r < 1e-4) return kPi / 2 * (1 - t * t / 6);
  return std::sin(t) / r;
}

// The phase 2 pi fM u, u = cos(pi r/2), reduced modulo 2 pi: fM is an integer, so it equals
// 2 pi fM (u - 1), and u - 1 = -2 sin^2(pi r/4) has no cancellation. Near the axis the phase is
// close to 12 pi, where computing it directly would leave sin(phase) with a relative error of
// about 1e-16 * 12 pi / |phase - 12 pi| (measured against long double at r = 3e-5: 4e-8 direct,
// below 1e-10 reduced).
double marschner_lobb_phase(double r) {
  static_assert(kMarschnerLobbFrequency == static_cast<int>(kMarschnerLobbFrequency),
                "the reduction needs an integer fM");
  const double s = std::sin(kPi * r / 4);
  return 2 * kPi * kMarschnerLobbFrequency * (-2 * s * s);
}

}  // namespace

double marschner_lobb(const Vec3& p) {
  const double a = kMarschnerLobbAlpha;
  const double radial = std::cos(marschner_lobb_phase(std::hypot(p[0], p[1])));
  return (1 - std::sin(kPi * p[2] / 2) + a * (1 + radial)) / (2 * (1 + a));
}

Vec3 marschner_lobb_gradient(const Vec3& p) {
  const double a = kMarschnerLobbAlpha, fm = kMarschnerLobbFrequency;
  const double r = std::hypot(p[0], p[1]);
  // d/dx cos(2 pi fm u) = -sin(2 pi fm u) 2 pi fm du/dx,  du/dx = -(pi/2) sin(pi r/2) x / r.
  const double radial = a * std::sin(marschner_lobb_phase(r)) * 2 * kPi * fm * (kPi / 2) *
                        sin_half_pi_r_over_r(r) / (2 * (1 + a));
  return {radial * p[0], radial * p[1], -(kPi / 2) * std::cos(kPi * p[2] / 2) / (2 * (1 + a))};
}

double cubic(const Vec3& p) {
  const double x = p[0], y = p[1], z = p[2];
  return x * x * x - 2 * x * y * z + 3 * y * y - z + 1;
}

Vec3 cubic_gradient(const Vec3& p) {
  const double x = p[0], y = p[1], z = p[2];
  return {3 * x * x - 2 * y * z, -2 * x * z + 6 * y, -2 * x * y - 1};
}

double sphere(const Vec3& p) { return std::sqrt(p[0] * p[0] + p[1] * p[1] + p[2] * p[2]); }

Vec3 sphere_gradient(const Vec3& p) {
  const double d = sphere(p);
  if (d == 0) return {0, 0, 0};
  return {p[0] / d, p[1] / d, p[2] / d};
}

double gaussian(const Vec3& p) {
  const double s = kGaussianWidth;
  return std::exp(-(p[0] * p[0] + p[1] * p[1] + p[2] * p[2]) / (2 * s * s));
}

Vec3 gaussian_gradient(const Vec3& p) {
  const double s = kGaussianWidth;
  const double g = -gaussian(p) / (s * s);
  return {g * p[0], g * p[1], g * p[2]};
}

std::span<const TestFunction> test_functions() {
  static constexpr TestFunction kFunctions[] = {
      {"ml", "Marschner-Lobb function, fM = 6, a = 0.25", marschner_lobb, marschner_lobb_gradient},
      {"cubic", "x^3 - 2xyz + 3y^2 - z + 1", cubic, cubic_gradient},
      {"sphere", "distance from the origin", sphere, sphere_gradient},
      {"gaussian", "exp(-|p|^2 / (2 * 0.4^2))", gaussian, gaussian_gradient},
  };
  return kFunctions;
}

const TestFunction& find_test_function(std::string_view name) {
  for (const TestFunction& f : test_functions())
    if (f.name == name) return f;
  // Echo at most 40 characters of the user's text, with control characters replaced.
  std::string shown;
  for (char ch : name.substr(0, 40))
    shown += (static_cast<unsigned char>(ch) < 0x20 || ch == 0x7f) ? '?' : ch;
  if (name.size() > 40) shown += "...";
  throw std::invalid_argument("unknown test function '" + shown + "' (expected one of " +
                              test_function_names() + ")");
}

std::string test_function_names() {
  std::string names;
  for (const TestFunction& f : test_functions()) {
    if (!names.empty()) names += '|';
    names += f.name;
  }
  return names;
}

}  // namespace boxgen::runtime
