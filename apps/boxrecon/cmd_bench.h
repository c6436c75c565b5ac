// boxrecon bench: evaluation speed of the generated evaluators through the runtime's batch API
// (the paper's Table 2 and the ratios of issue 8). See cmd_bench.cpp.
#pragma once

namespace boxrecon {

struct BenchOptions {
  bool quick = false;  // one cache-resident volume, few points: under a minute
  bool json = false;
  long points = 0;  // points per measurement; 0: 10^7 (full) or 2 10^5 (quick)
  int repeats = 3;  // the fastest of this many runs is reported
};

int run_bench(const BenchOptions& options);

}  // namespace boxrecon
