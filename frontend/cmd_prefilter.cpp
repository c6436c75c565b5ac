#include <fmt/core.h>

#include <algorithm>
#include <map>
#include <optional>
#include <utility>

#include "frontend/commands.h"
#include "frontend/optimised_prefilter.h"
#include "generator/prefilter.h"

namespace boxgen::frontend {

namespace {

// "5/3 - 1/12 sum_{S1} z^-xi" style: the z-transform grouped by equal weights, as in the paper's
// Table 1. A shell appears in a sum only if every one of its points has that weight; taps of a
// shell that is not uniform are listed one by one, so the summary matches the taps exactly.
std::string formula(const Prefilter& q, const Lattice& lattice) {
  const auto shells = lattice.shells(q.shells.back() + 1);
  std::map<IntVec, Rational> tap;
  for (const auto& w : q.weights) tap[w.offset] = w.weight;
  auto weight_at = [&](const IntVec& p) {
    auto it = tap.find(p);
    return it == tap.end() ? Rational(0) : it->second;
  };
  std::string centre = to_string(weight_at(IntVec(lattice.dimension(), 0)));
  std::map<std::string, std::vector<std::string>> groups;  // weight -> "S1", "z^-(1,0,0)", ...
  std::map<std::string, std::vector<std::string>> points;  // weight -> taps of non-uniform shells
  std::map<std::string, Rational> value_of;
  for (size_t s = 1; s < shells.size(); ++s) {
    const Rational first = weight_at(shells[s].front());
    const bool uniform = std::all_of(shells[s].begin(), shells[s].end(),
                                     [&](const IntVec& p) { return weight_at(p) == first; });
    if (uniform) {
      if (cln::zerop(first)) continue;
      groups[to_string(first)].push_back("S" + std::to_string(s));
      value_of[to_string(first)] = first;
      continue;
    }
    for (const auto& p : shells[s]) {
      const Rational w = weight_at(p);
      if (cln::zerop(w)) continue;
      points[to_string(w)].push_back(format_point(p));
      value_of[to_string(w)] = w;
    }
  }
  for (auto& [weight, pts] : points) {
    std::string set;
    for (size_t i = 0; i < pts.size(); ++i) set += (i ? ", " : "") + pts[i];
    groups[weight].push_back("{" + set + "}");
  }
  std::string out = centre;
  for (const auto& [weight, terms] : groups) {
    std::string set;
    for (size_t i = 0; i < terms.size(); ++i) set += (i ? " u " : "") + terms[i];
    const bool negative = cln::minusp(value_of[weight]);
    out += fmt::format(" {} {} sum_{{xi in {}}} z^-xi", negative ? "-" : "+",
                       negative ? weight.substr(1) : weight, set);
  }
  return out;
}

// 17 significant digits: the double nearest to a weight that is not printed exactly.
std::string digits17(const Rational& r) { return fmt::format("{:.17g}", to_double(r)); }

// Are the weights printed exactly? All but those of an optimisation with free parameters.
bool exact(const std::optional<OptimisedPrefilter>& o) { return !o || o->family.basis.empty(); }

// The prefilter on --shells or the one --prefilter names (exactly one of them is given), with the
// optimisation of q1opt and q2opt.
struct Chosen {
  Prefilter q;
  std::optional<OptimisedPrefilter> optimised;
};

Chosen chosen_prefilter(const BoxSplineSpec& spec, const std::string& shells_text,
                        const std::string& name) {
  if (shells_text.empty() == name.empty()) fail_usage("give either --shells or --prefilter");
  if (is_optimised_prefilter(name)) {
    OptimisedPrefilter o = optimised_prefilter(spec, name);
    Prefilter q = o.prefilter;
    return {std::move(q), std::move(o)};
  }
  return {name.empty() ? derive_prefilter(spec, parse_shells(shells_text))
                       : named_prefilter(spec, name),
          std::nullopt};
}

nlohmann::json prefilter_json(const Chosen& c) {
  const Prefilter& q = c.q;
  nlohmann::json w = nlohmann::json::array();
  for (const auto& x : q.weights)
    w.push_back({{"offset", x.offset},
                 {"weight", exact(c.optimised) ? to_string(x.weight) : digits17(x.weight)}});
  nlohmann::json out = {
      {"order", q.order}, {"shells", q.shells},          {"parametrisation", q.parametrisation},
      {"note", q.note},   {"exact", exact(c.optimised)}, {"weights", w}};
  if (c.optimised) {
    const auto& o = *c.optimised;
    nlohmann::json p = nlohmann::json::array();
    for (size_t i = 0; i < o.optimisation.parameters.size(); ++i)
      p.push_back({{"orbit", o.family.orbit_labels[o.family.free_orbits[i]]},
                   {"value", o.optimisation.parameters[i]}});
    out["optimisation"] = {{"parameters", p},
                           {"integrated_error_kernel", o.optimisation.optimised},
                           {"integrated_error_kernel_at_zero", o.optimisation.at_zero},
                           {"quadrature_change", o.optimisation.quadrature_change}};
  }
  return out;
}

}  // namespace

nlohmann::json prefilter_json(const Common& c, const std::string& shells_text,
                              const std::string& name) {
  const BoxSplineSpec spec = parse_spec(c.spec, c.lattice);
  return prefilter_json(chosen_prefilter(spec, shells_text, name));
}

int run_prefilter(const Common& c, const std::string& shells_text, const std::string& name) {
  const BoxSplineSpec spec = parse_spec(c.spec, c.lattice);
  const Chosen chosen = chosen_prefilter(spec, shells_text, name);
  const Prefilter& q = chosen.q;
  if (c.json) {
    print_json(prefilter_json(chosen));
    return 0;
  }
  std::string shells;
  for (size_t i = 0; i < q.shells.size(); ++i)
    shells += (i ? "," : "") + std::to_string(q.shells[i]);
  fmt::print("{}prefilter of approximation order {} for {} on shells {}\n",
             name.empty() ? "" : name + ": ", q.order, spec.name, shells);
  if (chosen.optimised && chosen.optimised->family.basis.empty()) {
    fmt::print(
        "  no free parameters on these shells (one weight per symmetry orbit): the unique "
        "prefilter of full order there, exact; integrated error kernel {:.10g}\n",
        chosen.optimised->optimisation.optimised);
    fmt::print("  Q(z) = {}\n", formula(q, spec.lattice));
  } else if (chosen.optimised) {
    const auto& o = *chosen.optimised;
    fmt::print(
        "  one weight per symmetry orbit; {} free parameter{} chosen to minimise the integrated "
        "error kernel (1/|N|) int_N E(w) dw over the Nyquist region\n",
        o.optimisation.parameters.size(), o.optimisation.parameters.size() == 1 ? "" : "s");
    for (size_t i = 0; i < o.optimisation.parameters.size(); ++i)
      fmt::print("  parameter: weight of {} = {:.17g}\n",
                 o.family.orbit_labels[o.family.free_orbits[i]], o.optimisation.parameters[i]);
    fmt::print(
        "  integrated error kernel: {:.10g} (parameters zero: {:.10g}; quadrature change {:.1e})\n",
        o.optimisation.optimised, o.optimisation.at_zero, o.optimisation.quadrature_change);
    fmt::print(
        "  weights (not rational: 17 significant digits; the moment conditions hold "
        "exactly for the printed parameters)\n");
  } else {
    fmt::print("  Q(z) = {}\n", formula(q, spec.lattice));
  }
  if (!q.note.empty()) fmt::print("  note: {}\n", q.note);
  for (const auto& x : q.weights)
    fmt::print("  {:<14} {}\n", format_point(x.offset),
               exact(chosen.optimised) ? to_string(x.weight) : digits17(x.weight));
  return 0;
}

}  // namespace boxgen::frontend
