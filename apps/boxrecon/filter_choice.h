// The filter a command's --filter names: a registry filter, or any SPEC compiled at run time
// (loader/filter_loader.h) on --lattice (default the preset's lattice), with progress on a
// terminal unless --quiet.
#pragma once
#include <string>

#include "runtime/gl/gl_spline.h"
#include "runtime/spline_filter.h"

namespace boxgen::app {

// Every command's --quiet: no progress of a filter's first use.
void set_quiet(bool quiet);
bool quiet();
runtime::SplineFilter filter_from(const std::string& filter, const std::string& lattice = {});
// The GLSL evaluator of filter_from(filter, lattice) = f for --device gl: the registry's, or a
// SPEC's emitted into the loader's cache with its compile.
runtime::gl::GlslEvaluator glsl_for(const runtime::SplineFilter& f, const std::string& filter,
                                    const std::string& lattice, bool double_precision);

// `boxrecon filters`: the registry's filters, then the cached ones.
int run_filters();

}  // namespace boxgen::app
