// boxrecon bench: seconds for evaluating M7, M8 and M12 at random points of N^3 x 2 BCC volumes
// through Reconstructor<T>::evaluate on one thread (the paper's Table 2), beside
//   the fetch floor: the same number of samples per point, fetched through precomputed linear
//     offsets (the evaluator's own stencil shape) and summed, with the same per-point addressing;
//   coherent access: the points in order along rays, as a ray caster issues them;
//   tricubic: the registry's tricubic B-spline through the same Reconstructor<T>::evaluate (the
//     same engine and SIMD path) on a Cartesian volume with as many samples;
//   2 threads over 1 (BOXGEN_THREADS-style cap through set_batch_threads).
// Every ratio is measured in this run; the fastest of `repeats` runs counts.
#include "apps/boxrecon/cmd_bench.h"
#include "frontend/input_checks.h"

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <random>
#include <string>
#include <thread>
#include <vector>

#include "generated/registry.hpp"
#include "runtime/batch_threads.h"
#include "runtime/lattice_volume.h"
#include "runtime/reconstruction.h"
#include "runtime/simd_batch.h"

namespace boxrecon {

using boxgen::runtime::Vec3;

// A volume of random samples with unit spacing at the origin: lattice = world coordinates.
template <class T>
boxgen::runtime::LatticeVolume<T> random_volume(int n) {
  using namespace boxgen::runtime;
  LatticeVolume<T> volume(CosetLattice::bcc(), {n, n, n}, 1.0, {0, 0, 0});
  std::mt19937_64 rng(n);
  for (auto& s : volume.samples()) s = static_cast<T>(static_cast<double>(rng() % 4096) / 4096.0);
  return volume;
}

// Points whose stencils of every filter lie inside: [6, 2N - 7]^3 in lattice coordinates.
std::vector<boxgen::runtime::Vec3> random_points(int n, long count) {
  std::mt19937_64 rng(42);
  std::uniform_real_distribution<double> u(6.0, 2.0 * n - 7.0);
  std::vector<Vec3> out(count);
  for (auto& p : out) p = {u(rng), u(rng), u(rng)};
  return out;
}

// The same number of points along parallel rays through the inner box, step 0.5 lattice units.
std::vector<boxgen::runtime::Vec3> ray_points(int n, long count) {
  std::mt19937_64 rng(7);
  const double lo = 6.0, hi = 2.0 * n - 7.0;
  std::uniform_real_distribution<double> u(lo, hi);
  const Vec3 dir{0.48, 0.6, 0.64};  // unit length
  std::vector<Vec3> out;
  out.reserve(count);
  while (static_cast<long>(out.size()) < count) {
    Vec3 p{lo, u(rng), u(rng)};
    while (static_cast<long>(out.size()) < count && p[0] < hi && p[1] < hi && p[2] < hi) {
      out.push_back(p);
      for (int a = 0; a < 3; ++a) p[a] += 0.5 * dir[a];
    }
  }
  return out;
}

template boxgen::runtime::LatticeVolume<float> random_volume<float>(int);
template boxgen::runtime::LatticeVolume<double> random_volume<double>(int);

namespace {

using namespace boxgen::runtime;

constexpr const char* kFilters[] = {"m7", "m8", "m12"};

std::string cpu_model() {
  std::ifstream in("/proc/cpuinfo");
  std::string line;
  while (std::getline(in, line))
    if (line.rfind("model name", 0) == 0) return line.substr(line.find(':') + 2);
  return "unknown";
}

// The fetch floor of a filter: per point the corner floor(x + c) and its base index (as the
// runtime computes them), then kStencilSize samples at fixed precomputed offsets, summed.
template <class Tr, class T>
void fetch_floor(const LatticeVolume<T>& volume, const std::vector<Vec3>& points,
                 std::vector<T>& out) {
  const std::int64_t n0 = volume.sizes()[0], n1 = volume.sizes()[1];
  std::vector<std::int64_t> offsets(Tr::kStencilSize);
  for (int k = 0; k < Tr::kStencilSize; ++k) {
    const auto& d = Tr::kOffsets[0][k];
    offsets[k] = d[0] + n0 * d[1] + n0 * n1 * d[2] - (d[0] & 1) * (n0 + n0 * n1);
  }
  const T* samples = volume.samples().data();
  for (std::size_t i = 0; i < points.size(); ++i) {
    std::int64_t corner[3];
    for (int a = 0; a < 3; ++a)
      corner[a] = static_cast<std::int64_t>(
          std::floor(static_cast<T>(points[i][a]) + static_cast<T>(Tr::kCentre[a])));
    corner[0] &= ~std::int64_t{1};  // an even corner keeps every offset on the lattice
    corner[1] &= ~std::int64_t{1};
    corner[2] &= ~std::int64_t{1};
    const T* base = samples + (corner[0] + n0 * corner[1] + n0 * n1 * corner[2]);
    T sum = 0;
    for (int k = 0; k < Tr::kStencilSize; ++k) sum += base[offsets[k]];
    out[i] = sum;
  }
}

template <class T>
double floor_seconds(const char* f, const LatticeVolume<T>& volume, const std::vector<Vec3>& points,
                     int repeats) {
  std::vector<T> out(points.size());
  namespace g = boxgen::generated;
  return fastest_seconds(repeats, [&] {
    g::with_filter(SplineFilter::parse(f).registry_index(), [&](auto entry) {
      fetch_floor<typename decltype(entry)::Traits>(volume, points, out);
    });
  });
}

template <class T>
double filter_seconds(const char* f, const LatticeVolume<T>& volume,
                      const std::vector<Vec3>& points, int repeats) {
  std::vector<T> values(points.size());
  const Reconstructor<T> r(volume, SplineFilter::parse(f));
  return fastest_seconds(repeats, [&] { r.evaluate(points, values); });
}

// The tricubic B-spline on a Cartesian volume of m^3 samples (m^3 ~ 2 n^3), through the runtime's
// batch API (Reconstructor: the same engine, SIMD path and offset fetching as on BCC), at the BCC
// points scaled to its inner box.
template <class T>
double tricubic_seconds(int n, const std::vector<Vec3>& bcc_points, int repeats) {
  const SplineFilter tricubic = SplineFilter::parse("tricubic");
  const int m = static_cast<int>(std::lround(n * std::cbrt(2.0)));
  LatticeVolume<T> volume(tricubic.lattice(), {m, m, m}, 1.0, {0, 0, 0});
  std::mt19937_64 rng(m);
  for (auto& s : volume.samples()) s = static_cast<T>(static_cast<double>(rng() % 4096) / 4096.0);
  const double scale = (m - 6.0) / (2.0 * n - 13.0);
  std::vector<Vec3> points(bcc_points.size());
  for (std::size_t i = 0; i < points.size(); ++i)
    for (int a = 0; a < 3; ++a) points[i][a] = 3.0 + (bcc_points[i][a] - 6.0) * scale;
  std::vector<T> values(points.size());
  const Reconstructor<T> r(volume, tricubic);
  return fastest_seconds(repeats, [&] { r.evaluate(points, values); });
}

struct Row {
  int n;
  const char* precision;
  double t[3];
};

template <class T>
Row table2_row(int n, long count, int repeats) {
  const LatticeVolume<T> volume = random_volume<T>(n);
  const auto points = random_points(n, count);
  Row row{n, sizeof(T) == 4 ? "float" : "double", {}};
  for (int f = 0; f < 3; ++f) row.t[f] = filter_seconds(kFilters[f], volume, points, repeats);
  return row;
}

}  // namespace

int run_bench(const BenchOptions& o) {
  const long count = o.points > 0 ? o.points : (o.quick ? 200000 : 10000000);
  // Random and ray points (Vec3 each) and one value per point, in double at most.
  boxgen::frontend::check_memory(static_cast<std::uint64_t>(count),
                                 2 * sizeof(Vec3) + sizeof(double),
                                 fmt::format("--points {}", count), "points");
  const auto per_point = [count](double seconds) {
    return 1e9 * seconds / static_cast<double>(count);
  };
  const int repeats = std::max(1, o.repeats);
  set_batch_threads(1);
  nlohmann::json result;
  // The ratios, on one cache-resident volume (32^3 x 2 float: 256 KiB).
  const int n_cache = 32;
  {
    const LatticeVolume<float> volume = random_volume<float>(n_cache);
    const auto points = random_points(n_cache, count);
    const auto rays = ray_points(n_cache, count);
    double t[3], floor[3], coherent[3];
    for (int f = 0; f < 3; ++f) {
      t[f] = filter_seconds(kFilters[f], volume, points, repeats);
      floor[f] = floor_seconds(kFilters[f], volume, points, repeats);
      coherent[f] = filter_seconds(kFilters[f], volume, rays, repeats);
    }
    const double tricubic = tricubic_seconds<float>(n_cache, points, repeats);
    set_batch_threads(2);
    const double two = filter_seconds("m7", volume, points, repeats);
    set_batch_threads(1);
    result["volume"] = fmt::format("{}^3 x 2 float, {} random points, one thread", n_cache, count);
    result["ns_per_point"] = {{"m7", per_point(t[0])},
                              {"m8", per_point(t[1])},
                              {"m12", per_point(t[2])},
                              {"m7_floor", per_point(floor[0])},
                              {"m8_floor", per_point(floor[1])},
                              {"m12_floor", per_point(floor[2])},
                              {"m7_rays", per_point(coherent[0])},
                              {"m8_rays", per_point(coherent[1])},
                              {"m12_rays", per_point(coherent[2])},
                              {"tricubic", per_point(tricubic)},
                              {"m7_2_threads", per_point(two)}};
    result["t7_over_t8"] = t[0] / t[1];
    result["t12_over_t8"] = t[2] / t[1];
    result["m7_over_floor"] = t[0] / floor[0];
    result["m8_over_floor"] = t[1] / floor[1];
    result["m12_over_floor"] = t[2] / floor[2];
    result["m7_over_tricubic"] = t[0] / tricubic;
    result["speedup_2_threads"] = t[0] / two;
  }
  // The paper's Table 2: seconds for `count` points per volume N^3 x 2, and one volume larger than
  // the last-level cache (256^3 x 2: 128 MiB in float).
  if (!o.quick) {
    nlohmann::json table = nlohmann::json::array();
    for (int n : {21, 27, 32, 37, 45, 57, 77, 93, 117, 256}) {
      for (const Row& row :
           {table2_row<float>(n, count, repeats), table2_row<double>(n, count, repeats)}) {
        table.push_back({{"n", row.n},
                         {"precision", row.precision},
                         {"m7_s", row.t[0]},
                         {"m8_s", row.t[1]},
                         {"m12_s", row.t[2]},
                         {"t7_over_t8", row.t[0] / row.t[1]},
                         {"t12_over_t8", row.t[2] / row.t[1]}});
        if (!o.json)
          fmt::print(
              "N={:>3} {:<6}  M7 {:8.3f} s  M8 {:8.3f} s  M12 {:8.3f} s  t7/t8 {:.2f}  t12/t8 "
              "{:.2f}\n",
              row.n, row.precision, row.t[0], row.t[1], row.t[2], row.t[0] / row.t[1],
              row.t[2] / row.t[1]);
      }
    }
    result["table2"] = table;
    result["table2_points"] = count;
  }
  result["machine"] = {
      {"cpu", cpu_model()},
      {"cores", std::thread::hardware_concurrency()},
      // Highway's name of the instruction set the batch path dispatches to on this CPU ("AVX3"
      // is AVX-512), and whether evaluate() used it in this run (BOXGEN_SIMD=0 switches it off).
      {"simd_target", simd::target_name()},
      {"simd_batch", simd::enabled()}};
  if (o.json) {
    fmt::print("{}\n", result.dump());
  } else {
    for (const char* key : {"t7_over_t8", "t12_over_t8", "m7_over_floor", "m8_over_floor",
                            "m12_over_floor", "speedup_2_threads", "m7_over_tricubic"})
      fmt::print("{:<18} {:.3f}\n", key, result[key].get<double>());
    for (const auto& [key, value] : result["ns_per_point"].items())
      fmt::print("{:<18} {:.1f} ns/point\n", key, value.get<double>());
    fmt::print("machine: {}, {} cores, SIMD {} ({})\n", result["machine"]["cpu"].get<std::string>(),
               result["machine"]["cores"].get<unsigned>(),
               result["machine"]["simd_target"].get<std::string>(),
               simd::enabled() ? "batch path on" : "batch path off");
  }
  return 0;
}

}  // namespace boxrecon
