#include "apps/boxrecon/lattice_commands.h"

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <optional>
#include <random>
#include <stdexcept>
#include <utility>

#include "apps/boxrecon/cmd_bench.h"
#include "apps/boxrecon/device_choice.h"
#include "apps/boxrecon/output_volume.h"
#include "apps/boxrecon/progress.h"
#include "frontend/filter_choice.h"
#include "frontend/input_checks.h"
#include "frontend/sample_grid.h"
#include "runtime/batch_threads.h"
#include "runtime/gl/gl_spline.h"
#include "runtime/lattice_grid_choice.h"
#include "runtime/nifti_io.h"
#include "runtime/nrrd_checks.h"
#include "runtime/points_file.h"
#include "runtime/prefilter.h"
#include "runtime/resample.h"
#include "runtime/sample_encoding.h"
#include "runtime/sampling.h"
#include "runtime/test_functions.h"
#include "runtime/volume_output.h"
#include "support/output_file.h"

namespace boxgen::app {

using namespace boxgen::runtime;

template <class T>
LatticeVolume<T> read_for(const SplineFilter& f, const PrefilterSetting& setting,
                          const std::string& path, const NrrdReadLimits& limits,
                          SourceSamples* source) {
  NrrdReadLimits on_lattice = limits;
  on_lattice.lattice = f.lattice();
  LatticeVolume<T> volume = read_volume_file<T>(path, on_lattice, source);
  f.check_lattice(volume.lattice());
  return coefficients_for(std::move(volume), f, setting);
}

template LatticeVolume<float> read_for<float>(const SplineFilter&, const PrefilterSetting&,
                                              const std::string&, const NrrdReadLimits&,
                                              SourceSamples*);
template LatticeVolume<double> read_for<double>(const SplineFilter&, const PrefilterSetting&,
                                                const std::string&, const NrrdReadLimits&,
                                                SourceSamples*);

template <class T>
void print_evaluations(std::span<const T> values, std::span<const Vec3> gradients,
                       std::span<const Hessian> hessians, bool gradient, bool hessian) {
  std::string out;
  for (std::size_t i = 0; i < values.size(); ++i) {
    out += fmt::format("{:.17g}", static_cast<double>(values[i]));
    if (gradient)
      out += fmt::format(" {:.17g} {:.17g} {:.17g}", gradients[i][0], gradients[i][1],
                         gradients[i][2]);
    if (hessian)  // h_xx h_xy h_xz h_yy h_yz h_zz
      for (double h : hessians[i]) out += fmt::format(" {:.17g}", h);
    out += '\n';
  }
  std::fwrite(out.data(), 1, out.size(), stdout);
}

template <class T>
int run_eval(const std::string& filter, const std::string& lattice, const PrefilterOptions& pre,
             const std::string& volume_path, const std::string& points_path, bool gradient,
             bool hessian, const NrrdReadLimits& limits, Device device, bool verbose) {
  const PrefilterSetting q = parse_prefilter_options(pre);
  const SplineFilter f = frontend::filter_for_volume(filter, lattice, volume_path);
  // An oblique volume is evaluated in its own frame: world points map through the inverse of its
  // frame, derivatives back through that map's linear part (derivatives_to_world).
  NrrdReadLimits oblique = limits;
  oblique.allow_oblique = true;
  SourceSamples source;
  const LatticeVolume<T> volume = read_for<T>(f, q, volume_path, oblique, &source);
  const std::optional<Affine> to_volume = grid_to_volume(source.frame, std::nullopt);
  const std::vector<Vec3> world = read_points_file(points_path);
  std::vector<Vec3> in_frame;
  if (to_volume)
    for (const Vec3& p : world) in_frame.push_back(to_volume->apply(p));
  const std::span<const Vec3> points = to_volume ? in_frame : world;
  std::vector<T> values(points.size());
  std::vector<Vec3> gradients(gradient || hessian ? points.size() : 0);
  std::vector<Hessian> hessians(hessian ? points.size() : 0);
  const Reconstructor<T> spline(volume, f);
  if (device == Device::Gl) {
    if (verbose) std::cerr << gl_device_line() << '\n';
    const gl::GlSpline<T> gpu(volume, f, gl::filter_glsl(f, sizeof(T) == 8));
    gpu.evaluate(points, values, gradients, hessians);
  } else {
    spline.evaluate(points, values, gradients, hessians);
  }
  spline.require_finite(world, values, gradients, hessians);  // its message names world points
  if (to_volume) derivatives_to_world(*to_volume, gradients, hessians);
  print_evaluations<T>(values, gradients, hessians, gradient, hessian);
  return 0;
}

void print_error_report(const ErrorReport& r, double rms, double max, double gradient_rms) {
  if (r.json) {
    nlohmann::json j{{"function", r.function},
                     {"n", r.n},
                     {"filter", r.filter},
                     {"lattice", r.lattice},
                     {"prefilter", r.prefilter},
                     {"points", r.points},
                     {"seed", r.seed},
                     {"samples", r.samples},
                     {"sample_sizes", {r.sizes[0], r.sizes[1], r.sizes[2]}},
                     {"margin", r.margin},
                     {"rms", rms},
                     {"max", max}};
    if (r.gradient) j["gradient_rms"] = gradient_rms;
    if (r.interpolation)
      j["interpolation"] = {{"lambda", r.interpolation->lambda},
                            {"residual_max", r.interpolation->residual_max},
                            {"residual_rms", r.interpolation->residual_rms},
                            {"symbol_min", r.interpolation->symbol.min},
                            {"symbol_max", r.interpolation->symbol.max}};
    std::cout << j.dump(2) << '\n';
  } else {
    std::cout << fmt::format("rms {:.6e}  max {:.6e}", rms, max);
    if (r.gradient) std::cout << fmt::format("  gradient_rms {:.6e}", gradient_rms);
    std::cout << fmt::format(
        "  samples {} ({} x {} x {} x {}, margin {})", r.samples,
        r.samples / (static_cast<std::uint64_t>(r.sizes[0]) * r.sizes[1] * r.sizes[2]), r.sizes[0],
        r.sizes[1], r.sizes[2], r.margin);
    std::cout << '\n';
    if (r.interpolation)
      std::cout << fmt::format(
          "interp: lambda {:g}, residual at the samples max {:.3g}, rms {:.3g} (of max |sample|)\n",
          r.interpolation->lambda, r.interpolation->residual_max, r.interpolation->residual_rms);
  }
}

int run_error(const std::string& function, int n, const std::string& filter,
              const std::string& lattice_text, const PrefilterOptions& pre, int count,
              std::uint64_t seed, bool gradient, bool json) {
  const TestFunction& fn = find_test_function(function);
  const SplineFilter f = frontend::filter_from(filter, lattice_text);
  (void)frontend::lattice_for(f, lattice_text);
  const PrefilterSetting q = parse_prefilter_options(pre);
  if (count < 1 || count > 100000000)
    throw std::invalid_argument("--points must be between 1 and 100000000");
  ErrorReport report;
  report.function = function;
  report.filter = filter;
  report.prefilter = q.choice.text();
  report.n = n;
  report.points = count;
  report.seed = seed;
  report.gradient = gradient;
  report.json = json;
  report.lattice = f.lattice().name();
  if (n < 2 || n > 1024)
    throw std::invalid_argument(fmt::format("--n must be between 2 and 1024, got {}", n));
  const CosetLattice& lattice = f.lattice();
  report.margin = f.required_margin(q.choice);
  const LatticeGrid grid = cube_lattice_grid(lattice, n, report.margin);
  report.sizes = grid.sizes;
  report.samples = static_cast<std::uint64_t>(lattice.coset_count()) * grid.sizes[0] *
                   grid.sizes[1] * grid.sizes[2];
  frontend::check_memory(report.samples, sizeof(double), fmt::format("--n {}", n), "samples");
  InterpolationReport interpolation;
  const LatticeVolume<double> volume = spline_coefficients(
      sample_lattice<double>(fn.value, grid), f, q.choice, q.boundary, &interpolation, true);
  if (!q.choice.is_fir()) report.interpolation = interpolation;
  std::mt19937_64 rng(report.seed);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  std::vector<Vec3> points(count);
  for (auto& p : points) p = {u(rng), u(rng), u(rng)};
  std::vector<double> values(count);
  std::vector<Vec3> gradients(report.gradient ? count : 0);
  Reconstructor<double>(volume, f).evaluate(points, values, gradients);
  double sum2 = 0, worst = 0, gsum2 = 0;
  for (int i = 0; i < count; ++i) {
    const double e = values[i] - fn.value(points[i]);
    sum2 += e * e;
    worst = std::max(worst, std::abs(e));
    if (report.gradient) {
      const Vec3 g = fn.gradient(points[i]);
      for (int d = 0; d < 3; ++d) gsum2 += (gradients[i][d] - g[d]) * (gradients[i][d] - g[d]);
    }
  }
  print_error_report(report, std::sqrt(sum2 / count), worst, std::sqrt(gsum2 / count));
  return 0;
}

namespace {

// --spacing H (or HX HY HZ) over the box: as many points as fit from box.min on, spacing h.
CartesianGrid grid_with_spacing(const Box& box, const std::vector<double>& given) {
  const Vec3 h =
      given.size() == 1 ? Vec3{given[0], given[0], given[0]} : Vec3{given[0], given[1], given[2]};
  Sizes n{};
  for (int a = 0; a < 3; ++a) {
    if (!(std::isfinite(h[a]) && h[a] > 0))
      throw std::invalid_argument(fmt::format("--spacing must be finite and > 0, got {}", h[a]));
    // A relative 1e-9 keeps an extent that is a whole number of steps, up to rounding, whole.
    const double steps = std::floor((box.max[a] - box.min[a]) / h[a] * (1 + 1e-9));
    if (!(steps >= 1))
      throw std::invalid_argument(
          fmt::format("--spacing {} is wider than the box on axis {} ({} to {}): no two points fit",
                      h[a], "xyz"[a], box.min[a], box.max[a]));
    if (steps >= kMaxGridSize)
      throw std::invalid_argument(
          fmt::format("--spacing {} gives {} points on axis {}, more than {}", h[a], steps + 1,
                      "xyz"[a], kMaxGridSize));
    n[a] = static_cast<int>(steps) + 1;
  }
  return {n, h, box.min};
}

// resample() of the whole grid, with its progress (progress.h). While progress may show, the grid
// is done in slabs of z planes (GridBlock: each value bit for bit the one the whole grid gets).
template <class T>
CartesianVolume<T> resample_grid(const LatticeVolume<T>& volume, const SplineFilter& f,
                                 const CartesianGrid& grid, const BatchEvaluate<T>& evaluate) {
  Progress progress("resampling");
  if (!progress.enabled())
    return resample(volume, f, grid, GridBlock{{0, 0, 0}, grid.sizes}, evaluate);
  const Sizes& n = grid.sizes;
  const std::size_t plane = static_cast<std::size_t>(n[0]) * static_cast<std::size_t>(n[1]);
  CartesianVolume<T> out{n, grid.spacing, grid.origin,
                         std::vector<T>(plane * static_cast<std::size_t>(n[2]))};
  const int slabs = std::min(n[2], 100);
  for (int s = 0; s < slabs; ++s) {
    const int z0 = n[2] * s / slabs, z1 = n[2] * (s + 1) / slabs;
    const CartesianVolume<T> part =
        resample(volume, f, grid, GridBlock{{0, 0, z0}, {n[0], n[1], z1}}, evaluate);
    std::copy(
        part.values.begin(), part.values.end(),
        out.values.begin() + static_cast<std::ptrdiff_t>(plane * static_cast<std::size_t>(z0)));
    progress.update(static_cast<double>(z1) / n[2]);
  }
  return out;
}

// The image of --like: its lattice (Cartesian for an image such as resample's output), grid and,
// when it is oblique, its frame. Its samples are read only for the geometry (non-finite ones do
// not matter).
struct LikeImage {
  CosetLattice lattice = CosetLattice::cartesian();
  Sizes sizes{};
  Vec3 spacing{}, origin{};
  std::optional<Affine> frame;
  std::string anatomical;  // SourceSamples::anatomical
  NiftiCodes nifti_codes;  // SourceSamples::nifti_codes
};

LikeImage read_like(const std::string& path) {
  NrrdReadLimits limits;
  limits.allow_non_finite = true;
  limits.allow_oblique = true;
  SourceSamples source;
  const LatticeVolume<float> image = read_volume_file<float>(path, limits, &source);
  return {image.lattice(), image.sizes(),     image.axis_spacing(), image.origin(),
          source.frame,    source.anatomical, source.nifti_codes};
}

bool is_cartesian(const CosetLattice& lattice) { return lattice == CosetLattice::cartesian(); }

// The output lattice: --lattice, else the --like image's, else Cartesian. A --lattice that
// differs from the --like image's is refused (one line).
CosetLattice output_lattice(const std::string& text, const std::optional<LikeImage>& like,
                            const std::string& like_path) {
  if (text.empty()) return like ? like->lattice : CosetLattice::cartesian();
  CosetLattice lattice = CosetLattice::parse(text);
  if (like && !(like->lattice == lattice))
    throw std::invalid_argument(
        fmt::format("--lattice {} differs from the lattice of --like '{}' ({}): give one of them",
                    lattice.name(), nrrd_checks::printable(like_path, 80), like->lattice.name()));
  return lattice;
}

// The grid of a non-Cartesian output: the --like volume's own, or the lattice at --spacing H
// (its h) or at about --n^3 samples (default 64^3) over the box, centred in it (as subsample's).
LatticeGrid output_lattice_grid(const CosetLattice& lattice, const OutputGridOptions& options,
                                const std::optional<LikeImage>& like, const Box& box) {
  if (like) return {lattice, like->sizes, like->spacing[0], like->origin};
  if (!options.size.empty())
    throw std::invalid_argument(
        fmt::format("--size counts Cartesian grid points: onto the {} lattice give --spacing H "
                    "(its h) or --n N "
                    "(about N^3 samples)",
                    lattice.name()));
  if (options.spacing.size() > 1)
    throw std::invalid_argument(fmt::format(
        "the {} lattice has one spacing h: give --spacing H, not three values", lattice.name()));
  std::optional<double> h;
  if (!options.spacing.empty()) {
    h = options.spacing[0];
    if (!(std::isfinite(*h) && *h > 0))
      throw std::invalid_argument(fmt::format("--spacing must be finite and > 0, got {}", *h));
  }
  return lattice_grid_for(lattice, box, h, options.n);
}

// A whole grid of a non-Cartesian lattice onto which the volume is resampled, with progress.
template <class T>
LatticeVolume<T> resample_lattice_grid(const LatticeVolume<T>& volume, const SplineFilter& f,
                                       const LatticeGrid& grid, const BatchEvaluate<T>& evaluate) {
  Progress progress("resampling");
  return resample_to_lattice(volume, f, grid, evaluate,
                             [&progress](double done) { progress.update(done); });
}

// The values in T of a Cartesian grid or of a lattice grid, and their copy in the file's type
// while it is written (`stored` bytes each), must fit in memory.
void check_output_memory(std::uint64_t count, std::size_t bytes, const std::string& grid) {
  frontend::check_memory(count, bytes, fmt::format("the output grid of {}", grid), "values");
}

}  // namespace

template <class T>
int run_resample(const std::string& filter, const std::string& lattice_text,
                 const PrefilterOptions& pre, const std::string& volume_path,
                 const std::string& output, const std::string& type_text,
                 const OutputGridOptions& options, const NrrdReadLimits& limits, Device device,
                 bool verbose) {
  const PrefilterSetting q = parse_prefilter_options(pre);
  const std::optional<SampleType> type = parse_type_option(type_text);
  if (options.n < 2 || options.n > kMaxGridSize)
    throw std::invalid_argument(
        fmt::format("--n must be between 2 and {}, got {}", kMaxGridSize, options.n));
  for (const int s : options.size)
    if (s < 2 || s > kMaxGridSize)
      throw std::invalid_argument(
          fmt::format("--size must be between 2 and {} on each axis, got {}", kMaxGridSize, s));
  if (!options.spacing.empty() && options.spacing.size() != 1 && options.spacing.size() != 3)
    throw std::invalid_argument(
        fmt::format("--spacing takes one value or three, got {}", options.spacing.size()));
  const std::filesystem::path input = volume_path;
  // --like's geometry and the output lattice first: a refused output costs no work.
  std::optional<LikeImage> like;
  if (!options.like.empty()) like = read_like(options.like);
  const CosetLattice lattice = output_lattice(lattice_text, like, options.like);
  const bool cartesian = is_cartesian(lattice);
  // Before the work (a SPEC's first compile included), not after it; never the input.
  require_output_volume(output, {&input, 1}, lattice);
  const VolumeFormat format = output_format(output);
  // The filter is on the volume's lattice (a SPEC's too: --lattice is the output's).
  const SplineFilter f = frontend::filter_for_volume(filter, "", volume_path);
  // Oblique volumes are read in their own frame (index space times the voxel sizes); the
  // output's world points map into it through the inverse of the volume's affine.
  NrrdReadLimits read_limits = limits;
  read_limits.allow_oblique = true;
  SourceSamples source;
  const LatticeVolume<T> volume = read_for<T>(f, q, volume_path, read_limits, &source);
  // The output is in the volume's world; a --like image in another anatomical frame (LPS
  // against RAS) would put its grid elsewhere, so it is refused rather than mirrored.
  if (like && !like->anatomical.empty() && !source.anatomical.empty() &&
      like->anatomical != source.anatomical)
    throw std::invalid_argument(fmt::format(
        "--like '{}' is in {} world coordinates, the volume '{}' in {}: give an image in the "
        "volume's frame",
        nrrd_checks::printable(options.like, 80), like->anatomical,
        nrrd_checks::printable(volume_path, 80), source.anatomical));
  const std::string& anatomical =
      source.anatomical.empty() && like ? like->anatomical : source.anatomical;
  // A NIfTI output claims the NIfTI codes of the image whose grid it takes (--like's, as
  // nibabel's and nilearn's resampling keep the target's header), else the volume's.
  const NiftiCodes& codes =
      like && like->nifti_codes.any() ? like->nifti_codes : source.nifti_codes;
  // A lattice grid lies on the volume's own axes (an oblique volume's output keeps its affine):
  // a world box, or a --like lattice volume with an affine of its own, would need another frame.
  if (!cartesian && source.frame && given_box(options.box))
    throw std::invalid_argument(fmt::format(
        "'{}' is oblique: onto the {} lattice it is resampled on its own axes (the output keeps "
        "its affine), which a world box does not bound; leave out --box (--min/--max)",
        nrrd_checks::printable(volume_path, 80), lattice.name()));
  if (!cartesian && like && like->frame)
    throw std::invalid_argument(fmt::format(
        "--like '{}' is an oblique {} volume: resample onto its lattice with subsample, or onto "
        "a Cartesian --like image",
        nrrd_checks::printable(options.like, 80), lattice.name()));
  // The values in T, and their copy in the file's type while it is written.
  const SampleType stored =
      type ? *type
           : (format == VolumeFormat::Nifti
                  ? SampleType::Float32
                  : (sizeof(T) == 8 ? SampleType::Float64 : SampleType::Float32));
  const std::size_t bytes = sizeof(T) + sample_type_size(stored);
  std::optional<gl::GlSpline<T>> gpu;
  const auto evaluator = [&]() {
    if (device == Device::Cpu) return BatchEvaluate<T>{};
    if (verbose) std::cerr << gl_device_line() << '\n';
    gpu.emplace(volume, f, gl::filter_glsl(f, sizeof(T) == 8));
    return BatchEvaluate<T>(
        [&gpu](std::span<const Vec3> points, std::span<T> out) { gpu->evaluate(points, out); });
  };
  if (!cartesian) {
    const std::optional<Box> given = given_box(options.box);
    const Box box = given ? *given : default_box(volume, f);
    const LatticeGrid grid = output_lattice_grid(lattice, options, like, box);
    const Sizes& n = grid.sizes;
    check_output_memory(static_cast<std::uint64_t>(lattice.coset_count()) *
                            static_cast<std::uint64_t>(n[0]) * static_cast<std::uint64_t>(n[1]) *
                            static_cast<std::uint64_t>(n[2]),
                        bytes,
                        fmt::format("{} x {} x {} x {} {} samples", lattice.coset_count(), n[0],
                                    n[1], n[2], lattice.name()));
    write_output_volume(output, resample_lattice_grid(volume, f, grid, evaluator()), type,
                        anatomical, source.frame, codes);
    return 0;
  }
  CartesianGrid grid;
  std::optional<Affine> output_frame = source.frame;  // the output's map to world
  if (like) {
    output_frame = like->frame;
    grid = {like->sizes, like->spacing, like->origin};
    grid.to_volume = grid_to_volume(source.frame, output_frame);
  } else {
    // --box (--min/--max) is in world coordinates: for an oblique volume the output is then
    // axis-aligned in the world; without them the grid lies on the volume's own axes (its affine
    // kept).
    const std::optional<Box> given = given_box(options.box);
    const bool world_box = source.frame && given;
    const Box box = given ? *given : default_box(volume, f);
    if (!options.spacing.empty())
      grid = grid_with_spacing(box, options.spacing);
    else if (!options.size.empty())
      grid = grid_over(box, {options.size[0], options.size[1], options.size[2]});
    else
      grid = grid_over(box, {options.n, options.n, options.n});
    if (world_box) {
      output_frame = std::nullopt;
      grid.to_volume = source.frame->inverse();
    }
  }
  const Sizes& n = grid.sizes;
  check_output_memory(static_cast<std::uint64_t>(n[0]) * static_cast<std::uint64_t>(n[1]) *
                          static_cast<std::uint64_t>(n[2]),
                      bytes, fmt::format("{} x {} x {} points", n[0], n[1], n[2]));
  CartesianVolume<T> values = resample_grid(volume, f, grid, evaluator());
  values.frame = output_frame;
  write_output_grid(output, values, type, anatomical, codes);
  return 0;
}

int run_filter_bench(const SplineFilter& f, long point_count, int repeats, bool json) {
  const long count = point_count > 0 ? point_count : 1000000;
  const CosetLattice& lattice = f.lattice();
  constexpr int kSize = 48;  // samples per coset and axis: a few MB, as a small data set
  LatticeVolume<double> volume(lattice, {kSize, kSize, kSize}, 1.0, {0, 0, 0});
  std::mt19937_64 rng(1);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (double& s : volume.samples()) s = u(rng);
  const Box box = default_box(volume, f);
  std::vector<Vec3> points(static_cast<std::size_t>(count));
  for (auto& p : points)
    for (int a = 0; a < 3; ++a)
      p[a] = box.min[a] + (box.max[a] - box.min[a]) * (0.5 + 0.5 * u(rng));
  std::vector<double> values(points.size());
  std::vector<Vec3> gradients(points.size());
  const Reconstructor<double> spline(volume, f);
  const int all = batch_threads();
  struct Timing {
    int threads;
    double value, gradient;  // seconds per point
  };
  std::vector<Timing> timings;
  for (int threads : {1, all}) {
    if (!timings.empty() && threads == timings.front().threads) break;
    set_batch_threads(threads);
    const double v = boxrecon::fastest_seconds(repeats, [&] { spline.evaluate(points, values); });
    const double g =
        boxrecon::fastest_seconds(repeats, [&] { spline.evaluate(points, values, gradients); });
    timings.push_back({threads, v / static_cast<double>(count), g / static_cast<double>(count)});
  }
  set_batch_threads(all);
  if (json) {
    nlohmann::json j{{"filter", f.name()},
                     {"lattice", lattice.name()},
                     {"points", count},
                     {"repeats", repeats},
                     {"volume", fmt::format("{} x {}^3", lattice.coset_count(), kSize)},
                     {"timings", nlohmann::json::array()}};
    for (const auto& t : timings)
      j["timings"].push_back({{"threads", t.threads},
                              {"value_ns_per_point", t.value * 1e9},
                              {"gradient_ns_per_point", t.gradient * 1e9}});
    std::cout << j.dump(2) << '\n';
    return 0;
  }
  std::cout << fmt::format(
      "{} on the {} lattice ({} x {}^3 random samples), {} random points, fastest of {}:\n",
      f.name(), lattice.name(), lattice.coset_count(), kSize, count, repeats);
  for (const auto& t : timings)
    std::cout << fmt::format(
        "  {} thread{}: value {:.1f} ns/point, value + gradient {:.1f} ns/point\n", t.threads,
        t.threads == 1 ? "" : "s", t.value * 1e9, t.gradient * 1e9);
  return 0;
}

template void print_evaluations<float>(std::span<const float>, std::span<const Vec3>,
                                       std::span<const Hessian>, bool, bool);
template void print_evaluations<double>(std::span<const double>, std::span<const Vec3>,
                                        std::span<const Hessian>, bool, bool);
template int run_eval<float>(const std::string&, const std::string&, const PrefilterOptions&,
                             const std::string&, const std::string&, bool, bool,
                             const NrrdReadLimits&, Device, bool);
template int run_eval<double>(const std::string&, const std::string&, const PrefilterOptions&,
                              const std::string&, const std::string&, bool, bool,
                              const NrrdReadLimits&, Device, bool);
template int run_resample<float>(const std::string&, const std::string&, const PrefilterOptions&,
                                 const std::string&, const std::string&, const std::string&,
                                 const OutputGridOptions&, const NrrdReadLimits&, Device, bool);
template int run_resample<double>(const std::string&, const std::string&, const PrefilterOptions&,
                                  const std::string&, const std::string&, const std::string&,
                                  const OutputGridOptions&, const NrrdReadLimits&, Device, bool);

}  // namespace boxgen::app
