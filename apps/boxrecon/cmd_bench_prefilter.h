// boxrecon bench --prefilter P [--filter F] [--n N]: the time and peak memory of a prefilter
// (cmd_bench_prefilter.cpp).
#pragma once
#include "apps/boxrecon/prefilter_options.h"
#include "runtime/spline_filter.h"

namespace boxgen::app {

// Seconds of spline_coefficients on N^3 x K random samples (the fastest of `repeats`, each on a
// fresh volume moved in, as a command does), and the process's peak resident memory against the
// volume's size in double.
int run_prefilter_bench(const runtime::SplineFilter& f, const PrefilterSetting& setting, int n,
                        int repeats, bool json);

}  // namespace boxgen::app
