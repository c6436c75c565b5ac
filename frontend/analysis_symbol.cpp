#include "frontend/analysis_symbol.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <optional>

#include "analysis/symbol_extremes.h"
#include "frontend/commands.h"
#include "generator/approximation_order.h"
#include "generator/interpolation_symbol.h"

namespace boxgen::frontend {

namespace {

// |A| below this fraction of max |A| counts as a zero where the generator cannot decide exactly.
constexpr double kNumericalZero = 1e-9;

struct SymbolReport {
  std::optional<std::string> undefined;  // why there is no symbol (a discontinuous filter)
  std::vector<LatticeSample> samples;
  ExactSymbolValues exact;
  analysis::SymbolExtremes numeric;
  bool exact_minimum = false;  // the numerical minimum is the exact one at a candidate
  bool well_posed = false;
};

SymbolReport symbol_report(const Derivation& a) {
  SymbolReport r;
  const int n = a.spec.dimension();
  if (approximation_order(a.spec.directions, n) < 2) {
    r.undefined = "the filter is discontinuous at lattice points";
    return r;
  }
  r.samples = lattice_samples(a.form);
  r.exact = exact_symbol_values(r.samples, a.spec.lattice);
  std::vector<analysis::LatticeTap> taps;
  for (const auto& s : r.samples) taps.push_back({s.point, to_double(s.value)});
  r.numeric = analysis::symbol_extremes(taps);
  // Every candidate lies on the numerical grid, so the numerical minimum is at most the exact
  // one; where they agree the minimum is attained at a candidate.
  r.exact_minimum = std::fabs(r.numeric.min_abs - to_double(r.exact.min_abs)) <=
                    1e-12 * std::max(1.0, r.numeric.max_abs);
  r.well_posed = r.exact.zeros.empty() && r.numeric.min_abs > kNumericalZero * r.numeric.max_abs;
  return r;
}

std::string frequency_text(const RatVec& r) {
  std::string s = "pi (";
  for (std::size_t i = 0; i < r.size(); ++i) s += (i ? "," : "") + to_string(r[i]);
  return s + ")";
}

// "pi (1,0,0) and 5 equivalent points" for a class.
std::string class_text(const FrequencyClass& c) {
  const std::size_t others = c.representatives.size() - 1;
  return frequency_text(c.representatives.front()) +
         (others == 0 ? ""
                      : fmt::format(" and {} equivalent point{}", others, others == 1 ? "" : "s"));
}

nlohmann::json classes_json(const std::vector<FrequencyClass>& classes) {
  nlohmann::json out = nlohmann::json::array();
  for (const auto& c : classes) {
    nlohmann::json reps = nlohmann::json::array();
    for (const auto& r : c.representatives) reps.push_back(rational_list(r));
    out.push_back(reps);
  }
  return out;
}

}  // namespace

nlohmann::json symbol_json(const Derivation& a) {
  const SymbolReport r = symbol_report(a);
  if (r.undefined) return {{"defined", false}, {"reason", *r.undefined}};
  nlohmann::json samples = nlohmann::json::array();
  for (const auto& s : r.samples)
    samples.push_back({{"point", s.point}, {"value", to_string(s.value)}});
  std::vector<double> at;
  for (int i = 0; i < a.spec.dimension(); ++i)
    at.push_back(r.numeric.min_at[static_cast<std::size_t>(i)] / std::numbers::pi);
  return {
      {"defined", true},
      {"samples", samples},
      {"well_posed", r.well_posed},
      {"max_abs", r.numeric.max_abs},
      {"min_abs", r.numeric.min_abs},
      {"min_at_over_pi", at},
      {"min_abs_exact",
       r.exact_minimum ? nlohmann::json(to_string(r.exact.min_abs)) : nlohmann::json(nullptr)},
      {"min_at_exact", r.exact_minimum ? classes_json(r.exact.min_at) : nlohmann::json::array()},
      {"zeros", classes_json(r.exact.zeros)},
      {"exact_candidates", r.exact.candidates}};
}

std::string symbol_text(const Derivation& a) {
  const SymbolReport r = symbol_report(a);
  std::string out = "interpolation symbol A(w) = sum_k M(k) exp(-i w.k)\n";
  const auto line = [&](const std::string& key, const std::string& value) {
    out += fmt::format("  {:<31} {}\n", key, value);
  };
  if (r.undefined) {
    line("defined", "no: " + *r.undefined);
    return out;
  }
  std::string centre = "0";
  for (const auto& s : r.samples)
    if (std::all_of(s.point.begin(), s.point.end(), [](auto x) { return x == 0; }))
      centre = to_string(s.value);
  line("lattice samples M(k)", fmt::format("{} nonzero, M(0) = {}", r.samples.size(), centre));
  if (!r.exact.zeros.empty()) {
    // A few classes; a zero set that is not a few points (cart7) has many.
    constexpr std::size_t kShown = 3;
    std::string where;
    for (std::size_t i = 0; i < std::min(kShown, r.exact.zeros.size()); ++i)
      where += (i ? "; " : "") + class_text(r.exact.zeros[i]);
    if (r.exact.zeros.size() > kShown)
      where += fmt::format("; and {} more (--json lists them)", r.exact.zeros.size() - kShown);
    line("min |A| over all w", "0 (exact): A vanishes at w = " + where);
  } else if (r.exact_minimum) {
    line("min |A| over all w",
         fmt::format("{} (exact, at w = {}; A(0) = 1)", to_string(r.exact.min_abs),
                     class_text(r.exact.min_at.front())));
  } else {
    std::string at;
    for (int i = 0; i < a.spec.dimension(); ++i)
      at += fmt::format("{}{:.6g}", i ? "," : "",
                        r.numeric.min_at[static_cast<std::size_t>(i)] / std::numbers::pi);
    line("min |A| over all w",
         fmt::format("{:.6g} (numerical, near w = pi ({}); A(0) = 1)", r.numeric.min_abs, at));
  }
  line("exact interpolation",
       r.well_posed ? "well posed"
                    : "ill posed (A vanishes): regularise, boxrecon --prefilter interp[:LAMBDA]");
  return out;
}

}  // namespace boxgen::frontend
