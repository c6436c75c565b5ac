#include "apps/boxrecon/filter_choice.h"

#include <unistd.h>

#include <fmt/format.h>

#include "loader/filter_loader.h"
#include "runtime/nrrd_checks.h"

namespace boxgen::app {

namespace {
bool quiet_flag = false;
}  // namespace

void set_quiet(bool quiet) { quiet_flag = quiet; }
bool quiet() { return quiet_flag; }

runtime::gl::GlslEvaluator glsl_for(const runtime::SplineFilter& f, const std::string& filter,
                                    const std::string& lattice, bool double_precision) {
  if (f.registry_index() >= 0) return runtime::gl::registry_glsl(f.name(), double_precision);
  loader::CompileOptions options;
  options.progress = !quiet_flag && isatty(STDERR_FILENO) != 0;
  loader::EmittedGlsl glsl = loader::load_glsl(
      filter, lattice.empty() ? std::nullopt : std::optional(lattice), double_precision, options);
  return {std::move(glsl.name), std::move(glsl.text)};
}

runtime::SplineFilter filter_from(const std::string& filter, const std::string& lattice) {
  loader::CompileOptions options;
  options.progress = !quiet_flag && isatty(STDERR_FILENO) != 0;
  return loader::load_filter(filter, lattice.empty() ? std::nullopt : std::optional(lattice),
                             options);
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

}  // namespace boxgen::app
