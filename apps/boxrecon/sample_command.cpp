#include "apps/boxrecon/sample_command.h"

#include <fmt/format.h>

#include <algorithm>
#include <optional>
#include <stdexcept>

#include "apps/boxrecon/filter_choice.h"
#include "apps/boxrecon/input_checks.h"
#include "apps/boxrecon/output_volume.h"
#include "runtime/nrrd_io.h"
#include "runtime/sampling.h"
#include "runtime/test_functions.h"

namespace boxgen::app {

namespace {

// Coset cells of margin on every side: enough for M7, M8 and M12 with Q^I or Q^II.
constexpr int kSampleMargin = 3;

// kSampleMargin, or what a registry filter on this lattice needs after Q^I or Q^II if that is more.
int sample_margin(const runtime::CosetLattice& lattice) {
  using runtime::PrefilterChoice;
  int margin = kSampleMargin;
  for (int i = 0; i < runtime::SplineFilter::count(); ++i) {
    const runtime::SplineFilter f = runtime::SplineFilter::at(i);
    if (runtime::same_points(f.lattice(), lattice))
      margin = std::max(
          {margin, f.required_margin(PrefilterChoice::Q1), f.required_margin(PrefilterChoice::Q2)});
  }
  return margin;
}

template <class T>
void sample_and_write(const runtime::TestFunction& fn, const runtime::LatticeGrid& grid,
                      const std::string& output, std::optional<runtime::SampleType> type) {
  write_output_volume(output, runtime::sample_lattice<T>(fn.value, grid), type);
}

}  // namespace

runtime::CosetLattice lattice_for(const runtime::SplineFilter& f, const std::string& lattice) {
  if (lattice.empty()) return f.lattice();
  const runtime::CosetLattice given = runtime::CosetLattice::parse(lattice);
  if (!runtime::same_points(f.lattice(), given))
    throw std::invalid_argument(fmt::format("filter {} is for the {} lattice, but --lattice is {}",
                                            f.name(), f.lattice().name(), given.name()));
  return f.lattice();
}

runtime::LatticeGrid sample_grid(int n, const std::optional<double>& h,
                                 const std::string& lattice_text, const std::string& filter,
                                 std::size_t bytes_per_sample) {
  std::optional<runtime::SplineFilter> f;
  if (!filter.empty()) f = filter_from(filter, lattice_text);
  const runtime::CosetLattice lattice =
      f ? lattice_for(*f, lattice_text)
        : (lattice_text.empty() ? runtime::CosetLattice::bcc()
                                : runtime::CosetLattice::parse(lattice_text));
  const int margin = sample_margin(lattice);
  if (n < 2 || n > 1024)
    throw std::invalid_argument(fmt::format("--n must be between 2 and 1024, got {}", n));
  check_spacing(h);
  runtime::LatticeGrid grid = runtime::cube_lattice_grid(lattice, n, margin);
  const auto per_axis = static_cast<std::uint64_t>(grid.sizes[0]);
  check_memory(static_cast<std::uint64_t>(lattice.coset_count()) * per_axis * per_axis * per_axis,
               bytes_per_sample, fmt::format("--n {}", n), "samples");
  if (h) {  // --h overrides the spacing; the grid still starts margin cells below -1
    grid.h = *h;
    for (auto& o : grid.origin) o = -1 - lattice.period() * *h * margin;
  }
  return grid;
}

int run_sample(const std::string& function, int n, const std::optional<double>& h,
               const std::string& lattice_text, const std::string& filter,
               const std::string& precision, const std::string& output,
               const std::string& type_text) {
  const runtime::TestFunction& fn = runtime::find_test_function(function);
  const std::optional<runtime::SampleType> type = parse_type_option(type_text);
  const runtime::LatticeGrid grid = sample_grid(
      n, h, lattice_text, filter, precision == "float" ? sizeof(float) : sizeof(double));
  require_output_volume(output, {}, grid.lattice);
  if (precision == "float")
    sample_and_write<float>(fn, grid, output, type);
  else
    sample_and_write<double>(fn, grid, output, type);
  return 0;
}

}  // namespace boxgen::app
