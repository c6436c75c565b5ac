// boxrecon's eval, error, resample and bench for the registry filters that live on other lattices
// than BCC's Reconstructor (fcc6 on FCC, tricubic and cart7 on the Cartesian lattice, and any
// filter added to generated/registry.hpp): the same arguments, output and errors as the BCC
// commands in main.cpp, through runtime/lattice_filters.h on LatticeVolume. A volume of another
// lattice than the filter's is one line (std::invalid_argument).
#pragma once
#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "runtime/lattice_filters.h"
#include "runtime/nrrd_io.h"

namespace boxgen::app {

// eval's output: one line per point, the value and (when asked) the gradient and the Hessian's
// upper triangle h_xx h_xy h_xz h_yy h_yz h_zz, each with 17 significant digits.
template <class T>
void print_evaluations(std::span<const T> values, std::span<const runtime::Vec3> gradients,
                       std::span<const runtime::Hessian> hessians, bool gradient, bool hessian);

template <class T>
int run_lattice_eval(runtime::RegistryFilter f, runtime::PrefilterChoice q,
                     const std::string& volume_path, const std::string& points_path, bool gradient,
                     bool hessian, const runtime::NrrdReadLimits& limits);

// The error report of `error` (text or JSON, the BCC command's keys).
struct ErrorReport {
  std::string function, filter, prefilter;
  int n = 0, points = 0;
  std::uint64_t seed = 0;
  bool gradient = false, json = false;
  std::string lattice;  // the filter's lattice, where the samples were taken
};
void print_error_report(const ErrorReport& r, double rms, double max, double gradient_rms);

// `error` on the filter's lattice: N samples per coset and axis over [-1,1]^3 (cube_lattice_grid).
int run_lattice_error(const ErrorReport& report, runtime::RegistryFilter f,
                      runtime::PrefilterChoice q);

template <class T>
int run_lattice_resample(runtime::RegistryFilter f, runtime::PrefilterChoice q,
                         const std::string& volume_path, const std::string& output, int n,
                         const std::vector<double>& min, const std::vector<double>& max,
                         const runtime::NrrdReadLimits& limits);

// bench --filter NAME: seconds per point of the filter's value (and value + gradient) at random
// points of a volume of random samples on its lattice, one thread and all threads.
int run_filter_bench(runtime::RegistryFilter f, long points, int repeats, bool json);

}  // namespace boxgen::app
