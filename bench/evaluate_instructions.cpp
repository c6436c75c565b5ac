// Instructions of an emitted C++ evaluator alone, under valgrind (which stops in Highway's start-up
// on this machine, so the runtime's benchmarks cannot be counted here): `evaluate<float>` of
// generated/FILTER.hpp at N pseudo-random points of [-4, 4)^3, on the path PATH (0 value,
// 1 + gradient, 2 + Hessian), fetching hash data. It links nothing but the header and its glue,
// so the same file builds against an older tree's generated/ to compare emitters:
//   g++ -std=c++20 -O3 -DNDEBUG -I TREE -DFILTER=m7 bench/evaluate_instructions.cpp -o eval_m7
//   valgrind --tool=callgrind --callgrind-out-file=/dev/null ./eval_m7 20000 2   # minus N = 0
// The build here compiles it for m7 (bench_evaluate_instructions_m7) so that it cannot rot.
#include <array>
#include <cstdint>
#include <cstdio>
#include <cstdlib>

#define BOXGEN_STRINGIFY2(x) #x
#define BOXGEN_STRINGIFY(x) BOXGEN_STRINGIFY2(x)
// A path, not an expression:
// clang-format off
#include BOXGEN_STRINGIFY(generated/FILTER.hpp)
// clang-format on

namespace filter = boxgen::generated::FILTER;

int main(int argc, char** argv) {
  if (argc != 3) {
    std::fprintf(stderr, "usage: %s N PATH (PATH 0 value, 1 + gradient, 2 + Hessian)\n", argv[0]);
    return 2;
  }
  const long n = std::atol(argv[1]);
  const int path = std::atoi(argv[2]);
  std::uint64_t state = 12345;
  const auto uniform = [&] {
    state = state * 6364136223846793005ULL + 1442695040888963407ULL;
    return static_cast<float>((state >> 40) % 100000) / 100000.0F * 8.0F - 4.0F;
  };
  const auto fetch = [](const auto& j) {
    std::uint64_t h = 1469598103934665603ULL;
    for (auto v : j) h = (h ^ static_cast<std::uint64_t>(v + 4096)) * 1099511628211ULL;
    return static_cast<float>(h % 2001) - 1000.0F;
  };
  double sum = 0;
  for (long i = 0; i < n; ++i) {
    std::array<float, 3> x{uniform(), uniform(), uniform()};
    std::array<float, 3> g{};
    std::array<float, 6> h{};
    const float v =
        filter::evaluate<float>(x, fetch, path >= 1 ? &g : nullptr, path >= 2 ? &h : nullptr);
    sum += v + g[0] + h[0];
  }
  std::printf("checksum %.6g\n", sum);
  return 0;
}
