// Every command's --prefilter and --boundary (eval, error, resample, render, compare, slice,
// subsample): parsed in one place, applied in one place (runtime/coefficients.h), and interp's
// report printed in one place.
#pragma once
#include <CLI/CLI.hpp>

#include <string>

#include "runtime/boundary.h"
#include "runtime/coefficients.h"
#include "runtime/lattice_volume.h"
#include "runtime/prefilter_choice.h"
#include "runtime/spline_filter.h"

namespace boxgen::app {

struct PrefilterOptions {
  std::string prefilter = "none";
  std::string boundary = runtime::boundary_name(runtime::kDefaultBoundary);
};

// Adds --prefilter (its help ends with `default_note`, e.g. "default none") and --boundary.
void add_prefilter_options(CLI::App* command, PrefilterOptions& options,
                           const std::string& default_note = "default none");

struct PrefilterSetting {
  runtime::PrefilterChoice choice;
  runtime::Boundary boundary = runtime::kDefaultBoundary;
};
// Throws std::invalid_argument (one line) for an unknown prefilter or boundary.
PrefilterSetting parse_prefilter_options(const PrefilterOptions& options);

// The coefficients of f for `samples` (runtime::spline_coefficients). Where interp regularises,
// one line on stderr gives lambda and the residual at the samples (unless quiet).
template <class T>
runtime::LatticeVolume<T> coefficients_for(runtime::LatticeVolume<T> samples,
                                           const runtime::SplineFilter& f,
                                           const PrefilterSetting& setting,
                                           runtime::InterpolationReport* report = nullptr);

// interp's line: "interp: m7's symbol vanishes; lambda 0.0001, residual at the samples max ...".
std::string interpolation_line(const runtime::SplineFilter& f,
                               const runtime::InterpolationReport& r);

}  // namespace boxgen::app
