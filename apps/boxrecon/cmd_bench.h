// boxrecon bench: evaluation speed of the generated evaluators through the runtime's batch API
// (the paper's Table 2 and the ratios docs/performance.md names). See cmd_bench.cpp.
#pragma once
#include <algorithm>
#include <chrono>
#include <vector>

#include "runtime/lattice_volume.h"

namespace boxrecon {

struct BenchOptions {
  bool quick = false;  // one cache-resident volume, few points: under a minute
  bool json = false;
  long points = 0;  // points per measurement; 0: 10^7 (full) or 2 10^5 (quick)
  int repeats = 3;  // the fastest of this many runs is reported
};

int run_bench(const BenchOptions& options);
// bench --device gl (cmd_bench_gl.cpp): the GL device beside the CPU path in the same run.
int run_gl_bench(const BenchOptions& options);

// The benchmark's data (cmd_bench.cpp): N^3 x 2 BCC samples, random in [0, 1) (unit spacing at the
// origin: lattice = world coordinates); `count` random points whose stencils of M7, M8 and M12 lie
// inside; as many points along parallel rays, half a lattice unit apart.
template <class T>
boxgen::runtime::LatticeVolume<T> random_volume(int n);
std::vector<boxgen::runtime::Vec3> random_points(int n, long count);
std::vector<boxgen::runtime::Vec3> ray_points(int n, long count);

// The wall time of the fastest of `repeats` calls of run(), in seconds: every timing of
// `boxrecon bench` (with or without --filter) is taken this way.
template <class F>
double fastest_seconds(int repeats, F&& run) {
  double best = 1e300;
  for (int r = 0; r < repeats; ++r) {
    const auto t0 = std::chrono::steady_clock::now();
    run();
    best = std::min(best,
                    std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count());
  }
  return best;
}

}  // namespace boxrecon
