// The filter a command's --filter names: a registry filter, or any SPEC compiled at run time
// (loader/filter_loader.h) on --lattice (default the preset's lattice), with progress on a
// terminal unless --quiet.
#pragma once
#include <string>

#include "runtime/spline_filter.h"

namespace boxgen::app {

// Every command's --quiet: no progress of a filter's first use.
void set_quiet(bool quiet);
runtime::SplineFilter filter_from(const std::string& filter, const std::string& lattice = {});

// `boxrecon filters`: the registry's filters, then the cached ones.
int run_filters();

}  // namespace boxgen::app
