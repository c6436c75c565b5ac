#include <fmt/format.h>

#include <cmath>
#include <cstdint>
#include <iostream>
#include <optional>
#include <stdexcept>
#include <string>

#include "apps/boxrecon/cmd_volumes.h"
#include "apps/boxrecon/output_volume.h"
#include "apps/boxrecon/prefilter_options.h"
#include "apps/boxrecon/progress.h"
#include "frontend/filter_choice.h"
#include "frontend/input_checks.h"
#include "runtime/nifti_io.h"
#include "runtime/prefilter.h"
#include "runtime/resample.h"
#include "support/output_file.h"

namespace boxgen::recon {

namespace {

using namespace boxgen::runtime;

struct SubsampleArgs {
  std::string volume, lattice, filter = "tricubic", output, type;
  app::PrefilterOptions prefilter{"q2"};
  std::optional<double> fraction, spacing, smooth;
};
SubsampleArgs args;

}  // namespace

CLI::App* add_subsample_command(CLI::App& app) {
  auto* s = app.add_subcommand(
      "subsample",
      "a volume onto another lattice (bcc, fcc, a coarser cartesian grid) over its box, each "
      "sample the reconstruction of the input there (Fig. 10)");
  s->add_option("--volume", args.volume, "input volume (NRRD, or NIfTI .nii/.nii.gz)")->required();
  s->add_option("--lattice", args.lattice,
                "the output lattice: bcc | fcc | cartesian | \"a,b,c; d,e,f; g,h,i\" (rows of G)")
      ->required();
  auto* fraction =
      s->add_option("--fraction", args.fraction,
                    "about this fraction of the input's sample count, in (0, 1] (Fig. 10: 0.03)");
  auto* spacing = s->add_option("--spacing", args.spacing,
                                "the output lattice's spacing h (world units; BCC: sample "
                                "(c,i,j,k) at o + h (2i+c, 2j+c, 2k+c))");
  fraction->excludes(spacing);
  s->add_option("--filter", args.filter,
                "the filter that reconstructs the input (default tricubic; a registry filter of "
                "the input's lattice, or a SPEC, on the input's lattice)");
  app::add_prefilter_options(s, args.prefilter, "the input filter's; default q2");
  s->add_option("--smooth", args.smooth,
                "SIGMA: a Gaussian low-pass of this width (input samples) first, against aliasing");
  s->add_option("-o,--output", args.output,
                "the lattice volume: NRRD (.nrrd), or NIfTI-1 (.nii, .nii.gz) for a Cartesian one")
      ->required();
  app::add_type_option(s, args.type, "-o");
  return s;
}

int run_subsample() {
  if (args.fraction.has_value() == args.spacing.has_value())
    throw std::invalid_argument("give --fraction F or --spacing H");
  if (args.fraction && !(*args.fraction > 0 && *args.fraction <= 1))
    throw std::invalid_argument(
        fmt::format("--fraction must be in (0, 1], got {}", *args.fraction));
  if (args.spacing && !(std::isfinite(*args.spacing) && *args.spacing > 0))
    throw std::invalid_argument(
        fmt::format("--spacing must be finite and > 0, got {}", *args.spacing));
  const CosetLattice lattice = CosetLattice::parse(args.lattice);
  const SplineFilter filter = frontend::filter_for_volume(args.filter, "", args.volume);
  const app::PrefilterSetting q = app::parse_prefilter_options(args.prefilter);
  const std::optional<SampleType> type = app::parse_type_option(args.type);
  const std::filesystem::path input = args.volume;
  app::require_output_volume(args.output, {&input, 1}, lattice);

  // Its anatomical frame goes to the output; an oblique volume is subsampled in its own frame
  // (its box, and the output lattice, on its voxel axes) and the output keeps its affine.
  SourceSamples source;
  NrrdReadLimits oblique;
  oblique.allow_oblique = true;
  LatticeVolume<float> volume = read_volume_file<float>(args.volume, oblique, &source);
  filter.check_lattice(volume.lattice());
  const std::uint64_t input_count = volume.sample_count();
  if (args.smooth) volume = gaussian_smooth(volume, *args.smooth);
  volume = app::coefficients_for(std::move(volume), filter, q);
  const Box box = default_box(volume, filter);
  const double h =
      args.spacing
          ? *args.spacing
          : spacing_for_count(lattice, box, *args.fraction * static_cast<double>(input_count));
  // Before anything is allocated: the output samples, and the points and values of a block.
  frontend::check_memory(
      lattice_grid_count(lattice, box, h), 2 * sizeof(float),
      args.spacing ? fmt::format("--spacing {}", h) : fmt::format("--fraction {}", *args.fraction),
      "samples");
  const LatticeGrid grid = lattice_grid_in(lattice, box, h);
  const LatticeVolume<float> out = [&] {
    app::Progress progress("subsampling");
    return resample_to_lattice(volume, filter, grid, BatchEvaluate<float>{},
                               [&progress](double done) { progress.update(done); });
  }();
  app::write_output_volume(args.output, out, type, source.anatomical, source.frame,
                           source.nifti_codes);
  const std::uint64_t kept = out.sample_count();
  std::cout << fmt::format(
      "kept {} of {} samples: fraction {}/{} = {:.6f}, {} lattice h = {:.9g}, {} x {} x {} x {} "
      "samples, origin ({:.9g}, {:.9g}, {:.9g}); input reconstructed with {} after {}{}\n",
      kept, input_count, kept, input_count,
      static_cast<double>(kept) / static_cast<double>(input_count), lattice.name(), h,
      out.coset_count(), out.sizes()[0], out.sizes()[1], out.sizes()[2], out.origin()[0],
      out.origin()[1], out.origin()[2], filter.name(), q.choice.text(),
      args.smooth ? fmt::format(" and a Gaussian of width {}", *args.smooth) : std::string());
  return 0;
}

}  // namespace boxgen::recon
