#include <fmt/core.h>

#include <map>

#include "apps/boxgen/commands.h"
#include "generator/prefilter.h"

namespace boxgen::cli {

namespace {

// "5/3 - 1/12 sum(S1)" style: the z-transform grouped by equal weights, as in the paper's Table 1.
std::string formula(const Prefilter& q, const Lattice& lattice) {
  const auto shells = lattice.shells(q.shells.back() + 1);
  auto shell_of = [&](const IntVec& p) {
    for (size_t s = 0; s < shells.size(); ++s)
      for (const auto& x : shells[s])
        if (x == p) return static_cast<int>(s);
    return -1;
  };
  std::map<std::string, std::vector<int>> groups;  // weight -> shells (common parametrisation)
  std::string centre = "0";
  for (const auto& w : q.weights) {
    if (w.offset == IntVec(w.offset.size(), 0)) {
      centre = to_string(w.weight);
      continue;
    }
    auto& g = groups[to_string(w.weight)];
    int s = shell_of(w.offset);
    if (std::find(g.begin(), g.end(), s) == g.end()) g.push_back(s);
  }
  std::string out = centre;
  for (const auto& [weight, sh] : groups) {
    if (weight == "0") continue;
    std::string set;
    for (size_t i = 0; i < sh.size(); ++i) set += (i ? " u S" : "S") + std::to_string(sh[i]);
    const bool negative = weight[0] == '-';
    out += fmt::format(" {} {} sum_{{{}}} z^-xi", negative ? "-" : "+", negative ? weight.substr(1) : weight, set);
  }
  return out;
}

}  // namespace

int run_prefilter(const Common& c, const std::string& shells_text) {
  const BoxSplineSpec spec = parse_spec(c.spec, c.lattice);
  const std::vector<int> shells = parse_shells(shells_text);
  const Prefilter q = derive_prefilter(spec, shells);
  if (c.json) {
    nlohmann::json w = nlohmann::json::array();
    for (const auto& x : q.weights) w.push_back({{"offset", x.offset}, {"weight", to_string(x.weight)}});
    nlohmann::json out{{"order", q.order},
                       {"shells", q.shells},
                       {"parametrisation", q.parametrisation},
                       {"note", q.note},
                       {"weights", w}};
    print_json(out);
    return 0;
  }
  fmt::print("prefilter of approximation order {} for {} on shells {}\n", q.order, spec.name, shells_text);
  fmt::print("  Q(z) = {}\n", formula(q, spec.lattice));
  if (!q.note.empty()) fmt::print("  note: {}\n", q.note);
  for (const auto& x : q.weights) fmt::print("  {:<14} {}\n", format_point(x.offset), to_string(x.weight));
  return 0;
}

}  // namespace boxgen::cli
