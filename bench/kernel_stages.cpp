// Where the chunk kernel (runtime/simd_kernels-inl.h) of M7 and M8 spends its time, stage by stage
// (docs/performance.md, "Why M7's time ratio lags its instruction ratio"). For the same random
// points of an n^3 x 2 BCC volume, one thread, the thread CPU time per point of
//   full:   the kernel as Reconstructor runs it: locate, stencil addresses, gathers, polynomial;
//   fetch:  the same with the orbit polynomial replaced by the sum of the stencil values;
//   locate: locate and the stencil addresses only (no gather, no polynomial);
//   prefetched: an experiment, not the library's kernel: `full` after prefetching the stencil
//           samples of the NEXT chunk's points (located once more for that), every sample or
//           every N-th with `prefetch=N`, so that their memory latency overlaps this chunk's work;
//   pipelined: the same experiment with each chunk located once (the lanes carried from one call
//           to the next); with `prefetch=lines` only where a sample's cache line differs from the
//           previous sample's. Both give `full`'s values bit for bit (checked before timing).
// Each stage is a simd::Kernels chunk function passed to EmittedSpline, so all run through
// the same batch loop; all are compiled here for this machine alone (-march=native, as
// loader/ compiles a filter's kernels). The stages and filters alternate, round after round, and
// the minimum and median over the rounds are printed:
//   build/bench/bench_kernel_stages [double] [side=32] [rounds=30] [prefetch=1|N|lines]
#define HWY_COMPILE_ONLY_STATIC 1
#include <hwy/highway.h>

#include <algorithm>
#include <cstddef>
#include <cstdio>
#include <cstdlib>
#include <ctime>
#include <exception>
#include <random>
#include <span>
#include <string>
#include <vector>

#include "generated/m7.hpp"
#include "generated/m8.hpp"
#include "runtime/batch_threads.h"
#include "runtime/emitted_spline.h"
#include "runtime/simd_kernels-inl.h"

namespace rt = boxgen::runtime;
namespace simd = rt::simd;
namespace kernels = rt::simd::HWY_NAMESPACE;
namespace hn = hwy::HWY_NAMESPACE;
namespace support = boxgen::generated::support;

namespace {

// Tr with the orbit polynomial replaced by the sum of the orbit's stencil values: the kernel's
// fetch floor (every sample is still gathered, since the sum uses it).
template <class Tr>
struct StencilSum : Tr {
  template <int Order, class T>
  static T orbit(int o, const T* v, const T* /*x*/, T* /*d*/) {
    T sum = v[0];
    for (int k = 1; k < Tr::kOrbitStencilSize[o]; ++k) sum = sum + v[k];
    return sum;
  }
};

// The value path of the chunk kernel of Tr (the bench asks for values only).
template <class Tr, class T>
void value_chunk(int /*order*/, const double* points, const simd::Frame& frame,
                 const simd::LinearVolume<T>& volume, T* out) {
  kernels::evaluate_lanes<Tr, support::kValue>(
      points, frame, volume, out, std::make_integer_sequence<int, rt::StencilSteps<Tr>::kOrbits>{});
}

// Locate and stencil addresses only: the stages of evaluate_lanes before the gathers; the value of
// a lane is its first sample's index, so that nothing is optimised away.
template <class Tr, class T>
[[gnu::flatten]] void locate_chunk(int /*order*/, const double* points, const simd::Frame& frame,
                                   const simd::LinearVolume<T>& volume, T* out) {
  constexpr int kRow = simd::kChunk;
  const typename kernels::Pack<T>::D d;
  alignas(64) T x[3 * kRow];
  alignas(64) T near[kRow];
  kernels::lattice_lanes(points, frame, x, near);
  for (int at = 0; at < kRow; at += static_cast<int>(hn::Lanes(d))) {
    const auto l = kernels::locate_pack<Tr>(x, near, at, frame);
    const auto st = kernels::lane_stencil<Tr>(l, volume);
    auto index = hn::Add(st.first, hn::Add(st.flip, hn::Add(st.axis[0], st.axis[1])));
    index = hn::Add(index, st.axis[2]);
    hn::StoreU(hn::ConvertTo(d, index), d, out + at);
    hn::StoreU(l.cell.v, d, out + simd::kChunkCellRow * kRow + at);
    hn::StoreU(hn::IfThenElseZero(l.ok, hn::Set(d, T(1))), d, out + simd::kChunkOkRow * kRow + at);
  }
}

// The `prefetched` stage: prefetch the stencil samples of the chunk at `points` (the next one: the
// bench pads its points so that it is readable), every prefetch_every-th of them, lanes outside the
// volume at sample index 0. M7 and M8 have one orbit each.
int prefetch_every = 1;

// A prefetch the compiler keeps: GCC 12 removed every __builtin_prefetch (and _mm_prefetch) of
// prefetch_next, whose only effect is the prefetches.
inline void prefetch_line(const void* p) {
#if defined(__x86_64__) || defined(__i386__)
  asm volatile("prefetcht0 %0" : : "m"(*static_cast<const char*>(p)));
#else
  __builtin_prefetch(p, 0, 3);
#endif
}

template <class Tr, class T, int... K>
[[gnu::flatten]] HWY_ATTR void prefetch_next(const double* points, const simd::Frame& frame,
                                             const simd::LinearVolume<T>& volume,
                                             std::integer_sequence<int, K...> /*samples*/) {
  constexpr int kRow = simd::kChunk;
  const typename kernels::Pack<T>::D d;
  const hn::RebindToSigned<decltype(d)> di;
  using I = hn::TFromD<decltype(di)>;
  alignas(64) T x[3 * kRow];
  alignas(64) T near[kRow];
  kernels::lattice_lanes(points, frame, x, near);
  for (int at = 0; at < kRow; at += static_cast<int>(hn::Lanes(d))) {
    const auto l = kernels::locate_pack<Tr>(x, near, at, frame);
    auto st = kernels::lane_stencil<Tr>(l, volume);
    const auto m = hn::RebindMask(di, l.ok);
    st.first = hn::IfThenElseZero(m, st.first);
    st.flip = hn::IfThenElseZero(m, st.flip);
    for (auto& a : st.axis) a = hn::IfThenElseZero(m, a);
    alignas(64) I index[sizeof...(K)][hn::MaxLanes(di)];
    ((hn::Store(kernels::sample_index<Tr, 0, K>(st.first, st.axis, st.flip), di, index[K])), ...);
    for (std::size_t k = 0; k < sizeof...(K);
         k += static_cast<std::size_t>(std::max(1, prefetch_every)))
      for (std::size_t lane = 0; lane < hn::Lanes(di); ++lane)
        prefetch_line(volume.samples + index[k][lane]);
  }
}

template <class Tr, class T>
void prefetched_chunk(int order, const double* points, const simd::Frame& frame,
                      const simd::LinearVolume<T>& volume, T* out) {
  static_assert(Tr::kOrbitCount == 1, "the prefetch takes orbit 0's stencil");
  prefetch_next<Tr>(points + std::ptrdiff_t{3} * simd::kChunk, frame, volume,
                    std::make_integer_sequence<int, Tr::kOrbitStencilSize[0]>{});
  value_chunk<Tr, T>(order, points, frame, volume, out);
}

// The `pipelined` stage: each chunk located once. A call evaluates its chunk from the lanes the
// previous call located (when that call's next chunk is this one), then locates the next chunk
// and prefetches its stencil samples (every prefetch_every-th) before evaluating its own.
template <class Tr, class T>
struct Carried {
  using D = typename kernels::Pack<T>::D;
  using V = hn::Vec<hn::RebindToSigned<D>>;
  static constexpr int kVectors = simd::kChunk / static_cast<int>(hn::MaxLanes(D()));
  const double* points = nullptr;
  kernels::LocatedPack<Tr, T> l[kVectors];
  kernels::LaneStencil<V> st[kVectors];
};
template <class Tr, class T>
thread_local Carried<Tr, T> carried;

template <class Tr, class T, int... K>
[[gnu::flatten]] HWY_ATTR void locate_into(const double* points, const simd::Frame& frame,
                                           const simd::LinearVolume<T>& volume, Carried<Tr, T>& c,
                                           bool prefetch,
                                           std::integer_sequence<int, K...> /*samples*/) {
  constexpr int kRow = simd::kChunk;
  const typename kernels::Pack<T>::D d;
  const hn::RebindToSigned<decltype(d)> di;
  using I = hn::TFromD<decltype(di)>;
  alignas(64) T x[3 * kRow];
  alignas(64) T near[kRow];
  kernels::lattice_lanes(points, frame, x, near);
  for (int v = 0; v < Carried<Tr, T>::kVectors; ++v) {
    const int at = v * static_cast<int>(hn::Lanes(d));
    c.l[v] = kernels::locate_pack<Tr>(x, near, at, frame);
    c.st[v] = kernels::lane_stencil<Tr>(c.l[v], volume);
    if (!prefetch) continue;
    const auto m = hn::RebindMask(di, c.l[v].ok);
    typename Carried<Tr, T>::V axis[3];
    for (int i = 0; i < 3; ++i) axis[i] = hn::IfThenElseZero(m, c.st[v].axis[i]);
    const auto first = hn::IfThenElseZero(m, c.st[v].first);
    const auto flip = hn::IfThenElseZero(m, c.st[v].flip);
    if (prefetch_every == 0) {
      // One prefetch per change of cache line from the previous sample (per lane): the samples
      // whose line differs, compressed into one list.
      constexpr int kShift = sizeof(T) == 4 ? 4 : 3;  // sample index -> 64-byte line
      alignas(64) I wanted[sizeof...(K) * hn::MaxLanes(di)];
      std::size_t count = 0;
      auto previous = hn::Set(di, I{-1});
      (
          [&]() HWY_ATTR {
            const auto index = kernels::sample_index<Tr, 0, K>(first, axis, flip);
            const auto line = hn::ShiftRight<kShift>(index);
            count += hn::CompressStore(index, hn::Ne(line, previous), di, wanted + count);
            previous = line;
          }(),
          ...);
      for (std::size_t i = 0; i < count; ++i) prefetch_line(volume.samples + wanted[i]);
      continue;
    }
    alignas(64) I index[sizeof...(K)][hn::MaxLanes(di)];
    ((hn::Store(kernels::sample_index<Tr, 0, K>(first, axis, flip), di, index[K])), ...);
    for (std::size_t k = 0; k < sizeof...(K); k += static_cast<std::size_t>(prefetch_every))
      for (std::size_t lane = 0; lane < hn::Lanes(di); ++lane)
        prefetch_line(volume.samples + index[k][lane]);
  }
  c.points = points;
}

template <class Tr, class T>
[[gnu::flatten]] HWY_ATTR void pipelined_chunk(int /*order*/, const double* points,
                                               const simd::Frame& frame,
                                               const simd::LinearVolume<T>& volume, T* out) {
  static_assert(Tr::kOrbitCount == 1, "the prefetch takes orbit 0's stencil");
  constexpr int kRow = simd::kChunk;
  constexpr auto kSamples = std::make_integer_sequence<int, Tr::kOrbitStencilSize[0]>{};
  using P = kernels::Pack<T>;
  const typename P::D d;
  Carried<Tr, T>& c = carried<Tr, T>;
  if (c.points != points) locate_into<Tr>(points, frame, volume, c, false, kSamples);
  const Carried<Tr, T> now = c;
  locate_into<Tr>(points + std::ptrdiff_t{3} * kRow, frame, volume, c, true, kSamples);
  for (int v = 0; v < Carried<Tr, T>::kVectors; ++v) {
    const int at = v * static_cast<int>(hn::Lanes(d));
    P value(0.0);
    P derivatives[1] = {P(0.0)};
    kernels::evaluate_orbit<Tr, support::kValue, 0>(volume, frame, now.l[v], now.l[v].ok, now.st[v],
                                                    value, derivatives);
    hn::StoreU(value.v, d, out + at);
    hn::StoreU(now.l[v].cell.v, d, out + simd::kChunkCellRow * kRow + at);
    hn::StoreU(hn::IfThenElseZero(now.l[v].ok, hn::Set(d, T(1))), d,
               out + simd::kChunkOkRow * kRow + at);
  }
}

template <class T>
double thread_ns() {
  timespec t{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
  return 1e9 * static_cast<double>(t.tv_sec) + static_cast<double>(t.tv_nsec);
}

// One filter's three stages on one volume and one set of points.
template <class Tr, class T>
class Stages {
 public:
  Stages(int registry_index, int side, std::span<const rt::Vec3> points)
      : volume_(rt::CosetLattice::bcc(), {side, side, side}, 1.0, {0, 0, 0}), points_(points) {
    std::mt19937_64 rng(1);
    for (auto& s : volume_.samples()) s = static_cast<T>(rng() % 1000) / T(1000);
    const simd::Kernels& registry = *simd::registry_kernels(registry_index);
    for (simd::Kernels& k : kernels_) k = registry;
    set_chunk(kernels_[0], &value_chunk<Tr, float>, &value_chunk<Tr, double>);
    set_chunk(kernels_[1], &value_chunk<StencilSum<Tr>, float>,
              &value_chunk<StencilSum<Tr>, double>);
    set_chunk(kernels_[2], &locate_chunk<Tr, float>, &locate_chunk<Tr, double>);
    set_chunk(kernels_[3], &prefetched_chunk<Tr, float>, &prefetched_chunk<Tr, double>);
    set_chunk(kernels_[4], &pipelined_chunk<Tr, float>, &pipelined_chunk<Tr, double>);
    values_.resize(points.size());
  }

  // Thread CPU ns per point of stage s (0 full, 1 fetch, 2 locate, 3 prefetched, 4 pipelined).
  double run(int s) {
    using Spline = rt::EmittedSpline<Tr, rt::BccStencils<Tr, T, std::int32_t>>;
    const Spline spline(rt::BccStencils<Tr, T, std::int32_t>(volume_), -1, &kernels_[s]);
    const double t0 = thread_ns<T>();
    spline.batch(points_, values_, {}, {});
    return (thread_ns<T>() - t0) / static_cast<double>(points_.size());
  }

  // Whether stages a and b give the same values, bit for bit.
  bool same_values(int a, int b) {
    run(a);
    const std::vector<T> first = values_;
    run(b);
    return first == values_;
  }

 private:
  static void set_chunk(simd::Kernels& k, decltype(simd::Kernels::chunk_float) f,
                        decltype(simd::Kernels::chunk_double) d) {
    k.chunk_float = f;
    k.chunk_double = d;
  }

  rt::LatticeVolume<T> volume_;
  std::span<const rt::Vec3> points_;
  std::vector<T> values_;
  simd::Kernels kernels_[5];
};

template <class T>
void run_all(int side, int rounds) {
  std::mt19937_64 rng(2);
  std::uniform_real_distribution<double> u(6.0, 2.0 * side - 7.0);
  std::vector<rt::Vec3> padded(200000 + simd::kChunk);
  for (auto& p : padded) p = {u(rng), u(rng), u(rng)};
  const std::span<const rt::Vec3> points(padded.data(), 200000);
  Stages<boxgen::generated::m7::Traits, T> m7(0, side, points);
  Stages<boxgen::generated::m8::Traits, T> m8(1, side, points);
  if (!m7.same_values(0, 3) || !m7.same_values(0, 4) || !m8.same_values(0, 3) ||
      !m8.same_values(0, 4)) {
    std::fprintf(stderr, "bench_kernel_stages: an experimental stage changed the values\n");
    std::exit(1);
  }
  std::vector<double> times[2][5];
  for (int r = 0; r < rounds; ++r)
    for (int s = 0; s < 5; ++s) {
      times[0][s].push_back(m7.run(s));
      times[1][s].push_back(m8.run(s));
    }
  const char* names[5] = {"full", "fetch", "locate", "prefetched", "pipelined"};
  double least[2][5];
  std::printf("%s, %d^3 x 2, %d rounds: ns per point, minimum (median)\n",
              sizeof(T) == 4 ? "float" : "double", side, rounds);
  for (int s = 0; s < 5; ++s) {
    double median[2];
    for (int f = 0; f < 2; ++f) {
      std::sort(times[f][s].begin(), times[f][s].end());
      least[f][s] = times[f][s].front();
      median[f] = times[f][s][times[f][s].size() / 2];
    }
    std::printf("  %-10s  M7 %6.2f (%6.2f)  M8 %6.2f (%6.2f)  M7/M8 %.3f (%.3f)\n", names[s],
                least[0][s], median[0], least[1][s], median[1], least[0][s] / least[1][s],
                median[0] / median[1]);
  }
  std::printf("  M7 fetch / M8 full %.3f, M7 locate / M8 full %.3f (minima)\n",
              least[0][1] / least[1][0], least[0][2] / least[1][0]);
}

}  // namespace

int main(int argc, char** argv) {
  bool in_double = false;
  int side = 32, rounds = 30;
  for (int a = 1; a < argc; ++a) {
    const std::string arg = argv[a];
    if (arg == "double") {
      in_double = true;
    } else if (arg.rfind("side=", 0) == 0) {
      side = std::atoi(argv[a] + 5);
    } else if (arg.rfind("prefetch=", 0) == 0) {
      // prefetch=lines: one per change of line (the `pipelined` stage; `prefetched` takes all).
      prefetch_every = arg == "prefetch=lines" ? 0 : std::max(1, std::atoi(argv[a] + 9));
    } else if (arg.rfind("rounds=", 0) == 0) {
      rounds = std::atoi(argv[a] + 7);
    } else {
      std::fprintf(stderr,
                   "usage: bench_kernel_stages [double] [side=N] [rounds=R] [prefetch=N]\n");
      return 2;
    }
  }
  if (side < 8 || rounds < 1) {
    std::fprintf(stderr, "bench_kernel_stages: side must be at least 8 and rounds at least 1\n");
    return 2;
  }
  rt::set_batch_threads(1);
  try {
    if (in_double)
      run_all<double>(side, rounds);
    else
      run_all<float>(side, rounds);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "bench_kernel_stages: %s\n", e.what());
    return 1;
  }
  return 0;
}
