#include "frontend/filter_choice.h"

#include <unistd.h>

#include <fmt/format.h>

#include <optional>
#include <stdexcept>

#include "loader/filter_loader.h"
#include "runtime/nifti_io.h"
#include "runtime/nrrd_checks.h"

namespace boxgen::frontend {

namespace {
bool quiet_flag = false;

// A lattice as --lattice spells it: its name, or the rows of G of a custom one.
std::string lattice_text(const runtime::CosetLattice& lattice) {
  return lattice.name() == "custom" ? lattice.rows_text() : lattice.name();
}
}  // namespace

void set_quiet(bool quiet) { quiet_flag = quiet; }
bool quiet() { return quiet_flag; }

runtime::SplineFilter filter_from(const std::string& filter, const std::string& lattice) {
  loader::CompileOptions options;
  options.progress = !quiet_flag && isatty(STDERR_FILENO) != 0;
  return loader::load_filter(filter, lattice.empty() ? std::nullopt : std::optional(lattice),
                             options);
}

std::string lattice_for_volume(const std::string& filter, const std::string& lattice,
                               const runtime::CosetLattice& volume_lattice,
                               const std::string& volume, const std::string& option) {
  if (!lattice.empty()) {
    const runtime::CosetLattice given = runtime::CosetLattice::parse(lattice);
    if (!runtime::same_points(given, volume_lattice))
      throw std::invalid_argument(fmt::format("{} is {}, but {} is on the {} lattice", option,
                                              given.name(), volume, volume_lattice.name()));
    return lattice;
  }
  const bool direction_list = filter.find_first_of(",;") != std::string::npos;
  return direction_list ? lattice_text(volume_lattice) : std::string();
}

runtime::SplineFilter filter_for_volume(const std::string& filter, const std::string& lattice,
                                        const std::string& volume_path) {
  const std::optional<runtime::CosetLattice> of_file = runtime::read_volume_lattice(volume_path);
  if (!of_file) return filter_from(filter, lattice);  // reading the volume will say why
  return filter_from(
      filter, lattice_for_volume(filter, lattice, *of_file,
                                 fmt::format("the volume '{}'",
                                             runtime::nrrd_checks::printable(volume_path, 80))));
}

int run_filters() {
  const auto cached = loader::cached_filters();  // first: a cache it refuses prints nothing
  fmt::print("registry filters (built in):\n");
  for (int i = 0; i < runtime::SplineFilter::count(); ++i) {
    const runtime::SplineFilter f = runtime::SplineFilter::at(i);
    fmt::print("  {:<10} {}\n", f.name(), f.lattice().name());
  }
  // The directory's name is the user's own, but a terminal sees it as text all the same.
  fmt::print("compiled filters (cached in {}): {}\n",
             runtime::nrrd_checks::printable(loader::cache_directory().string()),
             cached.empty() ? "none" : std::to_string(cached.size()));
  for (const auto& c : cached)
    fmt::print("  \"{}\" --lattice {}  ({})\n", c.spec,
               c.lattice == "custom" ? "\"" + c.rows + "\"" : c.lattice,
               runtime::nrrd_checks::printable(c.library.string()));
  return 0;
}

}  // namespace boxgen::frontend
