// boxrecon's eval, error, resample and bench --filter for every filter of generated/registry.hpp
// on a volume of its lattice (M7, M8, M12 on BCC, fcc6 on FCC, tricubic and cart7 on the
// Cartesian lattice, and any filter added to the registry), through the runtime's one API
// (runtime/reconstruction.h). A volume of another lattice than the filter's is one line
// (std::invalid_argument).
#pragma once
#include <array>
#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "apps/boxrecon/box_options.h"
#include "apps/boxrecon/device_choice.h"
#include "apps/boxrecon/prefilter_options.h"
#include "runtime/nrrd_io.h"
#include "runtime/reconstruction.h"
#include "runtime/resample.h"

namespace boxgen::app {

// The coefficients of the volume of a file (NRRD or NIfTI: runtime/nifti_io.h), on the filter's
// lattice, after the prefilter and boundary of `setting` (coefficients_for). `source`, when
// given, receives what the file held (and an oblique volume's frame: NrrdReadLimits).
template <class T>
runtime::LatticeVolume<T> read_for(const runtime::SplineFilter& f, const PrefilterSetting& setting,
                                   const std::string& path, const runtime::NrrdReadLimits& limits,
                                   runtime::SourceSamples* source = nullptr);

// eval's output: one line per point, the value and (when asked) the gradient and the Hessian's
// upper triangle h_xx h_xy h_xz h_yy h_yz h_zz, each with 17 significant digits.
template <class T>
void print_evaluations(std::span<const T> values, std::span<const runtime::Vec3> gradients,
                       std::span<const runtime::Hessian> hessians, bool gradient, bool hessian);

// resample's output grid: --n N (a cube, default 64), --size NX NY NZ, or --spacing H
// (one, or three) over the box --box or --min/--max (default: default_box); or --like IMAGE, the
// grid of that Cartesian image (its sizes, spacings and origin). CLI11 keeps them exclusive.
struct OutputGridOptions {
  int n = 64;
  std::vector<int> size;
  std::vector<double> spacing;
  std::string like;
  BoxOptions box;
};

// eval: the filter's spline (after the prefilter and boundary of `pre`) at the points of a file,
// printed; a value that is not finite is an error (std::domain_error), and nothing is printed. On
// Device::Gl the points are evaluated by the GL device (verbose: its renderer on stderr).
template <class T>
int run_eval(const std::string& filter, const std::string& lattice, const PrefilterOptions& pre,
             const std::string& volume_path, const std::string& points_path, bool gradient,
             bool hessian, const runtime::NrrdReadLimits& limits, Device device = Device::Cpu,
             bool verbose = false);

// The error report of `error` (text or JSON, the BCC command's keys).
struct ErrorReport {
  std::string function, filter, prefilter;
  int n = 0, points = 0;
  std::uint64_t seed = 0;
  bool gradient = false, json = false;
  std::string lattice;  // the filter's lattice, where the samples were taken
  // The samples taken: K cosets of sizes[0] x sizes[1] x sizes[2], `margin` coset cells beyond
  // [-1,1]^3 on every side.
  std::uint64_t samples = 0;
  std::array<int, 3> sizes{};
  int margin = 0;
  std::optional<runtime::InterpolationReport> interpolation;
};
void print_error_report(const ErrorReport& r, double rms, double max, double gradient_rms);

// `error` on the filter's lattice: N samples per coset and axis over [-1,1]^3 (cube_lattice_grid)
// and the margin the prefilter needs (SplineFilter::required_margin), the RMS and max error at
// `count` random points; it says how many samples it took.
int run_error(const std::string& function, int n, const std::string& filter,
              const std::string& lattice, const PrefilterOptions& pre, int count,
              std::uint64_t seed, bool gradient, bool json);

// resample: the grid of `grid` (OutputGridOptions) on `output_lattice` (--lattice: empty is the
// --like image's lattice, else Cartesian), written as NRRD or NIfTI (Cartesian only) by the
// output's name, samples of --type `type` (empty: the format's default); nothing is written when
// any value is not finite. The filter (a SPEC too) is on the volume's lattice. A grid whose values
// do not fit in memory (check_memory: the values in T and their encoded copy) is refused, with the
// numbers, before any evaluation. Device as for run_eval.
template <class T>
int run_resample(const std::string& filter, const std::string& output_lattice,
                 const PrefilterOptions& pre, const std::string& volume_path,
                 const std::string& output, const std::string& type, const OutputGridOptions& grid,
                 const runtime::NrrdReadLimits& limits, Device device = Device::Cpu,
                 bool verbose = false);

// bench --filter NAME: seconds per point of the filter's value (and value + gradient) at random
// points of a volume of random samples on its lattice, one thread and all threads.
int run_filter_bench(const runtime::SplineFilter& f, long points, int repeats, bool json);

}  // namespace boxgen::app
