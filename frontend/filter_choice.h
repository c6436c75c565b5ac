// The filter a command's --filter names: a registry filter, or any SPEC compiled at run time
// (loader/filter_loader.h) on --lattice (default the preset's lattice), with progress on a
// terminal unless --quiet.
#pragma once
#include <string>

#include "runtime/spline_filter.h"

namespace boxgen::frontend {

// Every command's --quiet: no progress of a filter's first use.
void set_quiet(bool quiet);
bool quiet();
runtime::SplineFilter filter_from(const std::string& filter, const std::string& lattice = {});
// The filter of --filter for the volume in `volume_path`: a SPEC direction list without --lattice
// is on the volume's lattice (read from its header, before anything is compiled), and a --lattice
// the volume is not on is refused up front (std::invalid_argument, one line). Presets and
// registry names keep their own lattice (the volume is checked against it when read).
runtime::SplineFilter filter_for_volume(const std::string& filter, const std::string& lattice,
                                        const std::string& volume_path);
// The lattice filter_from() gets for --filter on a volume on `volume_lattice` (the rule above):
// `lattice` when given (std::invalid_argument, one line naming `option` and `volume`, when the
// volume is not on it), else the volume's for a direction list, else none. Python's
// Filter(spec, volume=) takes it too.
std::string lattice_for_volume(const std::string& filter, const std::string& lattice,
                               const runtime::CosetLattice& volume_lattice,
                               const std::string& volume, const std::string& option = "--lattice");
// `boxrecon filters`: the registry's filters, then the cached ones.
int run_filters();

}  // namespace boxgen::frontend
