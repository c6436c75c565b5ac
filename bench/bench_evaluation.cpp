// Time per evaluation of the emitted M7, M8 and M12 evaluators, one strategy against the other
// (generated/ holds the default, horner; the monomial ones are emitted at build time). One
// thread, data from an in-memory hash (no volume, no bounds checks), points uniform in a box of
// lattice coordinates, value only and value + gradient.
#include <benchmark/benchmark.h>

#include <array>
#include <cstdint>
#include <random>
#include <vector>

#include "emitted/m12_monomial.hpp"
#include "emitted/m7_monomial.hpp"
#include "emitted/m8_monomial.hpp"
#include "generated/m12.hpp"
#include "generated/m7.hpp"
#include "generated/m8.hpp"

namespace {

using Point3 = std::array<std::int64_t, 3>;

// A cheap fetch: values of a fixed pseudo-random field, so the optimiser cannot fold them.
struct HashFetch {
  double operator()(const Point3& j) const {
    std::uint64_t h = static_cast<std::uint64_t>(j[0] * 73856093) ^ static_cast<std::uint64_t>(j[1] * 19349663) ^
                      static_cast<std::uint64_t>(j[2] * 83492791);
    h ^= h >> 13;
    return static_cast<double>(h & 1023) / 1024.0;
  }
};

std::vector<std::array<double, 3>> points() {
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> u(-8.0, 8.0);
  std::vector<std::array<double, 3>> p(4096);
  for (auto& x : p) x = {u(rng), u(rng), u(rng)};
  return p;
}

template <class Evaluate>
void run(benchmark::State& state, Evaluate evaluate, bool gradient) {
  const auto xs = points();
  std::size_t i = 0;
  std::array<double, 3> g{};
  for (auto _ : state) {
    const double v = evaluate(xs[i], gradient ? &g : nullptr);
    benchmark::DoNotOptimize(v);
    benchmark::DoNotOptimize(g);
    i = (i + 1) & (xs.size() - 1);
  }
  state.SetItemsProcessed(state.iterations());
}

#define BOXGEN_EVAL_BENCHMARK(NS)                                                                       \
  void NS##_value(benchmark::State& s) {                                                                \
    run(s, [](const auto& x, auto* g) { return boxgen::generated::NS::evaluate<double>(x, HashFetch{}, g); }, false); \
  }                                                                                                     \
  void NS##_gradient(benchmark::State& s) {                                                             \
    run(s, [](const auto& x, auto* g) { return boxgen::generated::NS::evaluate<double>(x, HashFetch{}, g); }, true); \
  }                                                                                                     \
  BENCHMARK(NS##_value);                                                                                \
  BENCHMARK(NS##_gradient)

BOXGEN_EVAL_BENCHMARK(m7);
BOXGEN_EVAL_BENCHMARK(m7_monomial);
BOXGEN_EVAL_BENCHMARK(m8);
BOXGEN_EVAL_BENCHMARK(m8_monomial);
BOXGEN_EVAL_BENCHMARK(m12);
BOXGEN_EVAL_BENCHMARK(m12_monomial);

}  // namespace

BENCHMARK_MAIN();
