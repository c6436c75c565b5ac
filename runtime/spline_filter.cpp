#include "runtime/spline_filter.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>
#include <utility>

#include "generated/registry.hpp"
#include "runtime/emitted_filter.h"

namespace boxgen::runtime {

namespace generated = boxgen::generated;

PrefilterChoice parse_prefilter(std::string_view name) {
  if (name == "none") return PrefilterChoice::None;
  if (name == "q1") return PrefilterChoice::Q1;
  if (name == "q2") return PrefilterChoice::Q2;
  throw std::invalid_argument(
      fmt::format("unknown prefilter '{}': expected none, q1 or q2", name.substr(0, 40)));
}

SplineFilter SplineFilter::parse(std::string_view name) {
  for (int i = 0; i < generated::kFilterCount; ++i)
    if (name == generated::kFilterNames[i]) return at(i);
  throw std::invalid_argument(
      fmt::format("unknown filter '{}': expected {}", name.substr(0, 40), names()));
}

int SplineFilter::count() { return generated::kFilterCount; }

SplineFilter SplineFilter::at(int index) {
  if (index < 0 || index >= generated::kFilterCount)
    throw std::invalid_argument(fmt::format("no registry filter {}", index));
  // One source per registry entry, made on first use (thread-safe static initialisation).
  static const auto sources = [] {
    std::vector<std::shared_ptr<const FilterSource>> all;
    for (int i = 0; i < generated::kFilterCount; ++i)
      all.push_back(
          generated::with_filter(i, [i](auto entry) -> std::shared_ptr<const FilterSource> {
            return std::make_shared<EmittedFilter<typename decltype(entry)::Traits>>(
                prefilter_from(entry.q1), prefilter_from(entry.q2), entry.approximation_order, i);
          }));
    return all;
  }();
  return SplineFilter(sources[static_cast<std::size_t>(index)], index);
}

std::string SplineFilter::names() {
  std::string out;
  for (int i = 0; i < generated::kFilterCount; ++i) {
    if (i > 0) out += i + 1 == generated::kFilterCount ? " or " : ", ";
    out += generated::kFilterNames[i];
  }
  return out;
}

SplineFilter::SplineFilter(std::shared_ptr<const FilterSource> source)
    : SplineFilter(std::move(source), -1) {}

SplineFilter::SplineFilter(std::shared_ptr<const FilterSource> source, int registry_index)
    : source_(source ? std::move(source)
                     : throw std::invalid_argument("a SplineFilter needs a filter source")),
      name_(source_->name()),
      lattice_(source_->lattice()),
      registry_index_(registry_index) {}

PrefilterTaps SplineFilter::prefilter(PrefilterChoice q) const {
  if (q == PrefilterChoice::None) return {{{0, 0, 0}, 1.0}};
  return source_->prefilter(q);
}

int SplineFilter::required_margin(PrefilterChoice q) const {
  // Evaluation needs -lo - c <= x < d N - hi - c in the volume's lattice coordinates
  // (resample.h). A margin of m coset cells puts [-1,1] at lattice coordinates [d m, d (m + N -
  // 1)] in a volume of N + 2m cells per coset: it needs d m >= -lo - c and d m > hi + c - d; half
  // a coset cell of slack for rounding at the faces. Then the prefilter's own reach.
  const StencilReach r = reach();
  const int d = lattice_.period();
  double need = 0;
  for (int a = 0; a < 3; ++a)
    need = std::max({need, -r.lo[a] - r.centre[a], r.hi[a] + r.centre[a] - d});
  const int reconstruction = static_cast<int>(std::ceil(need / d + 0.5));
  if (q == PrefilterChoice::None) return reconstruction;
  return reconstruction + prefilter_margin(prefilter(q), lattice_);
}

void SplineFilter::check_lattice(const CosetLattice& volume_lattice) const {
  if (!same_points(lattice_, volume_lattice))
    throw std::invalid_argument(
        fmt::format("filter {} is for the {} lattice, but the volume is on the {} lattice", name_,
                    lattice_.name(), volume_lattice.name()));
}

}  // namespace boxgen::runtime
