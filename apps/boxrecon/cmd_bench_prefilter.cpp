// boxrecon bench --prefilter P: the time and peak memory of one prefilter (interp above all) on a
// volume of N^3 random samples per coset on the filter's lattice (the target we keep: interp on
// 256^3 x 2 BCC samples in under 3 s on 2 cores, peak memory under 4x the volume in double).
#include "apps/boxrecon/cmd_bench_prefilter.h"

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include <chrono>
#include <cstdint>
#include <fstream>
#include <iostream>
#include <random>
#include <stdexcept>
#include <string>
#include <utility>

#include "runtime/batch_threads.h"
#include "runtime/coefficients.h"

namespace boxgen::app {

using namespace boxgen::runtime;

namespace {

// The process's peak resident memory so far (VmHWM of /proc/self/status), in bytes; 0 where it
// cannot be read.
std::uint64_t peak_resident_bytes() {
  std::ifstream status("/proc/self/status");
  std::string key;
  while (status >> key) {
    if (key == "VmHWM:") {
      std::uint64_t kib = 0;
      status >> kib;
      return kib * 1024;
    }
    status.ignore(1 << 20, '\n');
  }
  return 0;
}

}  // namespace

int run_prefilter_bench(const SplineFilter& f, const PrefilterSetting& setting, int n, int repeats,
                        bool json) {
  if (n < 2 || n > 1024)
    throw std::invalid_argument(fmt::format("--n must be between 2 and 1024, got {}", n));
  const CosetLattice& lattice = f.lattice();
  const std::uint64_t count =
      static_cast<std::uint64_t>(lattice.coset_count()) * static_cast<std::uint64_t>(n) * n * n;
  double best = 1e300;
  InterpolationReport report;
  Sizes out_sizes{};
  for (int r = 0; r < repeats; ++r) {
    LatticeVolume<double> volume(lattice, {n, n, n}, 1.0, {0, 0, 0});
    std::mt19937_64 rng(1);
    std::uniform_real_distribution<double> u(0.0, 1.0);
    for (double& s : volume.samples()) s = u(rng);
    const auto t0 = std::chrono::steady_clock::now();
    const LatticeVolume<double> c =
        spline_coefficients(std::move(volume), f, setting.choice, setting.boundary, &report);
    best = std::min(best,
                    std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count());
    out_sizes = c.sizes();
  }
  const double volume_bytes = static_cast<double>(count) * sizeof(double);
  const double peak = static_cast<double>(peak_resident_bytes());
  if (json) {
    nlohmann::json j{{"filter", f.name()},
                     {"lattice", lattice.name()},
                     {"prefilter", setting.choice.text()},
                     {"boundary", boundary_name(setting.boundary)},
                     {"samples", count},
                     {"n", n},
                     {"threads", batch_threads()},
                     {"repeats", repeats},
                     {"seconds", best},
                     {"peak_resident_bytes", peak},
                     {"peak_over_volume_in_double", peak / volume_bytes},
                     {"coefficient_sizes", {out_sizes[0], out_sizes[1], out_sizes[2]}}};
    if (!setting.choice.is_fir())
      j["interpolation"] = {
          {"lambda", report.lambda},
          {"padding", report.padding},
          {"transform", {report.transform[0], report.transform[1], report.transform[2]}}};
    std::cout << j.dump(2) << '\n';
    return 0;
  }
  std::cout << fmt::format(
      "prefilter {} of {} on {} x {}^3 random {} samples (boundary {}), {} thread{}, fastest of "
      "{}: {:.3f} s; peak resident memory {:.0f} MiB = {:.2f} x the volume in double ({:.0f} "
      "MiB)\n",
      setting.choice.text(), f.name(), lattice.coset_count(), n, lattice.name(),
      boundary_name(setting.boundary), batch_threads(), batch_threads() == 1 ? "" : "s", repeats,
      best, peak / (1 << 20), peak / volume_bytes, volume_bytes / (1 << 20));
  if (!setting.choice.is_fir())
    std::cout << fmt::format("  transform {} x {} x {} per coset (padding {}), lambda {:g}\n",
                             report.transform[0], report.transform[1], report.transform[2],
                             report.padding, report.lambda);
  return 0;
}

}  // namespace boxgen::app
