// boxrecon bench: evaluation speed of the generated evaluators through the runtime's batch API
// (the paper's Table 2 and the ratios of issue 8). See cmd_bench.cpp.
#pragma once
#include <algorithm>
#include <chrono>

namespace boxrecon {

struct BenchOptions {
  bool quick = false;  // one cache-resident volume, few points: under a minute
  bool json = false;
  long points = 0;  // points per measurement; 0: 10^7 (full) or 2 10^5 (quick)
  int repeats = 3;  // the fastest of this many runs is reported
};

int run_bench(const BenchOptions& options);

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
