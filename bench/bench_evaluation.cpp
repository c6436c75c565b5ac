// Evaluation speed (Google Benchmark; `boxrecon bench` prints the ratios and the full
// Table 2 replica). Two groups:
//   scalar/<filter>_<strategy>_<path>: the emitted evaluate<double>() per strategy (generated/
//     holds the cost-chosen `auto` forms; the monomial and Horner ones are emitted at build time),
//     data from an in-memory hash (no volume, no bounds checks), value / gradient / Hessian paths;
//   batch/<filter>/<precision>/N: Reconstructor<T>::evaluate on one thread at random points of an
//     N^3 x 2 volume (the paper's Table 2 sizes, and 96), items = points;
//   threads/<filter>/float/N:96/threads: the same with 400,000 points per call on 1 and 2 threads
//     (wall clock: the batch API's own OpenMP threads).
#include <benchmark/benchmark.h>

#include <array>
#include <cstdint>
#include <random>
#include <vector>

#include "emitted/m12_horner.hpp"
#include "emitted/m12_monomial.hpp"
#include "emitted/m7_bernstein.hpp"
#include "emitted/m7_horner.hpp"
#include "emitted/m7_monomial.hpp"
#include "emitted/m8_bernstein.hpp"
#include "emitted/m8_horner.hpp"
#include "emitted/m8_monomial.hpp"
#include "generated/m12.hpp"
#include "generated/m7.hpp"
#include "generated/m8.hpp"
#include "runtime/batch_threads.h"
#include "runtime/reconstruction.h"

namespace {

using Point3 = std::array<std::int64_t, 3>;

// A cheap fetch: values of a fixed pseudo-random field, so the optimiser cannot fold them.
struct HashFetch {
  double operator()(const Point3& j) const {
    std::uint64_t h = static_cast<std::uint64_t>(j[0] * 73856093) ^
                      static_cast<std::uint64_t>(j[1] * 19349663) ^
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
void run(benchmark::State& state, Evaluate evaluate, int order) {
  const auto xs = points();
  std::size_t i = 0;
  std::array<double, 3> g{};
  std::array<double, 6> h{};
  for (auto _ : state) {
    const double v = evaluate(xs[i], order >= 1 ? &g : nullptr, order >= 2 ? &h : nullptr);
    benchmark::DoNotOptimize(v);
    benchmark::DoNotOptimize(g);
    benchmark::DoNotOptimize(h);
    i = (i + 1) & (xs.size() - 1);
  }
  state.SetItemsProcessed(state.iterations());
}

#define BOXGEN_SCALAR_BENCHMARK(NS)                                             \
  void NS##_scalar(benchmark::State& s) {                                       \
    run(                                                                        \
        s,                                                                      \
        [](const auto& x, auto* g, auto* h) {                                   \
          return boxgen::generated::NS::evaluate<double>(x, HashFetch{}, g, h); \
        },                                                                      \
        static_cast<int>(s.range(0)));                                          \
  }                                                                             \
  BENCHMARK(NS##_scalar)->Name("scalar/" #NS)->ArgName("order")->DenseRange(0, 2)

BOXGEN_SCALAR_BENCHMARK(m7);
BOXGEN_SCALAR_BENCHMARK(m7_horner);
BOXGEN_SCALAR_BENCHMARK(m7_bernstein);
BOXGEN_SCALAR_BENCHMARK(m7_monomial);
BOXGEN_SCALAR_BENCHMARK(m8);
BOXGEN_SCALAR_BENCHMARK(m8_horner);
BOXGEN_SCALAR_BENCHMARK(m8_bernstein);
BOXGEN_SCALAR_BENCHMARK(m8_monomial);
BOXGEN_SCALAR_BENCHMARK(m12);
BOXGEN_SCALAR_BENCHMARK(m12_horner);
BOXGEN_SCALAR_BENCHMARK(m12_monomial);

template <class T>
void batch(benchmark::State& state, const char* filter, int threads = 1, int count = 100000) {
  using namespace boxgen::runtime;
  const int n = static_cast<int>(state.range(0));
  LatticeVolume<T> volume(CosetLattice::bcc(), {n, n, n}, 1.0, {0, 0, 0});
  std::mt19937_64 rng(n);
  for (auto& s : volume.samples()) s = static_cast<T>(static_cast<double>(rng() % 4096) / 4096.0);
  std::uniform_real_distribution<double> u(6.0, 2.0 * n - 7.0);
  std::vector<Vec3> pts(static_cast<std::size_t>(count));
  for (auto& p : pts) p = {u(rng), u(rng), u(rng)};
  std::vector<T> values(pts.size());
  set_batch_threads(threads);
  const Reconstructor<T> r(volume, SplineFilter::parse(filter));
  for (auto _ : state) {
    r.evaluate(pts, values);
    benchmark::DoNotOptimize(values.data());
  }
  state.SetItemsProcessed(state.iterations() * static_cast<std::int64_t>(pts.size()));
  set_batch_threads(0);
}

void batch_float(benchmark::State& state, const char* f) { batch<float>(state, f); }
void batch_double(benchmark::State& state, const char* f) { batch<double>(state, f); }

#define BOXGEN_BATCH_BENCHMARK(F, name, T)    \
  BENCHMARK_CAPTURE(batch_##T, F##_##T, name) \
      ->Name("batch/" #F "/" #T)              \
      ->ArgName("N")                          \
      ->Arg(21)                               \
      ->Arg(32)                               \
      ->Arg(45)                               \
      ->Arg(77)                               \
      ->Arg(96)                               \
      ->Arg(117)                              \
      ->Unit(benchmark::kMillisecond)

BOXGEN_BATCH_BENCHMARK(M7, "m7", float);
BOXGEN_BATCH_BENCHMARK(M8, "m8", float);
BOXGEN_BATCH_BENCHMARK(M12, "m12", float);
BOXGEN_BATCH_BENCHMARK(M7, "m7", double);
BOXGEN_BATCH_BENCHMARK(M8, "m8", double);
BOXGEN_BATCH_BENCHMARK(M12, "m12", double);

void threads_float(benchmark::State& state, const char* f) {
  batch<float>(state, f, static_cast<int>(state.range(1)), 400000);
}

#define BOXGEN_THREADS_BENCHMARK(F, name)           \
  BENCHMARK_CAPTURE(threads_float, F##_float, name) \
      ->Name("threads/" #F "/float")                \
      ->ArgNames({"N", "threads"})                  \
      ->Args({96, 1})                               \
      ->Args({96, 2})                               \
      ->UseRealTime()                               \
      ->Unit(benchmark::kMillisecond)

BOXGEN_THREADS_BENCHMARK(M7, "m7");
BOXGEN_THREADS_BENCHMARK(M8, "m8");
BOXGEN_THREADS_BENCHMARK(M12, "m12");

}  // namespace

BENCHMARK_MAIN();
