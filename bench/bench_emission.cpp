// Derivation + emission time of M7, M8 and M12: boxgen emit's work (the exact analysis with its
// default checks, then the cost-chosen emission of the evaluator and prefilter headers), wall
// clock. The time limits we keep are shown as target_s.
#include <benchmark/benchmark.h>

#include "generator/codegen/emitter.h"
#include "generator/derivation.h"
#include "generator/spec.h"

namespace {

void derive_and_emit(benchmark::State& state, const char* preset, double target_seconds) {
  std::size_t bytes = 0;
  for (auto _ : state) {
    const boxgen::generator::Derivation a =
        boxgen::generator::derive(boxgen::generator::parse_spec(preset));
    for (const auto& f :
         boxgen::generator::emit(a, {preset, "bench", boxgen::generator::EmissionStrategy::Auto})
             .files)
      bytes += f.text.size();
    benchmark::DoNotOptimize(bytes);
  }
  state.counters["target_s"] = target_seconds;
}

#define BOXGEN_EMISSION_BENCHMARK(preset, target)             \
  BENCHMARK_CAPTURE(derive_and_emit, preset, #preset, target) \
      ->Unit(benchmark::kSecond)                              \
      ->Iterations(1)

BOXGEN_EMISSION_BENCHMARK(m7, 10);
BOXGEN_EMISSION_BENCHMARK(m8, 20);
BOXGEN_EMISSION_BENCHMARK(m12, 60);

}  // namespace

BENCHMARK_MAIN();
