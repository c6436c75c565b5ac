// Test functions: Marschner-Lobb values worked out by hand from docs/design.md §13, gradients
// against central differences, the registry.
#include "runtime/test_functions.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <random>
#include <stdexcept>
#include <string>
#include <vector>

namespace boxgen::runtime {
namespace {

// A point at distance r from the z axis (any angle) and height z.
Vec3 at_radius(double r, double angle, double z) {
  return {r * std::cos(angle), r * std::sin(angle), z};
}

// rho = (1 - sin(pi z/2) + a (1 + cos(2 pi 6 u))) / 2.5 with u = cos(pi r/2), a = 1/4. The points
// are chosen where the sines and cosines are known exactly: sin(pi z/2) in {0, +-1, +-1/2} and
// 2 pi 6 u in {12 pi, 0, pi/2, pi/3}.
TEST(TestFunction, MarschnerLobbValuesWorkedByHand) {
  const double tol = 1e-14;
  // r = 0: u = 1, cos(12 pi) = 1; z = 0: (1 - 0 + 0.5) / 2.5 = 0.6.
  EXPECT_NEAR(marschner_lobb({0, 0, 0}), 0.6, tol);
  // z = 1: (1 - 1 + 0.5) / 2.5 = 0.2; z = -1: (1 + 1 + 0.5) / 2.5 = 1.
  EXPECT_NEAR(marschner_lobb({0, 0, 1}), 0.2, tol);
  EXPECT_NEAR(marschner_lobb({0, 0, -1}), 1.0, tol);
  // r = 1: u = cos(pi/2) = 0, cos(0) = 1: 0.6 again, on any side.
  EXPECT_NEAR(marschner_lobb({1, 0, 0}), 0.6, tol);
  EXPECT_NEAR(marschner_lobb({0, -1, 0}), 0.6, tol);
  // u = 1/24: cos(pi/2) = 0, a (1 + 0) = 0.25; z = -1/3: sin(-pi/6) = -1/2: (1.5 + 0.25) / 2.5 =
  // 0.7.
  const double r24 = 2 / std::numbers::pi * std::acos(1.0 / 24);
  EXPECT_NEAR(marschner_lobb(at_radius(r24, 0.7, -1.0 / 3)), 0.7, tol);
  // u = 1/36: cos(pi/3) = 1/2, a * 1.5 = 0.375; z = 1/3: (1 - 0.5 + 0.375) / 2.5 = 0.35.
  const double r36 = 2 / std::numbers::pi * std::acos(1.0 / 36);
  EXPECT_NEAR(marschner_lobb(at_radius(r36, 2.1, 1.0 / 3)), 0.35, tol);
  // u = 1/12: cos(pi) = -1, radial term 0; z = 0: 1 / 2.5 = 0.4.
  const double r12 = 2 / std::numbers::pi * std::acos(1.0 / 12);
  EXPECT_NEAR(marschner_lobb(at_radius(r12, -1.3, 0)), 0.4, tol);
  EXPECT_EQ(kMarschnerLobbFrequency, 6.0);
  EXPECT_EQ(kMarschnerLobbAlpha, 0.25);
}

TEST(TestFunction, OtherValuesWorkedByHand) {
  // x^3 - 2xyz + 3y^2 - z + 1 at (1, 2, 3): 1 - 12 + 12 - 3 + 1 = -1; gradient
  // (3x^2 - 2yz, -2xz + 6y, -2xy - 1) = (-9, 6, -5).
  EXPECT_EQ(cubic({1, 2, 3}), -1.0);
  EXPECT_EQ(cubic_gradient({1, 2, 3}), (Vec3{-9, 6, -5}));
  EXPECT_EQ(sphere({3, 4, 12}), 13.0);
  EXPECT_EQ(sphere_gradient({0, 0, 0}), (Vec3{0, 0, 0}));
  EXPECT_EQ(gaussian({0, 0, 0}), 1.0);
  // |p|^2 = 2 s^2 = 0.32: exp(-1).
  EXPECT_NEAR(gaussian({0.4, 0, 0.4}), std::exp(-1.0), 1e-15);
}

// Central differences with step 1e-6: truncation error ~ step^2 |f'''| / 6, below 1e-8 even for
// Marschner-Lobb (|f'''| ~ 0.1 * (6 pi^2)^3 ~ 2e4), rounding ~ 1e-16 / 1e-6 = 1e-10. Tolerance
// 1e-7.
void expect_gradient_matches_differences(const TestFunction& f, const Vec3& p) {
  const double step = 1e-6, tol = 1e-7;
  const Vec3 g = f.gradient(p);
  for (int a = 0; a < 3; ++a) {
    Vec3 plus = p, minus = p;
    plus[a] += step;
    minus[a] -= step;
    const double difference = (f.value(plus) - f.value(minus)) / (plus[a] - minus[a]);
    EXPECT_NEAR(g[a], difference, tol)
        << f.name << " axis " << a << " at (" << p[0] << ", " << p[1] << ", " << p[2] << ")";
  }
}

TEST(TestFunction, GradientsMatchCentralDifferences) {
  std::mt19937_64 random(20240611);
  std::uniform_real_distribution<double> coordinate(-1, 1);
  for (const TestFunction& f : test_functions())
    for (int n = 0; n < 200; ++n) {
      const Vec3 p{coordinate(random), coordinate(random), coordinate(random)};
      if (f.name == "sphere" && std::hypot(p[0], p[1], p[2]) < 0.05)
        continue;  // not differentiable at 0
      expect_gradient_matches_differences(f, p);
    }
}

TEST(TestFunction, MarschnerLobbGradientIsSmoothNearTheAxis) {
  const TestFunction& ml = find_test_function("ml");
  // On the axis the radial part vanishes; near it (including the series branch below r = 1e-4)
  // it matches differences.
  const Vec3 g = marschner_lobb_gradient({0, 0, 0.3});
  EXPECT_EQ(g[0], 0.0);
  EXPECT_EQ(g[1], 0.0);
  for (const Vec3& p :
       {Vec3{3e-5, 4e-5, 0.2}, Vec3{-9.9e-5, 0, -0.5}, Vec3{1e-3, -2e-3, 0.7}, Vec3{0.3, 0.1, 0.0}})
    expect_gradient_matches_differences(ml, p);
  // Near the axis (the series branch below r = 1e-4 included) the radial derivative matches the
  // formula d/dx = a sin(2 pi fM u) 2 pi fM (pi/2) sin(pi r/2) (x/r) / (2 (1 + a)), u = cos(pi
  // r/2), evaluated here in long double. Its factor sin(2 pi fM u) is tiny there (~ r^2), so this
  // also checks that the implementation avoids the cancellation in 2 pi fM u ~ 12 pi.
  for (long double r : {3e-5L, 0.99999e-4L, 1.00001e-4L, 2e-3L}) {
    const long double pi = std::numbers::pi_v<long double>, a = 0.25L, fm = 6;
    const long double u = std::cos(pi * r / 2);
    const long double expected = a * std::sin(2 * pi * fm * u) * 2 * pi * fm * (pi / 2) *
                                 std::sin(pi * r / 2) / (2 * (1 + a));
    const double got = marschner_lobb_gradient({static_cast<double>(r), 0, 0.4})[0];
    EXPECT_NEAR(got, static_cast<double>(expected), 1e-9 * std::fabs(static_cast<double>(expected)))
        << "r = " << static_cast<double>(r);
  }
}

TEST(TestFunction, RegistryFindsEveryName) {
  EXPECT_EQ(test_function_names(), "ml|cubic|sphere|gaussian");
  EXPECT_EQ(find_test_function("ml").value, &marschner_lobb);
  EXPECT_EQ(find_test_function("ml").gradient, &marschner_lobb_gradient);
  EXPECT_EQ(find_test_function("cubic").value, &cubic);
  EXPECT_EQ(find_test_function("sphere").gradient, &sphere_gradient);
  EXPECT_EQ(find_test_function("gaussian").value, &gaussian);
  for (const TestFunction& f : test_functions()) EXPECT_FALSE(f.description.empty());
}

TEST(TestFunction, UnknownNameIsOneLineListingTheNames) {
  for (const std::string& name :
       std::vector<std::string>{"", "ML", "foo", "ml\nsecond line", std::string(500, 'x')}) {
    try {
      (void)find_test_function(name);
      ADD_FAILURE() << "no error for '" << name << "'";
    } catch (const std::invalid_argument& e) {
      const std::string message = e.what();
      EXPECT_NE(message.find("ml|cubic|sphere|gaussian"), std::string::npos) << message;
      EXPECT_EQ(message.find('\n'), std::string::npos) << message;
      EXPECT_LT(message.size(), 200u);
    }
  }
}

}  // namespace
}  // namespace boxgen::runtime
