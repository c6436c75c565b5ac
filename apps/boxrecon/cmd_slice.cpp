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

#include "analysis/gnuplot.h"
#include "apps/boxrecon/cmd_volumes.h"
#include "apps/boxrecon/lattice_commands.h"
#include "frontend/filter_choice.h"
#include "runtime/affine.h"
#include "runtime/nifti_io.h"
#include "runtime/nrrd_checks.h"
#include "runtime/percentiles.h"
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
  std::vector<double> range, percentiles;
};
SliceArgs args;

// Pixels where a panel has no value (outside the filter's region): a colour no map produces.
constexpr const char* kOutside = "#600060";
// The longest side of a panel whose pixels are square on an anisotropic reference.
constexpr int kMaxSquarePixels = 4096;
// A panel shorter than this on its longer side is drawn larger, each pixel as a square of
// screen pixels, so that its labels and tics fit.
constexpr int kLeastDrawnSide = 256;

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

// The world's axis-aligned box around `box` of a volume's own frame (`frame`: its map to world;
// nothing: the box itself).
Box world_box(const Box& box, const std::optional<Affine>& frame) {
  if (!frame) return box;
  Box out{};
  for (int a = 0; a < 3; ++a) {
    out.min[a] = HUGE_VAL;
    out.max[a] = -HUGE_VAL;
  }
  for (int corner = 0; corner < 8; ++corner) {
    Vec3 p{};
    for (int a = 0; a < 3; ++a) p[a] = (corner >> a & 1) != 0 ? box.max[a] : box.min[a];
    const Vec3 w = frame->apply(p);
    for (int a = 0; a < 3; ++a) {
      out.min[a] = std::min(out.min[a], w[a]);
      out.max[a] = std::max(out.max[a], w[a]);
    }
  }
  return out;
}

// World points in a volume's own frame (through the inverse of `frame`, its map to world).
std::vector<Vec3> into_frame(const std::vector<Vec3>& world, const std::optional<Affine>& frame) {
  const std::optional<Affine> to_volume = grid_to_volume(frame, std::nullopt);
  if (!to_volume) return world;
  std::vector<Vec3> out(world.size());
  std::transform(world.begin(), world.end(), out.begin(),
                 [&](const Vec3& w) { return to_volume->apply(w); });
  return out;
}

// Every argument check that needs no file, before any work.
void check_slice_args() {
  const bool reconstruct = !args.volume.empty();
  if (!reconstruct && args.reference.empty())
    throw std::invalid_argument("give --volume FILE --filter F, --reference FILE, or both");
  if (reconstruct && args.filters.empty()) throw std::invalid_argument("--volume needs --filter");
  if (!args.reference.empty() && !args.difference_to.empty())
    throw std::invalid_argument(
        "give --reference (a panel of it beside the reconstructions) or --difference-to (the "
        "reconstructions minus it), not both");
  for (const std::string& f : args.filters)  // the comma list of earlier versions: "m7,m8"
    if (!f.empty() && f.find(',') != std::string::npos && f.find(';') == std::string::npos &&
        std::isalpha(static_cast<unsigned char>(f.front())) != 0)
      throw std::invalid_argument(fmt::format(
          "--filter '{}' is not one filter: repeat --filter for panels side by side (--filter m7 "
          "--filter m8)",
          nrrd_checks::printable(f, 40)));
  if (!reconstruct &&
      (!args.filters.empty() || !args.lattice.empty() || args.prefilter.prefilter != "none"))
    throw std::invalid_argument(
        "--filter, --lattice and --prefilter need --volume (with --reference alone the slice is "
        "the reference's)");
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
  if (!args.percentiles.empty() && !args.range.empty())
    throw std::invalid_argument("give --range or --percentiles, not both");
  if (!args.percentiles.empty() && !args.difference_to.empty())
    throw std::invalid_argument(
        "--percentiles has no effect with --difference-to (its window is +- the largest "
        "difference; set one with --range)");
  if (!args.percentiles.empty() &&
      !(args.percentiles[0] >= 0 && args.percentiles[0] < args.percentiles[1] &&
        args.percentiles[1] <= 100))
    throw std::invalid_argument("--percentiles needs 0 <= LO < HI <= 100");
}

// Pixels per panel, square in world units unless --size says otherwise: on a reference's box
// one pixel per voxel along its finer axis of the plane (its voxels once each when isotropic,
// repeated along the coarser axis when not; at most kMaxSquarePixels a side), else 512 on the
// box's longer side.
std::array<int, 2> panel_size(const Box& box, int u, int v,
                              const std::optional<LatticeVolume<float>>& reference) {
  if (!args.size.empty()) return {args.size[0], args.size[1]};
  const double wu = box.max[u] - box.min[u], wv = box.max[v] - box.min[v];
  if (reference) {
    const double pitch =
        std::max(std::min(reference->axis_spacing()[u], reference->axis_spacing()[v]),
                 std::max(wu, wv) / (kMaxSquarePixels - 1));
    return {static_cast<int>(std::lround(wu / pitch)) + 1,
            static_cast<int>(std::lround(wv / pitch)) + 1};
  }
  return {std::max(1, static_cast<int>(std::lround(wu >= wv ? 512 : 512 * wu / wv))),
          std::max(1, static_cast<int>(std::lround(wv >= wu ? 512 : 512 * wv / wu)))};
}

// The letter of the opposite anatomical direction.
char opposite(char letter) {
  switch (letter) {
    case 'R':
      return 'L';
    case 'L':
      return 'R';
    case 'A':
      return 'P';
    case 'P':
      return 'A';
    case 'S':
      return 'I';
    default:
      return 'S';
  }
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
                "a Cartesian volume: its slice (nearest voxel); with --volume the first panel, "
                "and every panel on its grid and window");
  s->add_option("--axis", args.axis, "x | y | z: the slice's normal (default z)");
  s->add_option("--at", args.at, "W: the slice's world coordinate on --axis")->required();
  s->add_option("--size", args.size,
                "W H: pixels per panel (default: square pixels, one per voxel of the reference's "
                "finer axis with --reference or --difference-to, else 512 on the longer side)")
      ->expected(2);
  s->add_option("--range", args.range,
                "LO HI: the values mapped to the colour map's ends (default: --percentiles 1 99; "
                "a difference: +-its largest magnitude)")
      ->expected(2);
  s->add_option("--percentiles", args.percentiles,
                "LO HI: map these percentiles of the samples (the reference's, else the "
                "volume's) to the colour map's ends (default 1 99; 0 100: min and max)")
      ->expected(2);
  s->add_option("--colormap", args.colormap, "grey (default) | viridis");
  s->add_option("--difference-to", args.difference_to,
                "a Cartesian volume: show reconstruction minus it (blue - white - red)");
  s->add_option("-o,--output", args.output, "PNG to write")->required();
  return s;
}

namespace {

// The plane of the slice: its normal `axis`, image x along u and image y along v (largest at the
// top), the box, and the pixels per panel with their spacing.
struct Plane {
  int axis = 2, u = 0, v = 1;
  Box box{};
  int width = 1, height = 1;
  double du = 1, dv = 1;
  // Pixel (x, y) of a panel (y = 0 the top row): its centre on the plane; the first and last
  // pixels on the box faces.
  Vec3 point(int x, int y) const {
    Vec3 p{};
    p[axis] = *args.at;
    p[u] = width == 1 ? box.min[u] : box.min[u] + du * x;
    p[v] = height == 1 ? box.max[v] : box.max[v] - dv * y;
    return p;
  }
};

Plane plane_over(const Box& box, const std::optional<LatticeVolume<float>>& reference) {
  Plane plane;
  plane.axis = args.axis[0] - 'x';
  plane.u = plane.axis == 0 ? 1 : 0;
  plane.v = plane.axis == 2 ? 1 : 2;
  plane.box = box;
  const int axis = plane.axis, u = plane.u, v = plane.v;
  if (*args.at < box.min[axis] || *args.at > box.max[axis] || box.min[u] >= box.max[u] ||
      box.min[v] >= box.max[v])
    throw std::out_of_range(fmt::format(
        "--at {} is outside the slice's range [{:.6g}, {:.6g}] on {} (the region every panel "
        "reconstructs, or the reference's grid)",
        *args.at, box.min[axis], box.max[axis], args.axis));
  const std::array<int, 2> size = panel_size(box, u, v, reference);
  plane.width = size[0];
  plane.height = size[1];
  const double wu = box.max[u] - box.min[u], wv = box.max[v] - box.min[v];
  plane.du = plane.width == 1 ? wu : wu / (plane.width - 1);
  plane.dv = plane.height == 1 ? wv : wv / (plane.height - 1);
  return plane;
}

// The values mapped to the colour map's ends, and where they came from.
struct Window {
  double lo = 0, hi = 1;
  std::string said;
};

// --range; +- the largest difference; or percentiles of `data`'s samples (`whose`: "reference").
Window choose_window(const std::vector<std::vector<double>>& values, bool difference,
                     const LatticeVolume<float>& data, const char* whose) {
  Window w;
  if (!args.range.empty()) {
    w = {args.range[0], args.range[1], "--range"};
  } else if (difference) {
    double largest = 0;
    for (const auto& panel : values)
      for (double x : panel)
        if (!std::isnan(x)) largest = std::max(largest, std::fabs(x));
    w = {-largest, largest, "+- the largest difference"};
  } else {
    const double p_lo = args.percentiles.empty() ? 1 : args.percentiles[0];
    const double p_hi = args.percentiles.empty() ? 99 : args.percentiles[1];
    const std::vector<double> p = percentiles(data.samples(), {p_lo / 100, p_hi / 100});
    w = {p[0], p[1],
         fmt::format("percentiles {:g} and {:g} of the {}'s samples", p_lo, p_hi, whose)};
  }
  if (!(w.hi > w.lo)) w.hi = w.lo + 1;  // a constant image: every pixel at the map's low end
  return w;
}

constexpr const char* kAxisName[3] = {"x", "y", "z"};

// One panel as image_png draws it; `anatomical` (SourceSamples) gives the edges' letters.
analysis::ImagePanel panel_image(const Plane& plane, const std::vector<double>& values,
                                 const std::string& title, const Window& window, bool difference,
                                 const std::string& anatomical) {
  const int u = plane.u, v = plane.v, width = plane.width, height = plane.height;
  analysis::ImagePanel image;
  image.title = fmt::format("{}, {} = {:g}", title, args.axis, *args.at);
  image.xlabel = kAxisName[u];
  image.ylabel = kAxisName[v];
  image.value_label = difference ? "reconstruction - reference" : "value";
  image.columns = width;
  image.rows = height;
  image.values.reserve(values.size());
  for (int y = height - 1; y >= 0; --y)  // bottom row first
    for (int x = 0; x < width; ++x)
      image.values.push_back(values[static_cast<std::size_t>(y) * width + x]);
  image.x_lo = plane.box.min[u] - plane.du / 2;
  image.x_hi = plane.box.min[u] + plane.du * (width - 0.5);
  image.y_lo = plane.box.max[v] - plane.dv * (height - 0.5);
  image.y_hi = plane.box.max[v] + plane.dv / 2;
  image.value_lo = window.lo;
  image.value_hi = window.hi;
  image.palette = difference                   ? analysis::Palette::difference
                  : args.colormap == "viridis" ? analysis::Palette::viridis
                                               : analysis::Palette::grey;
  image.blank = kOutside;
  image.zoom = std::max(1, kLeastDrawnSide / std::max(width, height));
  if (anatomical.size() == 3)
    image.edge_letters = {std::string(1, opposite(anatomical[u])), std::string(1, anatomical[u]),
                          std::string(1, opposite(anatomical[v])), std::string(1, anatomical[v])};
  return image;
}

// The two lines on stdout: the panels, the plane's box and the window; the orientation.
void print_summary(const Plane& plane, const std::vector<analysis::ImagePanel>& images,
                   const Window& window, const std::string& anatomical) {
  const int u = plane.u, v = plane.v, zoom = images.front().zoom;
  std::cout << fmt::format(
      "{} x {} pixels per panel{}, {} panel(s), {} = {} in [{:.6g}, {:.6g}] x "
      "[{:.6g}, {:.6g}], values [{:.6g}, {:.6g}] mapped to the colour map ({})\n",
      plane.width, plane.height, zoom == 1 ? "" : fmt::format(" (drawn {0} x {0} each)", zoom),
      images.size(), args.axis, *args.at, plane.box.min[u], plane.box.max[u], plane.box.min[v],
      plane.box.max[v], window.lo, window.hi, window.said);
  const auto& letters = images.front().edge_letters;
  if (anatomical.size() == 3)
    std::cout << fmt::format("orientation: left {}, right {}, bottom {}, top {} ({} world)\n",
                             letters[0], letters[1], letters[2], letters[3], anatomical);
  else
    std::cout << fmt::format(
        "orientation: {} to the right, {} upwards (the file has no anatomical frame)\n",
        kAxisName[u], kAxisName[v]);
}

}  // namespace

int run_slice() {
  check_slice_args();
  const bool reconstruct = !args.volume.empty();
  const std::vector<std::string>& names = args.filters;
  const app::PrefilterSetting q = app::parse_prefilter_options(args.prefilter);
  std::vector<std::filesystem::path> inputs{args.volume, args.reference, args.difference_to};
  (void)support::check_output_file(args.output, inputs);

  // What each panel shows, and the box of the slice plane.
  std::vector<LatticeVolume<float>> volumes;
  std::vector<SplineFilter> filters;
  Box box{};
  for (int a = 0; a < 3; ++a) {
    box.min[a] = -HUGE_VAL;
    box.max[a] = HUGE_VAL;
  }
  // Oblique volumes and references are read in their own frames (SourceSamples::frame); the
  // panels lie along the world's axes and each pixel's world point maps into those frames.
  NrrdReadLimits oblique;
  oblique.allow_oblique = true;
  SourceSamples volume_source;
  for (const std::string& name : names) {
    filters.push_back(frontend::filter_for_volume(name, args.lattice, args.volume));
    volumes.push_back(
        app::read_for<float>(filters.back(), q, args.volume, oblique, &volume_source));
    // Panels side by side share the box all of them reconstruct (in world: around an oblique
    // volume's region, the pixels outside it blank).
    const Box b = world_box(default_box(volumes.back(), filters.back()), volume_source.frame);
    for (int a = 0; a < 3; ++a) {
      box.min[a] = std::max(box.min[a], b.min[a]);
      box.max[a] = std::min(box.max[a], b.max[a]);
    }
  }
  // The samples the window comes from (the file's values, before any prefilter) and the world
  // frame the letters come from: the reference's when there is one, else the volume's.
  SourceSamples source;
  std::optional<LatticeVolume<float>> samples;
  if (reconstruct) samples = read_volume_file<float>(args.volume, oblique, &source);
  std::optional<LatticeVolume<float>> reference;
  const std::string& ref_path =
      reconstruct && args.reference.empty() ? args.difference_to : args.reference;
  std::optional<Affine> reference_frame;
  if (!ref_path.empty()) {
    SourceSamples ref_source;
    reference = read_volume_file<float>(ref_path, oblique, &ref_source);
    source = ref_source;
    reference_frame = ref_source.frame;
    if (reference->coset_count() != 1 || reference->period() != 1)
      throw std::invalid_argument("--reference and --difference-to must be Cartesian volumes");
    Box grid{};  // the reference's grid is the image's (its world box, when oblique)
    for (int a = 0; a < 3; ++a) {
      grid.min[a] = reference->origin()[a];
      grid.max[a] =
          reference->origin()[a] + reference->axis_spacing()[a] * (reference->sizes()[a] - 1);
    }
    box = world_box(grid, reference_frame);
  }
  const Plane plane = plane_over(box, reference);
  const bool difference = !args.difference_to.empty();
  const bool reference_panel = !args.reference.empty();
  const std::size_t pixels =
      static_cast<std::size_t>(plane.width) * static_cast<std::size_t>(plane.height);
  std::vector<Vec3> points(pixels);
  for (int y = 0; y < plane.height; ++y)
    for (int x = 0; x < plane.width; ++x)
      points[static_cast<std::size_t>(y) * plane.width + x] = plane.point(x, y);
  std::vector<double> ref_values(pixels, NAN);
  if (reference) {
    const std::vector<Vec3> in_frame = into_frame(points, reference_frame);
    for (std::size_t i = 0; i < pixels; ++i)
      if (const auto r = nearest_voxel(*reference, in_frame[i])) ref_values[i] = *r;
  }
  const std::vector<Vec3> volume_points = into_frame(points, volume_source.frame);
  std::vector<std::vector<double>> values;
  std::vector<std::string> titles;
  if (reference_panel) {
    values.push_back(ref_values);
    titles.push_back(fmt::format(
        "reference {}",
        nrrd_checks::printable(std::filesystem::path(args.reference).filename().string(), 40)));
  }
  for (std::size_t f = 0; f < filters.size(); ++f) {
    values.push_back(reconstructed_panel(volumes[f], filters[f], volume_points, ref_values,
                                         reference.has_value()));
    titles.push_back(
        nrrd_checks::printable(names[f], 40) +
        (args.prefilter.prefilter == "none" ? "" : " after " + args.prefilter.prefilter) +
        (difference ? " - reference" : ""));
  }
  const bool of_reference = reference_panel || !reconstruct;
  const Window window = choose_window(values, difference, of_reference ? *reference : *samples,
                                      of_reference ? "reference" : "volume");
  std::vector<analysis::ImagePanel> images;
  for (std::size_t f = 0; f < values.size(); ++f)
    images.push_back(
        panel_image(plane, values[f], titles[f], window, difference, source.anatomical));
  analysis::image_png(args.output, images);
  print_summary(plane, images, window, source.anatomical);
  return 0;
}

}  // namespace boxgen::recon
