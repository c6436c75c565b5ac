#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cctype>
#include <cmath>
#include <cstdint>
#include <iostream>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "analysis/png_image.h"
#include "apps/boxrecon/cmd_volumes.h"
#include "apps/boxrecon/lattice_commands.h"
#include "frontend/filter_choice.h"
#include "runtime/nifti_io.h"
#include "runtime/nrrd_checks.h"
#include "runtime/resample.h"
#include "support/output_file.h"

namespace boxgen::recon {

namespace {

using namespace boxgen::runtime;

struct SliceArgs {
  app::PrefilterOptions prefilter;
  std::string volume, lattice, reference, axis = "z", colormap = "grey", difference_to, output;
  std::vector<std::string> filters;
  std::optional<double> at;
  std::vector<int> size;
  std::vector<double> range;
};
SliceArgs args;

constexpr int kGap = 4;  // white pixels between side-by-side panels
// Pixels where a panel has no value (outside the filter's region): a colour no map produces.
constexpr std::uint8_t kOutside[3] = {96, 0, 96};

// The nearest voxel of a Cartesian volume to a world point, or nothing outside its grid.
std::optional<float> nearest_voxel(const LatticeVolume<float>& v, const Vec3& p) {
  const Vec3 l = v.to_lattice(p);
  int index[3];
  for (int a = 0; a < 3; ++a) {
    const double r = std::round(l[a]);
    if (!(r >= 0 && r <= v.sizes()[a] - 1)) return std::nullopt;
    index[a] = static_cast<int>(r);
  }
  return v(0, index[0], index[1], index[2]);
}

// Every argument check that needs no file, before any work.
void check_slice_args() {
  const bool reconstruct = !args.volume.empty();
  if (reconstruct == !args.reference.empty())
    throw std::invalid_argument("give --volume FILE --filter F or --reference FILE");
  if (reconstruct && args.filters.empty()) throw std::invalid_argument("--volume needs --filter");
  for (const std::string& f : args.filters)  // the comma list of earlier versions: "m7,m8"
    if (!f.empty() && f.find(',') != std::string::npos && f.find(';') == std::string::npos &&
        std::isalpha(static_cast<unsigned char>(f.front())) != 0)
      throw std::invalid_argument(fmt::format(
          "--filter '{}' is not one filter: repeat --filter for panels side by side (--filter m7 "
          "--filter m8)",
          nrrd_checks::printable(f, 40)));
  if (!reconstruct && (!args.filters.empty() || !args.lattice.empty() ||
                       args.prefilter.prefilter != "none" || !args.difference_to.empty()))
    throw std::invalid_argument(
        "--filter, --lattice, --prefilter and --difference-to have no effect with --reference");
  if (args.axis != "x" && args.axis != "y" && args.axis != "z")
    throw std::invalid_argument("--axis must be x, y or z, got '" + args.axis.substr(0, 20) + "'");
  if (args.colormap != "grey" && args.colormap != "viridis")
    throw std::invalid_argument("--colormap must be grey or viridis, got '" +
                                args.colormap.substr(0, 20) + "'");
  if (!args.difference_to.empty() && args.colormap != "grey")
    throw std::invalid_argument("--colormap has no effect with --difference-to (blue-white-red)");
  if (!std::isfinite(*args.at)) throw std::invalid_argument("--at must be finite");
  if (!args.size.empty() &&
      (args.size[0] < 1 || args.size[1] < 1 || args.size[0] > 8192 || args.size[1] > 8192))
    throw std::invalid_argument("--size must be 1..8192 pixels each way");
  if (!args.range.empty() && !(std::isfinite(args.range[0]) && std::isfinite(args.range[1]) &&
                               args.range[0] < args.range[1]))
    throw std::invalid_argument("--range needs finite LO < HI");
}

// Pixels per panel: --size, the reference's voxels, or 512 on the box's longer side.
std::array<int, 2> panel_size(const Box& box, int u, int v,
                              const std::optional<LatticeVolume<float>>& reference) {
  if (!args.size.empty()) return {args.size[0], args.size[1]};
  if (reference) return {reference->sizes()[u], reference->sizes()[v]};
  const double wu = box.max[u] - box.min[u], wv = box.max[v] - box.min[v];
  return {std::max(1, static_cast<int>(std::lround(wu >= wv ? 512 : 512 * wu / wv))),
          std::max(1, static_cast<int>(std::lround(wv >= wu ? 512 : 512 * wv / wu)))};
}

// A value's colour: blue - white - red for a difference, else viridis or grey, over [lo, hi].
std::array<std::uint8_t, 3> colour_of(double value, double lo, double hi, bool difference) {
  const double t = std::clamp((value - lo) / (hi - lo), 0.0, 1.0);
  std::uint8_t r = 0, g = 0, b = 0;
  if (difference) {
    const double s = 2 * t - 1;
    const auto fade = [](double w) { return static_cast<std::uint8_t>(std::lround(255 * w)); };
    r = s < 0 ? fade(1 + s) : 255;
    g = fade(1 - std::fabs(s));
    b = s > 0 ? fade(1 - s) : 255;
  } else if (args.colormap == "viridis") {
    analysis::colour_map(t, r, g, b);
  } else {
    r = g = b = static_cast<std::uint8_t>(std::lround(255 * t));
  }
  return {r, g, b};
}

// The values of one reconstructed panel at `points` (NaN outside the filter's region or where
// the reference has no voxel), minus the reference's with --difference-to.
std::vector<double> reconstructed_panel(const LatticeVolume<float>& volume,
                                        const SplineFilter& filter, const std::vector<Vec3>& points,
                                        const std::vector<double>& ref_values, bool has_reference) {
  std::vector<double> values(points.size(), NAN);
  const Reconstructor<float> spline(volume, filter);
  const Box region = evaluable_region(volume, filter);
  std::vector<Vec3> inside;
  std::vector<std::size_t> where;
  for (std::size_t i = 0; i < points.size(); ++i) {
    bool in = !has_reference || !std::isnan(ref_values[i]);
    for (int a = 0; a < 3; ++a)
      in = in && points[i][a] >= region.min[a] && points[i][a] < region.max[a];
    if (in) {
      inside.push_back(points[i]);
      where.push_back(i);
    }
  }
  std::vector<float> out(inside.size());
  spline.evaluate(inside, out);
  spline.require_finite(inside, out);
  for (std::size_t k = 0; k < inside.size(); ++k)
    values[where[k]] =
        static_cast<double>(out[k]) - (args.difference_to.empty() ? 0.0 : ref_values[where[k]]);
  return values;
}

}  // namespace

CLI::App* add_slice_command(CLI::App& app) {
  auto* s = app.add_subcommand(
      "slice",
      "a PNG of an axis-aligned slice of a reconstruction, a reference or their difference");
  s->add_option("--volume", args.volume, "a lattice volume to reconstruct (NRRD or NIfTI)");
  s->add_option("--filter", args.filters,
                "F: a registry filter or a SPEC (on --lattice, default the volume's); repeat for "
                "panels side by side (--filter m12 --filter m7)")
      ->expected(1)
      ->multi_option_policy(CLI::MultiOptionPolicy::TakeAll);
  s->add_option("--lattice", args.lattice,
                "the lattice of a SPEC --filter (default: the volume's)");
  app::add_prefilter_options(s, args.prefilter);
  s->add_option("--reference", args.reference,
                "a Cartesian volume: its slice (nearest voxel) instead of --volume");
  s->add_option("--axis", args.axis, "x | y | z: the slice's normal (default z)");
  s->add_option("--at", args.at, "W: the slice's world coordinate on --axis")->required();
  s->add_option("--size", args.size,
                "W H: pixels per panel (default: the reference's voxels with --difference-to or "
                "--reference, else 512 on the longer side)")
      ->expected(2);
  s->add_option("--range", args.range,
                "LO HI: the values mapped to the colour map's ends (default: the data's range; "
                "a difference: +-its largest magnitude)")
      ->expected(2);
  s->add_option("--colormap", args.colormap, "grey (default) | viridis");
  s->add_option("--difference-to", args.difference_to,
                "a Cartesian volume: show reconstruction minus it (blue - white - red)");
  s->add_option("-o,--output", args.output, "PNG to write")->required();
  return s;
}

int run_slice() {
  check_slice_args();
  const bool reconstruct = !args.volume.empty();
  const std::vector<std::string>& names = args.filters;
  const app::PrefilterSetting q = app::parse_prefilter_options(args.prefilter);
  std::vector<std::filesystem::path> inputs{args.volume, args.reference, args.difference_to};
  (void)support::check_output_file(args.output, inputs);

  const int axis = args.axis[0] - 'x';
  const int u = axis == 0 ? 1 : 0, v = axis == 2 ? 1 : 2;  // image x along u, image y along -v
  // What each panel shows, and the box of the slice plane.
  std::vector<LatticeVolume<float>> volumes;
  std::vector<SplineFilter> filters;
  SourceSamples source;
  Box box{};
  for (int a = 0; a < 3; ++a) {
    box.min[a] = -HUGE_VAL;
    box.max[a] = HUGE_VAL;
  }
  for (const std::string& name : names) {
    filters.push_back(frontend::filter_for_volume(name, args.lattice, args.volume));
    volumes.push_back(app::read_for<float>(filters.back(), q, args.volume, {}));
    const Box b = default_box(volumes.back(), filters.back());
    for (int a = 0; a < 3; ++a) {  // panels side by side share the box all of them reconstruct
      box.min[a] = std::max(box.min[a], b.min[a]);
      box.max[a] = std::min(box.max[a], b.max[a]);
    }
  }
  if (reconstruct) (void)read_volume_file<float>(args.volume, {}, &source);
  std::optional<LatticeVolume<float>> reference;
  const std::string& ref_path = reconstruct ? args.difference_to : args.reference;
  if (!ref_path.empty()) {
    reference = read_volume_file<float>(ref_path, {}, &source);
    if (reference->coset_count() != 1 || reference->period() != 1)
      throw std::invalid_argument("--reference and --difference-to must be Cartesian volumes");
    for (int a = 0; a < 3; ++a) {  // the reference's grid is the image's
      box.min[a] = reference->origin()[a];
      box.max[a] =
          reference->origin()[a] + reference->axis_spacing()[a] * (reference->sizes()[a] - 1);
    }
  }
  if (*args.at < box.min[axis] || *args.at > box.max[axis] || box.min[u] >= box.max[u] ||
      box.min[v] >= box.max[v])
    throw std::out_of_range(fmt::format(
        "--at {} is outside the slice's range [{:.6g}, {:.6g}] on {} (the region every panel "
        "reconstructs, or the reference's grid)",
        *args.at, box.min[axis], box.max[axis], args.axis));
  const std::array<int, 2> size = panel_size(box, u, v, reference);
  const int width = size[0], height = size[1];
  // Pixel (x, y) of a panel: its centre on the plane; the first and last pixels on the box faces.
  const auto pixel_point = [&](int x, int y) {
    Vec3 p{};
    p[axis] = *args.at;
    p[u] = width == 1 ? box.min[u] : box.min[u] + (box.max[u] - box.min[u]) * x / (width - 1);
    p[v] = height == 1 ? box.max[v] : box.max[v] - (box.max[v] - box.min[v]) * y / (height - 1);
    return p;
  };
  const std::size_t panels = reconstruct ? filters.size() : 1;
  const std::size_t pixels = static_cast<std::size_t>(width) * static_cast<std::size_t>(height);
  std::vector<double> values(panels * pixels, NAN);
  std::vector<Vec3> points(pixels);
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x)
      points[static_cast<std::size_t>(y) * width + x] = pixel_point(x, y);
  std::vector<double> ref_values(pixels, NAN);
  if (reference)
    for (std::size_t i = 0; i < pixels; ++i)
      if (const auto r = nearest_voxel(*reference, points[i])) ref_values[i] = *r;
  if (!reconstruct) std::copy(ref_values.begin(), ref_values.end(), values.begin());
  for (std::size_t f = 0; reconstruct && f < panels; ++f) {
    const std::vector<double> panel =
        reconstructed_panel(volumes[f], filters[f], points, ref_values, reference.has_value());
    std::copy(panel.begin(), panel.end(), values.begin() + static_cast<std::ptrdiff_t>(f * pixels));
  }
  const bool difference = !args.difference_to.empty();
  double lo = source.min, hi = source.max;
  if (difference) {
    double largest = 0;
    for (double x : values)
      if (!std::isnan(x)) largest = std::max(largest, std::fabs(x));
    lo = -largest;
    hi = largest;
  }
  if (!args.range.empty()) {
    lo = args.range[0];
    hi = args.range[1];
  }
  if (!(hi > lo)) hi = lo + 1;  // a constant image: every pixel at the map's low end
  const int total_width = static_cast<int>(panels) * width + static_cast<int>(panels - 1) * kGap;
  analysis::RgbImage image(total_width, height);
  std::fill(image.pixels.begin(), image.pixels.end(), std::uint8_t{255});
  for (std::size_t f = 0; f < panels; ++f)
    for (int y = 0; y < height; ++y)
      for (int x = 0; x < width; ++x) {
        const double value = values[f * pixels + static_cast<std::size_t>(y) * width + x];
        const int px = static_cast<int>(f) * (width + kGap) + x;
        if (std::isnan(value)) {
          image.set(px, y, kOutside[0], kOutside[1], kOutside[2]);
          continue;
        }
        const auto [r, g, b] = colour_of(value, lo, hi, difference);
        image.set(px, y, r, g, b);
      }
  analysis::write_png(args.output, image);
  std::cout << fmt::format(
      "{} x {} pixels per panel, {} panel(s), {} = {} in [{:.6g}, {:.6g}] x "
      "[{:.6g}, {:.6g}], values [{:.6g}, {:.6g}] mapped to the colour map\n",
      width, height, panels, args.axis, *args.at, box.min[u], box.max[u], box.min[v], box.max[v],
      lo, hi);
  return 0;
}

}  // namespace boxgen::recon
