// What a user waits for in `boxgen analyze SPEC`: the exact derivation of the piecewise form and
// structure plus the default exact checks, for the presets (with their time limits) and the
// table of matrices a researcher tries next (at most 10 s and 1 GB each; degree 1 and 2 under
// 1 s). Each iteration runs in a forked child, so its peak memory (ru_maxrss) and CPU time are
// its own; the counters also show the cost estimate (`boxgen analyze --estimate`) beside them.
#include <benchmark/benchmark.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cstdlib>
#include <sstream>
#include <string>
#include <vector>

#include "generator/cost_estimate.h"
#include "generator/derivation.h"
#include "generator/spec.h"

namespace {

struct Case {
  std::string spec;
  const char* lattice;
  double target_seconds;
};

// The directions "a; b; ..." as "a; a; ...; b; b; ..." (each `times` times), or the whole list
// `times` times ("a; b; ...; a; b; ...") when `whole`.
std::string repeated(const std::string& directions, int times, bool whole = false) {
  std::vector<std::string> list;
  std::stringstream in(directions);
  for (std::string d; std::getline(in, d, ';');) list.push_back(d);
  std::string out;
  for (int outer = 0; outer < (whole ? times : 1); ++outer)
    for (const std::string& d : list)
      for (int inner = 0; inner < (whole ? 1 : times); ++inner) out += (out.empty() ? "" : ";") + d;
  return out;
}

void analyze_case(benchmark::State& state, const Case& c) {
  const boxgen::generator::BoxSplineSpec spec = boxgen::generator::parse_spec(c.spec, c.lattice);
  const boxgen::generator::CostEstimate estimate = boxgen::generator::estimate_cost(spec);
  double peak_mb = 0, user_s = 0;
  for (auto _ : state) {
    const auto start = std::chrono::steady_clock::now();
    const pid_t child = fork();
    if (child == 0) {
      // A failed exact check throws: the child then exits non-zero and the run is an error.
      try {
        benchmark::DoNotOptimize(boxgen::generator::derive(spec).pieces);
      } catch (...) {
        _exit(1);
      }
      _exit(0);
    }
    int status = 0;
    rusage usage{};
    wait4(child, &status, 0, &usage);
    state.SetIterationTime(
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
    if (!WIFEXITED(status) || WEXITSTATUS(status) != 0)
      state.SkipWithError("the derivation or a check failed");
    peak_mb = std::max(peak_mb, static_cast<double>(usage.ru_maxrss) / 1024.0);
    user_s = static_cast<double>(usage.ru_utime.tv_sec) +
             static_cast<double>(usage.ru_utime.tv_usec) * 1e-6;
  }
  state.counters["target_s"] = c.target_seconds;
  state.counters["user_s"] = user_s;  // CPU time: less noisy than wall clock on a shared machine
  state.counters["peak_MB"] = peak_mb;
  state.counters["estimate_s"] = estimate.seconds;
  state.counters["estimate_MB"] = estimate.bytes / 1e6;
  state.counters["knot_cells"] = static_cast<double>(estimate.knot_cells);
}

#define BOXGEN_DERIVATION_BENCHMARK(name, spec, lattice, target)     \
  BENCHMARK_CAPTURE(analyze_case, name, Case{spec, lattice, target}) \
      ->Unit(benchmark::kSecond)                                     \
      ->UseManualTime()                                              \
      ->Iterations(1)

// Presets (with their time limits).
BOXGEN_DERIVATION_BENCHMARK(m7, "m7", "", 10);
BOXGEN_DERIVATION_BENCHMARK(m8, "m8", "", 20);
BOXGEN_DERIVATION_BENCHMARK(m12, "m12", "", 60);
BOXGEN_DERIVATION_BENCHMARK(fcc6, "fcc6", "", 20);
BOXGEN_DERIVATION_BENCHMARK(cart7, "cart7", "", 20);
// Matrices a researcher tries next.
BOXGEN_DERIVATION_BENCHMARK(cartesian_and_face_diagonals,
                            "1,0,0; 0,1,0; 0,0,1; 1,1,0; 1,-1,0; 1,0,1; 1,0,-1; 0,1,1; 0,1,-1",
                            "cartesian", 10);
BOXGEN_DERIVATION_BENCHMARK(
    fcc6_twice,
    "1,1,0; 1,-1,0; 1,0,1; 1,0,-1; 0,1,1; 0,1,-1; 1,1,0; 1,-1,0; 1,0,1; 1,0,-1; 0,1,1; 0,1,-1",
    "fcc", 10);
BOXGEN_DERIVATION_BENCHMARK(
    cart7_and_axes, "1,0,0; 0,1,0; 0,0,1; 1,1,1; 1,1,-1; 1,-1,1; -1,1,1; 1,0,0; 0,1,0; 0,0,1",
    "cartesian", 10);
BOXGEN_DERIVATION_BENCHMARK(scaled_hat, "64,0; 0,64; 64,64", "64,0; 0,64", 1);
BOXGEN_DERIVATION_BENCHMARK(long_directions, "20,1; 1,20; 7,5; -9,4", "cartesian", 1);
// Matrices of the same kinds that the table does not list (README, "Derivation cost"):
// longer or skewed directions, degree 1 to 4, the degree-1 and degree-2 ones under 1 s.
BOXGEN_DERIVATION_BENCHMARK(skewed_4_degree_1, "4,1,0; 0,4,1; 1,0,4; 1,1,1", "cartesian", 1);
BOXGEN_DERIVATION_BENCHMARK(skewed_2_degree_2, "2,1,0; 0,2,1; 1,0,2; 1,1,1; 1,1,-1", "cartesian",
                            1);
BOXGEN_DERIVATION_BENCHMARK(skewed_3_degree_1, "3,1,0; 0,3,1; 1,0,3; 1,1,1", "cartesian", 1);
BOXGEN_DERIVATION_BENCHMARK(longer_directions, "30,1; 1,30; 11,7; -13,5", "cartesian", 1);
BOXGEN_DERIVATION_BENCHMARK(five_2d_directions, "5,2; -3,7; 4,4; 1,-6; 2,9", "cartesian", 10);
BOXGEN_DERIVATION_BENCHMARK(axes_diagonal_two_faces, "1,0,0; 0,1,0; 0,0,1; 1,1,1; 1,-1,0; 0,1,-1",
                            "cartesian", 10);
BOXGEN_DERIVATION_BENCHMARK(axes_three_faces_diagonal,
                            "1,0,0; 0,1,0; 0,0,1; 1,1,0; 1,0,1; 0,1,1; 1,1,1", "cartesian", 10);
BOXGEN_DERIVATION_BENCHMARK(skewed_2_with_face, "2,1,0; 0,2,1; 1,0,2; 1,1,1; 1,-1,0", "cartesian",
                            1);
BOXGEN_DERIVATION_BENCHMARK(skewed_3_with_face, "3,1,1; 1,3,1; 1,1,3; 1,-1,0", "cartesian", 1);
BOXGEN_DERIVATION_BENCHMARK(skewed_5_2_1, "5,2,1; 1,1,0; 0,1,1; 1,0,1", "cartesian", 1);
// Scale invariance: M7 scaled by 8 and 32 on the correspondingly scaled BCC lattice (the same time
// as the m7 row: the pair is derived as M7 and stretched back, generator/common_scale.h).
BOXGEN_DERIVATION_BENCHMARK(m7_scaled_by_8,
                            "8,8,8; 8,-8,-8; -8,8,-8; -8,-8,8; 16,0,0; 0,16,0; 0,0,16",
                            "-8,8,8; 8,-8,8; 8,8,-8", 10);
BOXGEN_DERIVATION_BENCHMARK(m7_scaled_by_32,
                            "32,32,32; 32,-32,-32; -32,32,-32; -32,-32,32; 64,0,0; 0,64,0; 0,0,64",
                            "-32,32,32; 32,-32,32; 32,32,-32", 10);

// Estimate rows: the families the cost estimate is fitted on (docs/performance.md, "Cost
// estimate"; the two 32-direction rows there take minutes each and are commands, not benchmark
// rows; target 0: none), and long axes with a diagonal (the stencil of 274432 points dominates).
BOXGEN_DERIVATION_BENCHMARK(square_directions_5, repeated("1,0; 0,1; 1,1; 1,-1", 5), "cartesian",
                            0);
BOXGEN_DERIVATION_BENCHMARK(square_directions_6, repeated("1,0; 0,1; 1,1; 1,-1", 6), "cartesian",
                            0);
BOXGEN_DERIVATION_BENCHMARK(axes_7, repeated("1,0,0; 0,1,0; 0,0,1", 7), "cartesian", 0);
BOXGEN_DERIVATION_BENCHMARK(axes_9, repeated("1,0,0; 0,1,0; 0,0,1", 9), "cartesian", 0);
BOXGEN_DERIVATION_BENCHMARK(axes_and_diagonal_3, repeated("1,0,0; 0,1,0; 0,0,1; 1,1,1", 3, true),
                            "cartesian", 0);
BOXGEN_DERIVATION_BENCHMARK(axes_and_diagonal_4, repeated("1,0,0; 0,1,0; 0,0,1; 1,1,1", 4, true),
                            "cartesian", 0);
BOXGEN_DERIVATION_BENCHMARK(long_axes_and_diagonal, "64,0,0; 0,64,0; 0,0,64; 1,1,1", "cartesian",
                            10);

}  // namespace

BENCHMARK_MAIN();
