// A program to count instructions per point under valgrind (shared machines make times noisy):
//   valgrind --tool=callgrind --toggle-collect='*Reconstructor<float>::evaluate*'
//            build/bench/bench_instructions m7 20000
//   valgrind --tool=callgrind --toggle-collect='*fetch_floor*' build/bench/bench_instructions m7
//   20000 floor
// evaluates `points` random points of a 32^3 x 2 float volume through
// Reconstructor<float>::evaluate (BOXGEN_THREADS=1 is set here), or runs the filter's fetch floor:
// per point the corner and its base index, then the filter's own stencil shape (cell 0's offsets)
// fetched and summed. Divide the collected count by `points`. With `double` the volume, the
// evaluation and the floor are in double (toggle '*Reconstructor<double>::evaluate*'). With `time`
// it also prints the thread CPU time per point (best of 10 runs):
// `build/bench/bench_instructions m7 200000 time`. `side=96` takes a 96^3 x 2 volume instead
// (larger than the caches: `--cache-sim=yes` counts the misses). BOXGEN_SIMD=0 measures the scalar
// batch path. (valgrind emulates no AVX-512: under it the SIMD path dispatches to AVX2.) Any other
// registry filter (fcc6, tricubic, cart7) runs through the same Reconstructor<T>::evaluate on a
// volume of its own lattice with about as many samples (2 x 32^3), no floor:
//   valgrind --tool=callgrind --toggle-collect='*Reconstructor<float>::evaluate*'
//            build/bench/bench_instructions tricubic 20000
// `sorted` evaluates the same points in storage order (by the integer parts of z, y, x), so that
// consecutive points share their stencils' cache lines: the same instructions with (nearly) no
// memory latency, the bound that prefetching could at best reach on a volume beyond the caches.
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <ctime>
#include <random>
#include <string>
#include <vector>

#include "generated/registry.hpp"
#include "runtime/batch_threads.h"
#include "runtime/lattice_volume.h"
#include "runtime/reconstruction.h"
#include "support/evaluator_support.hpp"

using namespace boxgen::runtime;

template <class Tr, class T>
__attribute__((noinline)) void fetch_floor(const LatticeVolume<T>& volume,
                                           const std::vector<Vec3>& points, std::vector<T>& out) {
  const std::int64_t n0 = volume.sizes()[0], n1 = volume.sizes()[1];
  std::int32_t offsets[Tr::kStencilSize];
  for (int k = 0; k < Tr::kStencilSize; ++k) {
    const auto& d = Tr::kOffsets[0][k];
    offsets[k] =
        static_cast<std::int32_t>(d[0] + n0 * d[1] + n0 * n1 * d[2] - (d[0] & 1) * (n0 + n0 * n1));
  }
  const T* samples = volume.samples().data();
  for (std::size_t i = 0; i < points.size(); ++i) {
    std::int64_t corner[3];
    for (int a = 0; a < 3; ++a)
      corner[a] = static_cast<std::int64_t>(
                      std::floor(static_cast<T>(points[i][a]) + static_cast<T>(Tr::kCentre[a]))) &
                  ~std::int64_t{1};  // an even corner keeps every offset on the lattice
    const T* base = samples + (corner[0] + n0 * corner[1] + n0 * n1 * corner[2]);
    T sum = 0;
    for (int k = 0; k < Tr::kStencilSize; ++k) sum += base[offsets[k]];
    out[i] = sum;
  }
}

// The memory each point's stencil touches (its cell's orbit's samples), summed over the points:
// distinct 64-byte cache lines, storage rows (samples of one j, k: the storage index is
// c + K (i + N0 (j + N1 k))) and 4 KiB pages.
struct Footprint {
  double lines = 0, rows = 0, pages = 0;
};

template <class Tr, class T>
Footprint stencil_footprint(const LatticeVolume<T>& volume, const std::vector<Vec3>& points) {
  namespace support = boxgen::generated::support;
  const auto row_size = static_cast<std::int64_t>(volume.coset_count()) * volume.sizes()[0];
  const auto distinct = [](std::vector<std::int64_t>& v) {
    std::sort(v.begin(), v.end());
    return static_cast<double>(std::unique(v.begin(), v.end()) - v.begin());
  };
  Footprint f;
  std::vector<std::int64_t> lines, rows, pages;
  for (const Vec3& p : points) {
    const Vec3 x = volume.to_lattice(p);
    const auto at =
        support::locate<Tr, T>({static_cast<T>(x[0]), static_cast<T>(x[1]), static_cast<T>(x[2])});
    lines.clear();
    rows.clear();
    pages.clear();
    const int size = Tr::kOrbitStencilSize[Tr::kCells[at.cell].orbit];
    for (int k = 0; k < size; ++k) {
      const auto& d = Tr::kOffsets[at.cell][k];
      const std::int64_t index =
          volume.storage_offset({at.corner[0] + d[0], at.corner[1] + d[1], at.corner[2] + d[2]});
      const auto address = reinterpret_cast<std::uintptr_t>(volume.samples().data() + index);
      lines.push_back(static_cast<std::int64_t>(address / 64));
      pages.push_back(static_cast<std::int64_t>(address / 4096));
      rows.push_back(index / row_size);
    }
    f.lines += distinct(lines);
    f.rows += distinct(rows);
    f.pages += distinct(pages);
  }
  return f;
}

// The fastest of `runs` calls of run() in CPU time of this thread (ns), which a loaded machine
// disturbs far less than wall-clock time (it still shares caches and the core's frequency).
template <class F>
double best_thread_ns(int runs, F&& run) {
  double best = 0;
  for (int r = 0; r < runs; ++r) {
    timespec t0{}, t1{};
    clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t0);
    run();
    clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t1);
    const double ns = 1e9 * static_cast<double>(t1.tv_sec - t0.tv_sec) +
                      static_cast<double>(t1.tv_nsec - t0.tv_nsec);
    best = r == 0 ? ns : std::min(best, ns);
  }
  return best;
}

// Any registry filter on a volume of its own lattice with about 2 x side^3 samples (M7, M8, M12:
// side^3 x 2 on BCC), or the fetch floor of a BCC filter; or, with `footprint`, no evaluation
// but the points' stencil footprint.
template <class T>
double filter_ns(const SplineFilter& f, std::vector<T>& values, long count, bool floor, int runs,
                 int side, bool sorted, Footprint* footprint = nullptr) {
  const CosetLattice lattice = f.lattice();
  const int n =
      static_cast<int>(std::lround(std::cbrt(2.0 * side * side * side / lattice.coset_count())));
  LatticeVolume<T> volume(lattice, {n, n, n}, 1.0, {0, 0, 0});
  std::mt19937_64 rng(1);
  for (auto& s : volume.samples()) s = static_cast<T>(rng() % 1000) / T(1000);
  const double extent = static_cast<double>(lattice.period()) * n;
  std::uniform_real_distribution<double> u(6.0, extent - 7.0);
  std::vector<Vec3> points(count > 0 ? count : 1);
  for (auto& p : points) p = {u(rng), u(rng), u(rng)};
  if (sorted)
    std::sort(points.begin(), points.end(), [](const Vec3& a, const Vec3& b) {
      const auto key = [](const Vec3& p) {
        return std::array<double, 3>{std::floor(p[2]), std::floor(p[1]), p[0]};
      };
      return key(a) < key(b);
    });
  values.resize(points.size());
  if (footprint) {
    boxgen::generated::with_filter(f.registry_index(), [&](auto entry) {
      *footprint = stencil_footprint<typename decltype(entry)::Traits>(volume, points);
    });
    return 0;
  }
  const Reconstructor<T> reconstructor(volume, f);
  return best_thread_ns(runs, [&] {
    if (floor)
      boxgen::generated::with_filter(f.registry_index(), [&](auto entry) {
        fetch_floor<typename decltype(entry)::Traits, T>(volume, points, values);
      });
    else
      reconstructor.evaluate(points, values);
  });
}

int main(int argc, char** argv) {
  if (argc < 3) {
    std::fprintf(stderr,
                 "usage: bench_instructions FILTER POINTS [floor] [time] [lines] [double] [sorted] "
                 "[side=N]\n");
    return 2;
  }
  const long count = std::atol(argv[2]);
  bool floor = false, timed = false, in_double = false, lines = false, sorted = false;
  int side = 32;
  for (int a = 3; a < argc; ++a) {
    if (std::string(argv[a]).rfind("side=", 0) == 0) side = std::atoi(argv[a] + 5);
    floor = floor || std::string(argv[a]) == "floor";
    timed = timed || std::string(argv[a]) == "time";
    lines = lines || std::string(argv[a]) == "lines";
    in_double = in_double || std::string(argv[a]) == "double";
    sorted = sorted || std::string(argv[a]) == "sorted";
  }
  set_batch_threads(1);
  const SplineFilter filter = SplineFilter::parse(argv[1]);
  if (floor && !(filter.lattice() == CosetLattice::bcc())) {
    std::fprintf(stderr, "bench_instructions: the floor is measured for m7, m8 and m12\n");
    return 2;
  }
  double best = 0, sum = 0;
  std::size_t size = 0;
  Footprint footprint;
  const auto measure = [&](auto zero) {
    std::vector<decltype(zero)> values;
    best = filter_ns(filter, values, count, floor, timed ? 10 : 1, side, sorted,
                     lines ? &footprint : nullptr);
    for (auto v : values) sum += static_cast<double>(v);
    size = values.size();
  };
  if (in_double)
    measure(0.0);
  else
    measure(0.0F);
  std::printf("%s%s%s%s: %ld points, side %d, checksum %.6g", argv[1], in_double ? " double" : "",
              floor ? " floor" : "", sorted ? " sorted" : "", count, side, sum);
  if (lines) {
    const auto per_point = [&](double total) { return total / static_cast<double>(size); };
    std::printf(", per point: %.2f cache lines, %.2f storage rows, %.2f pages",
                per_point(footprint.lines), per_point(footprint.rows), per_point(footprint.pages));
  }
  if (timed)
    std::printf(", %.2f ns per point (thread CPU time, best of 10)",
                best / static_cast<double>(size));
  std::printf("\n");
  return 0;
}
