// What the GLSL and CUDA runs share (tests/gpu/gpu_exactness_test.cpp): the filters they check,
// the points with their exact values, and the comparison of a batch of evaluations (value of each
// path, gradients, Hessians) with them, with the tolerances of
// tests/emitted/emitted_accuracy_test.cpp.
#pragma once
#include <algorithm>
#include <cmath>
#include <ostream>
#include <string>
#include <vector>

#include "tests/emitted/exact_reference.h"

namespace boxgen::generator::gpu_test {

using exact_reference::Exact;
using exact_reference::kMaxV;
using exact_reference::Reference;

// A filter emitted at build time (tests/gpu/CMakeLists.txt): its name, preset or matrix, lattice.
struct Filter {
  const char* name;
  const char* spec;
  const char* lattice;
};

// Every registry filter, and a 2-D matrix of this test's own (five directions, not a preset).
inline const Filter kFilters[] = {{"m7", "m7", ""},
                                  {"m8", "m8", ""},
                                  {"m12", "m12", ""},
                                  {"fcc6", "fcc6", ""},
                                  {"tricubic", "tricubic", ""},
                                  {"cart7", "cart7", ""},
                                  {"five", "1,0; 0,1; 1,1; 1,-1; 1,0", ""}};

inline void PrintTo(const Filter& f, std::ostream* os) { *os << f.name; }

#ifndef BOXGEN_GPU_POINTS
#define BOXGEN_GPU_POINTS 1000
#endif

// The test points of a filter and their exact values, computed once for all four targets (the
// rational evaluation costs more than any of them).
struct ExactCase {
  Reference ref;
  std::vector<RatVec> points;
  std::vector<Exact> exact;
  explicit ExactCase(const Filter& f)
      : ref(f.spec, f.lattice), points(exact_reference::test_points(ref, BOXGEN_GPU_POINTS)) {
    for (const auto& x : points) exact.push_back(ref.at(x));
  }
};

// One evaluation per point of each path: value only; value and gradient; value, gradient and
// Hessian (all n x n entries).
struct Evaluations {
  std::vector<double> value0, value1, value2, gradient1, gradient2, hessian;
};

// The tolerances of tests/emitted, relative to max|V| (second derivatives 4x these).
constexpr double kFloatTolerance = 2e-6;
constexpr double kDoubleTolerance = 1e-13;

// A compiled and linked OpenGL compute program (glsl_runner.cpp), or 0 after a test failure
// naming `what` with the compiler's log.
unsigned compute_program(const std::string& source, const std::string& what);
std::string read_text(const std::string& path);

// The four runs (glsl_runner.cpp, cuda_host_runner.cpp); Real is float or double.
template <class Real>
void evaluate_glsl(const Filter& f, const ExactCase& c, Evaluations* e);
template <class Real>
Evaluations evaluate_cuda_host(const Filter& f, const ExactCase& c);

// The worst errors relative to max|V|, against the tolerance; Hessians only where they exist
// (C^2 splines, or off knot planes).
inline void compare(const Reference& ref, const std::vector<Exact>& exact, const Evaluations& e,
                    double tolerance, const std::string& what) {
  const int n = ref.dimension();
  const bool c2 = ref.twice_differentiable();
  double worst = 0, worst_gradient = 0, worst_hessian = 0;
  int hessians = 0;
  for (std::size_t p = 0; p < exact.size(); ++p) {
    const double v = to_double(exact[p].value);
    for (double got : {e.value0[p], e.value1[p], e.value2[p]})
      worst = std::max(worst, std::abs(got - v));
    for (int i = 0; i < n; ++i) {
      const double g = to_double(exact[p].gradient[i]);
      worst_gradient = std::max(worst_gradient, std::abs(e.gradient1[p * n + i] - g));
      worst_gradient = std::max(worst_gradient, std::abs(e.gradient2[p * n + i] - g));
    }
    if (!c2 && !exact[p].hessian_defined) continue;
    ++hessians;
    for (int i = 0; i < n; ++i)
      for (int j = 0; j < n; ++j) {
        const int a = std::min(i, j), b = std::max(i, j);
        const double h = to_double(exact[p].hessian[a * n - a * (a - 1) / 2 + (b - a)]);
        worst_hessian = std::max(worst_hessian, std::abs(e.hessian[(p * n + i) * n + j] - h));
      }
  }
  EXPECT_LE(worst / kMaxV, tolerance) << what << " value";
  EXPECT_LE(worst_gradient / kMaxV, tolerance) << what << " gradient";
  EXPECT_LE(worst_hessian / kMaxV, 4 * tolerance) << what << " hessian";
  EXPECT_GE(hessians, static_cast<int>(exact.size()) / 2) << what;
}

}  // namespace boxgen::generator::gpu_test
