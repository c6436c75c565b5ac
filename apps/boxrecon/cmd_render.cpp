#include "apps/boxrecon/cmd_render.h"
#include "frontend/input_checks.h"

#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <iostream>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "analysis/png_image.h"
#include "apps/boxrecon/box_options.h"
#include "apps/boxrecon/device_choice.h"
#include "apps/boxrecon/lattice_commands.h"
#include "apps/boxrecon/prefilter_options.h"
#include "frontend/filter_choice.h"
#include "frontend/sample_grid.h"
#include "runtime/gl/gl_render.h"
#include "runtime/nifti_io.h"
#include "runtime/nrrd_checks.h"
#include "runtime/prefilter.h"
#include "runtime/render.h"
#include "runtime/sampling.h"
#include "runtime/test_functions.h"
#include "support/output_file.h"

namespace boxgen::recon {

namespace {

using namespace boxgen::runtime;

struct RenderArgs {
  app::PrefilterOptions prefilter{"q2"};
  std::string function, volume, lattice, filter = "m7", shading = "normal", output, device = "cpu",
                                         precision;
  int n = 0;
  std::optional<double> iso;  // default: 0.5 for --function, the data's for --volume
  bool cutaway = false, closeup = false, quiet = false;
  int width = 512, height = 512;
  double step = 0;
  std::optional<double> azimuth, elevation, distance;
  app::BoxOptions box;
};
RenderArgs args;

// A volume's iso (unless --iso) and the cut faces' value range: from its samples, before the
// prefilter. The chosen iso is printed, as the only line on stdout.
void choose_from_data(const LatticeVolume<double>& volume, RenderOptions& o) {
  const auto samples = volume.samples();
  const auto [lo, hi] = std::minmax_element(samples.begin(), samples.end());
  o.value_lo = *lo;
  o.value_hi = *hi > *lo ? *hi : *lo + 1;  // a constant volume: any non-empty range
  if (args.iso) return;
  const IsoChoice choice = percentile_iso(samples);
  o.iso = choice.iso;
  fmt::print(
      "iso = {:.6g} (midpoint of the 1st and 99th percentiles of the samples, {:.6g} and "
      "{:.6g})\n",
      choice.iso, choice.p1, choice.p99);
}

// An oblique volume's frame must turn its voxel axes rigidly (orthonormal columns, to NIfTI's
// float32 precision): the image of a sheared frame would be distorted.
void check_rotation(const Affine& frame) {
  for (int i = 0; i < 3; ++i)
    for (int j = i; j < 3; ++j) {
      double d = 0;
      for (int r = 0; r < 3; ++r) d += frame.linear[r][i] * frame.linear[r][j];
      if (std::fabs(d - (i == j ? 1.0 : 0.0)) > 1e-5)
        throw std::invalid_argument(
            fmt::format("'{}' has an affine that shears its voxel axes (axes {} and {} are not "
                        "perpendicular): render takes rotated grids only; resample it first",
                        nrrd_checks::printable(args.volume, 80), i, j));
    }
}

// The image of the chosen filter's spline, on a volume of its own lattice.
RgbBuffer render_volume(const SplineFilter& rf, const app::PrefilterSetting& q, RenderOptions o,
                        gl::FrameTimes* times) {
  const Box cube{{-1, -1, -1}, {1, 1, 1}};
  (void)boxgen::frontend::lattice_for(rf, args.lattice);
  NrrdReadLimits on_lattice;
  on_lattice.lattice = rf.lattice();
  const auto sampled = [&] {
    const LatticeGrid grid = cube_lattice_grid(rf.lattice(), args.n, rf.required_margin(q.choice));
    boxgen::frontend::check_memory(static_cast<std::uint64_t>(rf.lattice().coset_count()) *
                                       grid.sizes[0] * grid.sizes[1] * grid.sizes[2],
                                   sizeof(double), fmt::format("--n {}", args.n), "samples");
    return sample_lattice<double>(find_test_function(args.function).value, grid);
  };
  // An oblique volume is rendered in its own frame with the world's camera (CameraView::frame).
  on_lattice.allow_oblique = true;
  SourceSamples source;
  LatticeVolume<double> volume =
      args.volume.empty() ? sampled() : read_volume_file<double>(args.volume, on_lattice, &source);
  rf.check_lattice(volume.lattice());
  if (source.frame && app::given_box(args.box))
    throw std::invalid_argument(fmt::format(
        "'{}' is oblique: it is rendered over its region on its own axes (the camera is the "
        "world's), which a world box does not bound; leave out --box (--min/--max)",
        nrrd_checks::printable(args.volume, 80)));
  if (source.frame) {
    check_rotation(*source.frame);
    o.camera.frame = source.frame;
  }
  if (!args.volume.empty()) choose_from_data(volume, o);
  volume = app::coefficients_for(std::move(volume), rf, q);
  const Box region = default_box(volume, rf);
  const Box box = app::given_box(args.box) ? app::box_from_options(args.box, region, rf.name())
                  : args.volume.empty()    ? cube
                                           : region;
  if (boxgen::app::parse_device(args.device) == boxgen::app::Device::Gl)
    return gl::render_isosurface(volume, rf, box, o,
                                 gl::filter_glsl(rf, args.precision == "double"),
                                 args.precision == "double", times);
  return render_isosurface(volume, rf, box, o);
}

}  // namespace

CLI::App* add_render_command(CLI::App& app) {
  auto* r = app.add_subcommand(
      "render", "ray-cast an isosurface of the reconstruction into a PNG (Figs. 8-9)");
  auto* fn = r->add_option("--function", args.function,
                           "sample this test function (ml | cubic | sphere | gaussian)");
  r->add_option("--n", args.n,
                "N for --function: N^3 x K samples over [-1,1]^3 on the filter's lattice");
  auto* vol = r->add_option("--volume", args.volume,
                            "a volume on the filter's lattice (NRRD, or NIfTI .nii/.nii.gz: "
                            "Cartesian) instead of --function");
  fn->excludes(vol);
  r->add_option(
      "--lattice", args.lattice,
      "the lattice of a SPEC --filter and of --function's samples: only the filter's own "
      "(bcc | fcc | cartesian | rows of G), default the volume's with --volume, else the filter's");
  r->add_option("--filter", args.filter,
                "a filter of the registry (default m7): " + SplineFilter::names() +
                    ", or any SPEC of boxgen (on --lattice), compiled on first use");
  app::add_prefilter_options(r, args.prefilter, "default q2, as in Fig. 8");
  r->add_option("--iso", args.iso,
                "iso value (default: 0.5 for --function; for --volume the midpoint of the 1st "
                "and 99th percentiles of its samples, printed)");
  r->add_flag("--cutaway", args.cutaway,
              "remove 3/8 of the volume {z > 0 and (x > 0 or y > 0)} (Fig. 8)");
  r->add_flag("--closeup", args.closeup, "the close-up camera of Fig. 9 (a fixed camera)");
  r->add_option("--azimuth", args.azimuth,
                "camera: degrees about the z axis from +x towards +y (default 37.95, the direction "
                "(1, 0.78, 0.82))");
  r->add_option("--elevation", args.elevation,
                "camera: degrees above the xy plane, -90 < E < 90 (default 32.89)");
  r->add_option("--distance", args.distance,
                "camera: from the box's centre in box diagonals (default 1.6)");
  app::add_box_options(r, args.box,
                       "default: [-1,1]^3 for --function, the region the filter reconstructs for "
                       "--volume; the box must lie in that region");
  r->add_option("--shading", args.shading, "normal (default) | curvature");
  r->add_option("--width", args.width, "pixels (default 512)");
  r->add_option("--height", args.height, "pixels (default 512)");
  r->add_option("--step", args.step,
                "ray-marching step in world units (default: half the lattice spacing)");
  r->add_flag("--quiet", args.quiet, "no progress bar");
  boxgen::app::add_device_option(r, args.device, nullptr);
  r->add_option("--precision", args.precision,
                "with --device gl: float (default) | double; the CPU renders in double");
  r->add_option("-o,--output", args.output, "PNG to write")->required();
  return r;
}

bool render_quiet() { return args.quiet; }

int run_render() {
  const SplineFilter rf = args.volume.empty()
                              ? frontend::filter_from(args.filter, args.lattice)
                              : frontend::filter_for_volume(args.filter, args.lattice, args.volume);
  const app::PrefilterSetting q = app::parse_prefilter_options(args.prefilter);
  if (args.shading != "normal" && args.shading != "curvature")
    throw std::invalid_argument("--shading must be normal or curvature, got '" +
                                args.shading.substr(0, 40) + "'");
  if (args.function.empty() == args.volume.empty())
    throw std::invalid_argument("give --function NAME --n N or --volume FILE");
  if (!args.volume.empty() && args.n != 0)
    throw std::invalid_argument("--n has no effect with --volume (the volume fixes the samples)");
  if (!args.function.empty() && (args.n < 2 || args.n > 1024))
    throw std::invalid_argument(fmt::format("--n must be between 2 and 1024, got {}", args.n));
  if (args.width < 1 || args.height < 1 || args.width > 8192 || args.height > 8192)
    throw std::invalid_argument(
        fmt::format("--width and --height must be 1..8192, got {} x {}", args.width, args.height));
  const bool on_gl = boxgen::app::parse_device(args.device) == boxgen::app::Device::Gl;
  if (!args.precision.empty() && args.precision != "float" && args.precision != "double")
    throw std::invalid_argument("--precision must be float or double, got '" +
                                args.precision.substr(0, 40) + "'");
  if (!on_gl && args.precision == "float")
    throw std::invalid_argument(
        "the CPU renderer works in double: --precision float needs "
        "--device gl");
  if (!(args.step >= 0) || !std::isfinite(args.step))
    throw std::invalid_argument("--step must be >= 0");
  // An unwritable -o, or one that is the input volume, fails before the work.
  const std::filesystem::path input = args.volume;
  (void)support::check_output_file(args.output, {&input, args.volume.empty() ? std::size_t{0} : 1});
  RenderOptions o;
  o.width = args.width;
  o.height = args.height;
  o.iso = args.iso.value_or(0.5);
  o.cutaway = args.cutaway;
  o.camera = {args.azimuth, args.elevation, args.distance, args.closeup, std::nullopt};
  (void)camera_for(Box{{-1, -1, -1}, {1, 1, 1}}, o.camera);  // a bad camera fails before the work
  o.shading = args.shading == "curvature" ? Shading::Curvature : Shading::Normal;
  o.step = args.step;
  o.progress = !args.quiet;
  const auto start = std::chrono::steady_clock::now();
  gl::FrameTimes frame;
  const RgbBuffer image = render_volume(rf, q, o, &frame);
  analysis::RgbImage png(image.width, image.height);
  png.pixels = image.pixels;
  analysis::write_png(args.output, png);
  if (!args.quiet)
    std::cerr << fmt::format(
        "rendered {} x {} in {:.2f} s{}\n", image.width, image.height,
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(),
        on_gl ? fmt::format(" (the frame: GPU dispatch {:.3f} s, CPU part {:.3f} s) on the {}",
                            frame.gpu, frame.cpu, boxgen::app::gl_device_line())
              : "");
  return 0;
}

}  // namespace boxgen::recon
