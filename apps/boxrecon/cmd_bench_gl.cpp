// boxrecon bench --device gl: the GL device (runtime/gl) beside the CPU path in the same run, on
// the same data: evaluations per second of M7, M8 and M12 in float at random points (the tables in
// a storage buffer, the device's default, and as the emitted `const` arrays) and at points along
// rays of a BCC volume of random samples; the fetch floor of M7 on the GPU (the same number
// of samples per point, read and summed); milliseconds per 512 x 512 and 1024 x 1024 render of
// the Marschner-Lobb volume (N = 64, M7, Q^II, curvature shading). The GL renderer is named; on
// a software renderer (llvmpipe) every GL number measures the CPU's emulation of a GPU, and says
// so.
#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include <chrono>
#include <string>
#include <vector>

#include "apps/boxrecon/cmd_bench.h"
#include "apps/boxrecon/device_choice.h"
#include "runtime/gl/gl_render.h"
#include "runtime/gl/gl_spline.h"
#include "runtime/prefilter.h"
#include "runtime/reconstruction.h"
#include "runtime/render.h"
#include "runtime/sampling.h"
#include "runtime/test_functions.h"

namespace boxrecon {

namespace {

using namespace boxgen::runtime;

// Seconds of the same dispatch run before a GL timing on a GPU. NVIDIA's driver first runs a
// quickly compiled program and swaps in the optimized one when its compile, in the background,
// ends; and an idle GPU clocks down. With a cold shader cache the fastest of three runs right
// after the compile measured M8 5x slower than after this warm-up (docs/performance.md).
constexpr double kGpuWarmUpSeconds = 2.0;

// Runs `run` untimed before a GL timing: for kGpuWarmUpSeconds on a GPU, once on a software
// renderer (llvmpipe compiles before the first dispatch returns, and its clock is the CPU's).
template <class F>
void warm_up(F&& run) {
  const double seconds = gl::device().software ? 0.0 : kGpuWarmUpSeconds;
  const auto t0 = std::chrono::steady_clock::now();
  do run();
  while (std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count() < seconds);
}

// The fastest of `repeats` GL runs after the warm-up.
template <class F>
double warm_fastest_seconds(int repeats, F&& run) {
  warm_up(run);
  return fastest_seconds(repeats, run);
}

// Evaluations per second of one filter: GL and CPU (all threads), random and ray points.
nlohmann::json filter_rates(const std::string& name, const LatticeVolume<float>& volume,
                            const std::vector<Vec3>& points, const std::vector<Vec3>& rays,
                            int repeats, double* floor_rate) {
  const SplineFilter f = SplineFilter::parse(name);
  const auto rate = [&](double seconds) { return static_cast<double>(points.size()) / seconds; };
  gl::GlSpline<float> gpu(volume, f, gl::registry_glsl(name, false));
  nlohmann::json out;
  gpu.upload(points);
  out["gl_random"] = rate(warm_fastest_seconds(repeats, [&] { gpu.run(0); }));
  if (floor_rate)
    *floor_rate =
        rate(warm_fastest_seconds(repeats, [&] { gpu.run(gl::GlSpline<float>::kFetchFloor); }));
  gpu.upload(rays);
  out["gl_rays"] = rate(warm_fastest_seconds(repeats, [&] { gpu.run(0); }));
  {  // the same kernel with the emitted text's tables as they are (glsl_tables.h)
    gl::GlSpline<float> constant(volume, f, gl::registry_glsl(name, false),
                                 gl::TableStorage::constant);
    constant.upload(points);
    out["gl_random_const_tables"] = rate(warm_fastest_seconds(repeats, [&] { constant.run(0); }));
  }
  const Reconstructor<float> cpu(volume, f);
  std::vector<float> values(points.size());
  out["cpu_random"] = rate(fastest_seconds(repeats, [&] { cpu.evaluate(points, values); }));
  out["cpu_rays"] = rate(fastest_seconds(repeats, [&] { cpu.evaluate(rays, values); }));
  return out;
}

// Milliseconds per frame of the Marschner-Lobb render at each size: GL (the whole frame: rays,
// march, shading, read back), the GPU's dispatch and the CPU's part in the fastest frame, and the
// CPU renderer.
nlohmann::json render_times(const std::vector<int>& sizes, int repeats) {
  const SplineFilter m7 = SplineFilter::parse("m7");
  const LatticeGrid grid =
      cube_lattice_grid(m7.lattice(), 64, m7.required_margin(PrefilterChoice::Q2));
  const LatticeVolume<double> volume =
      prefilter(sample_lattice<double>(find_test_function("ml").value, grid),
                m7.prefilter(PrefilterChoice::Q2));
  const LatticeVolume<float> single = gl::float_volume(volume);
  const gl::GlSpline<float> gpu(single, m7, gl::registry_glsl("m7", false));
  const Box cube{{-1, -1, -1}, {1, 1, 1}};
  nlohmann::json out;
  for (int size : sizes) {
    RenderOptions o;
    o.width = o.height = size;
    o.shading = Shading::Curvature;
    warm_up([&] { (void)gl::render_isosurface(gpu, cube, o); });  // compiles the caster
    gl::FrameTimes split, fastest{1e300, 1e300};
    const double gl_s = fastest_seconds(repeats, [&] {
      (void)gl::render_isosurface(gpu, cube, o, &split);
      if (split.gpu + split.cpu < fastest.gpu + fastest.cpu) fastest = split;
    });
    const double cpu_s = fastest_seconds(1, [&] { (void)render_isosurface(volume, m7, cube, o); });
    out[std::to_string(size)] = {{"gl_ms", 1e3 * gl_s},
                                 {"gl_dispatch_ms", 1e3 * fastest.gpu},
                                 {"gl_cpu_part_ms", 1e3 * fastest.cpu},
                                 {"cpu_ms", 1e3 * cpu_s}};
  }
  return out;
}

}  // namespace

int run_gl_bench(const BenchOptions& o) {
  const gl::DeviceInfo& device = gl::device();
  const std::string note =
      device.software ? " [llvmpipe: the GL numbers measure the CPU's emulation of a GPU]" : "";
  // On a GPU: a 256^3 x 2 volume (128 MiB in float) and 2^23 points; on a software renderer or
  // with --quick, 64^3 x 2 and 2^16 points.
  const bool small = o.quick || device.software;
  const int n = small ? 64 : 256;
  const long count = o.points > 0 ? o.points : (small ? 1L << 16 : 1L << 23);
  const int repeats = std::max(1, o.repeats);
  const LatticeVolume<float> volume = random_volume<float>(n);
  const auto points = random_points(n, count);
  const auto rays = ray_points(n, count);
  nlohmann::json result;
  result["device"] = {{"renderer", device.renderer},
                      {"platform", device.platform},
                      {"version", device.version},
                      {"software", device.software}};
  if (device.software) result["note"] = note.substr(2, note.size() - 3);
  result["volume"] = fmt::format("{}^3 x 2 float, {} points", n, count);
  double floor_rate = 0;
  for (const char* name : {"m7", "m8", "m12"})
    result["evaluations_per_second"][name] =
        filter_rates(name, volume, points, rays, repeats, name[1] == '7' ? &floor_rate : nullptr);
  result["m7_gl_fetch_floor_per_second"] = floor_rate;
  result["m7_gl_over_floor"] =
      floor_rate / result["evaluations_per_second"]["m7"]["gl_random"].get<double>();
  result["render_ml64_m7_curvature"] =
      render_times(small ? std::vector<int>{128} : std::vector<int>{512, 1024}, repeats);
  if (o.json) {
    fmt::print("{}\n", result.dump());
    return 0;
  }
  fmt::print("{}\n", boxgen::app::gl_device_line());
  fmt::print("{}\n", result["volume"].get<std::string>());
  for (const auto& [name, r] : result["evaluations_per_second"].items())
    fmt::print(
        "{:<4} GL {:.3g}/s random ({:.3g}/s with const tables), {:.3g}/s rays; CPU {:.3g}/s "
        "random, {:.3g}/s rays{}\n",
        name, r["gl_random"].get<double>(), r["gl_random_const_tables"].get<double>(),
        r["gl_rays"].get<double>(), r["cpu_random"].get<double>(), r["cpu_rays"].get<double>(),
        note);
  fmt::print("m7   GL fetch floor {:.3g}/s: M7 takes {:.2f}x the floor's time{}\n", floor_rate,
             result["m7_gl_over_floor"].get<double>(), note);
  for (const auto& [size, r] : result["render_ml64_m7_curvature"].items())
    fmt::print(
        "render ML N=64 M7 curvature {0}x{0}: GL {1:.1f} ms (dispatch {2:.1f}, CPU part {3:.1f}), "
        "CPU {4:.1f} ms{5}\n",
        size, r["gl_ms"].get<double>(), r["gl_dispatch_ms"].get<double>(),
        r["gl_cpu_part_ms"].get<double>(), r["cpu_ms"].get<double>(), note);
  return 0;
}

}  // namespace boxrecon
