#include "runtime/spline_filter.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <exception>
#include <limits>
#include <stdexcept>
#include <string>
#include <utility>

#include "generated/registry.hpp"
#include "runtime/emitted_filter.h"
#include "runtime/fir_interpolation.h"
#include "runtime/interpolation.h"

namespace boxgen::runtime {

namespace generated = boxgen::generated;

std::string PrefilterChoice::text() const {
  std::string name;
  switch (kind_) {
    case Kind::None:
      name = "none";
      break;
    case Kind::Q1:
      name = "q1";
      break;
    case Kind::Q2:
      name = "q2";
      break;
    case Kind::Q1Opt:
      name = "q1opt";
      break;
    case Kind::Q2Opt:
      name = "q2opt";
      break;
    case Kind::QFir:
      name = "qfir";
      break;
    case Kind::Interp:
      name = "interp";
      break;
  }
  if (parameter_) name += fmt::format(":{}", *parameter_);
  return name;
}

PrefilterChoice parse_prefilter(std::string_view text) {
  if (text == "none") return PrefilterChoice::None;
  if (text == "q1") return PrefilterChoice::Q1;
  if (text == "q2") return PrefilterChoice::Q2;
  if (text == "q1opt") return PrefilterChoice::Q1Opt;
  if (text == "q2opt") return PrefilterChoice::Q2Opt;
  if (text == "interp") return PrefilterChoice::interp();
  if (text.starts_with("qfir:")) {
    const std::string_view k = text.substr(5);
    if (k.size() != 1 || k.front() < '0' || k.front() > '0' + kMaxFirShell)
      throw std::invalid_argument(
          fmt::format("prefilter '{}': K in qfir:K must be a shell index 0 to {}",
                      text.substr(0, 40), kMaxFirShell));
    return PrefilterChoice::qfir(k.front() - '0');
  }
  if (text.starts_with("interp:")) {
    const std::string number(text.substr(7, 40));
    std::size_t used = 0;
    double lambda = std::numeric_limits<double>::quiet_NaN();
    try {
      lambda = std::stod(number, &used);
    } catch (const std::exception&) {
      used = 0;
    }
    if (number.empty() || used != number.size() || !std::isfinite(lambda) || lambda < 0 ||
        lambda > 1)
      throw std::invalid_argument(
          fmt::format("prefilter '{}': the regularisation after interp: must be a number in [0, 1]",
                      text.substr(0, 40)));
    return PrefilterChoice::interp(lambda);
  }
  throw std::invalid_argument(
      fmt::format("unknown prefilter '{}': expected none, q1, q2, q1opt, q2opt, qfir:K, interp or "
                  "interp:LAMBDA",
                  text.substr(0, 40)));
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
                GeneratedPrefilters{prefilter_from(entry.q1), prefilter_from(entry.q2),
                                    prefilter_from(entry.q1opt), prefilter_from(entry.q2opt)},
                entry.approximation_order, i);
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
  if (!q.is_fir())
    throw std::invalid_argument(
        fmt::format("prefilter {} of filter {} is not a table of taps", q.text(), name_));
  if (q.kind() == PrefilterChoice::Kind::QFir) return fir_interpolation_taps(*this, q.fir_shells());
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
  if (q.kind() == PrefilterChoice::Kind::Interp) return interpolation_margin(*this, q.parameter());
  return reconstruction + prefilter_margin(prefilter(q), lattice_);
}

void SplineFilter::check_lattice(const CosetLattice& volume_lattice) const {
  if (!same_points(lattice_, volume_lattice))
    throw std::invalid_argument(
        fmt::format("filter {} is for the {} lattice, but the volume is on the {} lattice", name_,
                    lattice_.name(), volume_lattice.name()));
}

}  // namespace boxgen::runtime
