#include "frontend/sample_grid.h"

#include <fmt/format.h>

#include <algorithm>
#include <cstdint>
#include <optional>
#include <stdexcept>

#include "frontend/filter_choice.h"
#include "frontend/input_checks.h"

namespace boxgen::frontend {

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

}  // namespace boxgen::frontend
