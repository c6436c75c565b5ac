#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <iostream>
#include <limits>
#include <optional>
#include <span>
#include <stdexcept>
#include <string>
#include <vector>

#include "apps/boxrecon/box_options.h"
#include "apps/boxrecon/cmd_volumes.h"
#include "apps/boxrecon/lattice_commands.h"
#include "apps/boxrecon/output_volume.h"
#include "apps/boxrecon/prefilter_options.h"
#include "apps/boxrecon/progress.h"
#include "frontend/filter_choice.h"
#include "runtime/affine.h"
#include "runtime/nifti_io.h"
#include "runtime/nrrd_checks.h"
#include "runtime/resample.h"
#include "runtime/volume_output.h"
#include "support/output_file.h"

namespace boxgen::recon {

namespace {

using namespace boxgen::runtime;

struct CompareArgs {
  std::string reference, volume, filter, lattice, error_volume, type, mask;
  app::PrefilterOptions prefilter;
  std::optional<double> mask_above;
  app::BoxOptions box;
  bool json = false;
};
CompareArgs args;

// Error sums over a set of points, in double.
struct ErrorSums {
  std::uint64_t count = 0;
  double squares = 0, absolute = 0, max = 0;
  void add(double error) {
    ++count;
    squares += error * error;
    absolute += std::fabs(error);
    max = std::max(max, std::fabs(error));
  }
  double rms() const { return std::sqrt(squares / static_cast<double>(count)); }
  double mean_abs() const { return absolute / static_cast<double>(count); }
};

// Reference grid indices whose world points lie in [box.min, box.max] on axis a.
struct IndexRange {
  int first, last;  // empty when first > last
};
IndexRange indices_inside(const LatticeVolume<float>& ref, const Box& box, int a) {
  const double o = ref.origin()[a], s = ref.axis_spacing()[a];
  const double lo = std::ceil((box.min[a] - o) / s), hi = std::floor((box.max[a] - o) / s);
  IndexRange r{static_cast<int>(std::clamp(lo, 0.0, static_cast<double>(ref.sizes()[a]))),
               static_cast<int>(std::clamp(hi, -1.0, static_cast<double>(ref.sizes()[a] - 1)))};
  // The division may round across the face: keep exactly the points the box holds.
  while (r.first <= r.last && o + s * r.first < box.min[a]) ++r.first;
  while (r.first <= r.last && o + s * r.last > box.max[a]) --r.last;
  return r;
}

nlohmann::json stats_json(const ErrorSums& e, double peak) {
  const double psnr = 20 * std::log10(peak / e.rms());
  return {{"points", e.count},
          {"rms", e.rms()},
          {"max", e.max},
          {"mean_abs", e.mean_abs()},
          {"psnr_db", std::isfinite(psnr) ? nlohmann::json(psnr) : nlohmann::json(nullptr)}};
}

std::string stats_text(const ErrorSums& e, double peak) {
  return fmt::format("{} points  rms {:.6g}  max {:.6g}  mean_abs {:.6g}  psnr {:.4f} dB", e.count,
                     e.rms(), e.max, e.mean_abs(), 20 * std::log10(peak / e.rms()));
}

// Two oblique frames (maps to world with unit columns) equal up to NIfTI's float32 affine; h: the
// grid's spacing, for the translations. Nothing and nothing are equal.
bool same_frame(const std::optional<Affine>& a, const std::optional<Affine>& b, double h) {
  if (!a || !b) return !a && !b;
  for (std::size_t r = 0; r < 3; ++r) {
    if (std::abs(a->translation[r] - b->translation[r]) > 1e-4 * h) return false;
    for (std::size_t c = 0; c < 3; ++c)
      if (std::abs(a->linear[r][c] - b->linear[r][c]) > 1e-6) return false;
  }
  return true;
}

// The mask of --mask: a Cartesian volume on the reference's grid (the same sizes, and spacings,
// origin and an oblique reference's frame equal up to NIfTI's float32 affine), read as every
// volume is (axes positive).
LatticeVolume<float> read_mask(const LatticeVolume<float>& ref,
                               const std::optional<Affine>& ref_frame) {
  NrrdReadLimits limits;
  limits.allow_oblique = true;
  SourceSamples source;
  LatticeVolume<float> mask = read_volume_file<float>(args.mask, limits, &source);
  const std::string name = nrrd_checks::printable(args.mask, 80);
  if (mask.coset_count() != 1 || mask.period() != 1)
    throw std::invalid_argument(fmt::format("--mask '{}' must be a Cartesian volume, not a {} one",
                                            name, mask.lattice().label()));
  if (!same_frame(source.frame, ref_frame, ref.axis_spacing()[0]))
    throw std::invalid_argument(fmt::format(
        "--mask '{}' is not on the reference's grid: its affine's axes are not the reference's; "
        "resample it onto the reference first (boxrecon resample --like)",
        name));
  bool same = mask.sizes() == ref.sizes();
  for (int a = 0; a < 3 && same; ++a) {
    const double h = ref.axis_spacing()[a];
    same = std::abs(mask.axis_spacing()[a] - h) <= 1e-6 * h &&
           std::abs(mask.origin()[a] - ref.origin()[a]) <= 1e-4 * h;
  }
  if (!same)
    throw std::invalid_argument(fmt::format(
        "--mask '{}' is not on the reference's grid: {} x {} x {} voxels of {:.6g} x {:.6g} x "
        "{:.6g} from ({:.6g}, {:.6g}, {:.6g}), the reference {} x {} x {} of {:.6g} x {:.6g} x "
        "{:.6g} from ({:.6g}, {:.6g}, {:.6g}); resample it onto the reference first (boxrecon "
        "resample --like)",
        name, mask.sizes()[0], mask.sizes()[1], mask.sizes()[2], mask.axis_spacing()[0],
        mask.axis_spacing()[1], mask.axis_spacing()[2], mask.origin()[0], mask.origin()[1],
        mask.origin()[2], ref.sizes()[0], ref.sizes()[1], ref.sizes()[2], ref.axis_spacing()[0],
        ref.axis_spacing()[1], ref.axis_spacing()[2], ref.origin()[0], ref.origin()[1],
        ref.origin()[2]));
  return mask;
}

}  // namespace

CLI::App* add_compare_command(CLI::App& app) {
  auto* c = app.add_subcommand(
      "compare",
      "errors of a reconstruction against a reference volume at the reference's grid points "
      "(RMS, max, mean absolute, PSNR)");
  c->add_option("--reference", args.reference,
                "the original Cartesian volume (NRRD, or NIfTI .nii/.nii.gz)")
      ->required();
  c->add_option("--volume", args.volume, "the lattice volume to reconstruct (NRRD or NIfTI)")
      ->required();
  c->add_option(
       "--filter", args.filter,
       "a filter of the registry (" + SplineFilter::names() + ") or a SPEC, compiled on first use")
      ->required();
  c->add_option("--lattice", args.lattice,
                "the lattice of a SPEC --filter (default: the volume's)");
  app::add_prefilter_options(c, args.prefilter);
  auto* above = c->add_option("--mask-above", args.mask_above,
                              "V: also the errors over the points whose reference value exceeds V");
  c->add_option("--mask", args.mask,
                "FILE: also the errors over the voxels where this mask is not 0 (a Cartesian "
                "volume on the reference's grid, NRRD or NIfTI, e.g. a brain mask)")
      ->excludes(above);
  app::add_box_options(c, args.box,
                       "compare only in this box, which must lie in the region the filter "
                       "reconstructs (default: that region)");
  c->add_flag("--json", args.json, "one JSON object");
  c->add_option("--error-volume", args.error_volume,
                "NRRD (.nrrd) or NIfTI (.nii, .nii.gz) on the reference's grid: reconstruction "
                "minus reference (0 outside the region compared)");
  app::add_type_option(c, args.type, "--error-volume");
  return c;
}

// --reference: a Cartesian volume, oblique included (its frame in `source`); an oblique one's
// --error-volume must be NIfTI, whose affine holds its grid (checked before any work).
LatticeVolume<float> read_reference(SourceSamples& source) {
  NrrdReadLimits oblique;
  oblique.allow_oblique = true;
  LatticeVolume<float> ref = read_volume_file<float>(args.reference, oblique, &source);
  if (ref.coset_count() != 1 || ref.period() != 1)
    throw std::invalid_argument(
        fmt::format("--reference must be a Cartesian volume, not a {} one", ref.lattice().label()));
  if (source.frame && !args.error_volume.empty() &&
      output_format(args.error_volume) != VolumeFormat::Nifti)
    throw std::invalid_argument(fmt::format(
        "the reference '{}' is oblique: write --error-volume as NIfTI (.nii or .nii.gz), whose "
        "affine holds its grid",
        nrrd_checks::printable(args.reference, 80)));
  return ref;
}

// A reference grid point `p` (in the reference's frame) in the volume's frame, when it is compared:
// all points of the box without a map (their range is cut to the box already), else those whose
// image lies in it.
std::optional<Vec3> compared_point(const Vec3& p, const std::optional<Affine>& to_volume,
                                   const Box& box) {
  if (!to_volume) return p;
  const Vec3 v = to_volume->apply(p);
  for (std::size_t a = 0; a < 3; ++a)
    if (!(v[a] >= box.min[a] && v[a] <= box.max[a])) return std::nullopt;
  return v;
}

// The errors on the reference's grid, in its world (`reference`: what the reference's file held):
// an oblique reference's as NIfTI with its affine.
void write_error_volume(const LatticeVolume<float>& errors, const SourceSamples& reference,
                        const std::optional<SampleType>& type) {
  const std::optional<Affine>& frame = reference.frame;
  if (!frame)
    return app::write_output_volume(args.error_volume, errors, type, reference.anatomical,
                                    std::nullopt, reference.nifti_codes);
  const std::span<const float> e = errors.samples();
  app::write_output_grid(
      args.error_volume,
      CartesianVolume<float>{
          errors.sizes(), errors.axis_spacing(), errors.origin(), {e.begin(), e.end()}, frame},
      type, reference.anatomical, reference.nifti_codes);
}

// The report on stdout: text, or one JSON object with --json.
void print_report(const std::string& filter, const app::PrefilterSetting& q, double peak,
                  std::size_t reference_points, const Box& box, const ErrorSums& all,
                  const ErrorSums& masked, bool mask) {
  if (args.json) {
    nlohmann::json j{{"reference", args.reference},
                     {"volume", args.volume},
                     {"filter", filter},
                     {"prefilter", q.choice.text()},
                     {"boundary", boundary_name(q.boundary)},
                     {"peak", peak},
                     {"reference_points", reference_points},
                     {"box", {{"min", box.min}, {"max", box.max}}},
                     {"region", stats_json(all, peak)}};
    if (args.mask_above) {
      j["mask_above"] = *args.mask_above;
      j["mask"] = stats_json(masked, peak);
    }
    if (mask) {
      j["mask_file"] = args.mask;
      j["mask"] = stats_json(masked, peak);
    }
    std::cout << j.dump(2) << '\n';
  } else {
    std::cout << fmt::format(
        "{} ({}) against '{}' (peak = range {:.6g}, {} of {} grid points in [{:.6g}, {:.6g}] x "
        "[{:.6g}, {:.6g}] x [{:.6g}, {:.6g}])\n",
        filter, q.choice.text(), args.reference, peak, all.count, reference_points, box.min[0],
        box.max[0], box.min[1], box.max[1], box.min[2], box.max[2]);
    std::cout << "region: " << stats_text(all, peak) << '\n';
    if (args.mask_above)
      std::cout << fmt::format("mask > {}: ", *args.mask_above) << stats_text(masked, peak) << '\n';
    if (mask) std::cout << "mask: " << stats_text(masked, peak) << '\n';
  }
}

int run_compare() {
  const SplineFilter filter = frontend::filter_for_volume(args.filter, args.lattice, args.volume);
  const app::PrefilterSetting q = app::parse_prefilter_options(args.prefilter);
  const std::filesystem::path inputs[2] = {args.reference, args.volume};
  const std::optional<SampleType> type = app::parse_type_option(args.type);
  if (type && args.error_volume.empty())
    throw std::invalid_argument(
        "--type sets the sample type of --error-volume, which is not given");
  if (!args.error_volume.empty())
    app::require_output_volume(args.error_volume, inputs, CosetLattice::cartesian());
  if (args.mask_above && !std::isfinite(*args.mask_above))
    throw std::invalid_argument("--mask-above must be finite");
  // Oblique volumes (either or both) are read in their own frames: each reference grid point maps
  // from the reference's frame to the volume's (to_volume), and is compared where it lands in the
  // region the filter reconstructs.
  NrrdReadLimits oblique;
  oblique.allow_oblique = true;
  SourceSamples source, volume_source;
  const LatticeVolume<float> ref = read_reference(source);
  std::optional<LatticeVolume<float>> mask;
  if (!args.mask.empty()) mask.emplace(read_mask(ref, source.frame));
  const LatticeVolume<float> volume =
      app::read_for<float>(filter, q, args.volume, oblique, &volume_source);
  const std::optional<Affine> to_volume = grid_to_volume(volume_source.frame, source.frame);
  if ((source.frame || volume_source.frame) && app::given_box(args.box))
    throw std::invalid_argument(
        "--box and --min/--max are world coordinates, which do not bound an oblique reference's "
        "or volume's grid: leave them out to compare over the whole region");
  const Box region = default_box(volume, filter);
  const Box box = app::box_from_options(args.box, region, filter.name());
  IndexRange range[3];
  for (int a = 0; a < 3; ++a)
    range[a] = to_volume ? IndexRange{0, ref.sizes()[a] - 1} : indices_inside(ref, box, a);
  const Reconstructor<float> spline(volume, filter);

  std::optional<LatticeVolume<float>> error_volume;
  if (!args.error_volume.empty())
    error_volume.emplace(ref.lattice(), ref.sizes(), ref.axis_spacing(), ref.origin(),
                         std::vector<float>(ref.sample_count(), 0.0f));
  ErrorSums all, masked;
  std::vector<Vec3> points;
  std::vector<float> values;
  std::vector<std::size_t> where;
  const auto flush = [&] {
    values.resize(points.size());
    spline.evaluate(points, values);
    spline.require_finite(points, values);
    for (std::size_t p = 0; p < points.size(); ++p) {
      const float reference = ref.samples()[where[p]];
      const double error = static_cast<double>(values[p]) - static_cast<double>(reference);
      all.add(error);
      if ((args.mask_above && reference > *args.mask_above) ||
          (mask && mask->samples()[where[p]] != 0))
        masked.add(error);
      if (error_volume) error_volume->samples()[where[p]] = static_cast<float>(error);
    }
    points.clear();
    where.clear();
  };
  {
    app::Progress progress("comparing");
    const int planes = range[2].last - range[2].first + 1;
    for (int k = range[2].first; k <= range[2].last; ++k) {
      for (int j = range[1].first; j <= range[1].last; ++j)
        for (int i = range[0].first; i <= range[0].last; ++i)
          if (const auto p = compared_point(ref.sample_position(0, i, j, k), to_volume, box)) {
            points.push_back(*p);
            where.push_back(ref.index(0, i, j, k));
          }
      if (points.size() >= (std::size_t{1} << 16) || (k == range[2].last && !points.empty())) {
        flush();
        progress.update(static_cast<double>(k - range[2].first + 1) / planes);
      }
    }
  }
  if (all.count == 0)
    throw std::invalid_argument(fmt::format(
        "no reference grid point lies in the region the {} filter reconstructs from '{}'",
        filter.name(), args.volume));
  if (mask && masked.count == 0)
    throw std::invalid_argument(
        fmt::format("the mask is empty: no compared voxel of --mask '{}' is other than 0",
                    nrrd_checks::printable(args.mask, 80)));
  if (args.mask_above && masked.count == 0)
    throw std::invalid_argument(fmt::format(
        "the mask is empty: no compared reference value exceeds {} (the reference's range is "
        "[{}, {}])",
        *args.mask_above, source.min, source.max));
  const double peak = source.max - source.min;
  if (!(peak > 0))
    throw std::invalid_argument("the reference is constant: PSNR (peak = its range) is undefined");
  if (error_volume) write_error_volume(*error_volume, source, type);
  print_report(filter.name(), q, peak, ref.sample_count(), box, all, masked, mask.has_value());
  return 0;
}

}  // namespace boxgen::recon
