#include <fmt/core.h>

#include "frontend/commands.h"
#include "generator/bbform.h"
#include "generator/box_spline_properties.h"
#include "generator/error.h"

namespace boxgen::frontend {

namespace {

std::string vertex_text(const RatVec& v) {
  std::string s = "(";
  for (size_t i = 0; i < v.size(); ++i) s += (i ? "," : "") + to_string(v[i]);
  return s + ")";
}

}  // namespace

namespace {

// The orbits --region selects: every reference region, or the one named by its index.
std::vector<int> selected_orbits(const std::string& region, std::size_t count) {
  std::vector<int> orbits;
  if (region == "reference") {
    for (size_t o = 0; o < count; ++o) orbits.push_back(static_cast<int>(o));
    return orbits;
  }
  const Rational r = parse_rational(region, "--region");
  if (!is_integer(r) || cln::minusp(r) || r >= Rational(static_cast<long>(count)))
    fail_input(fmt::format("--region must be 'reference' or an orbit index from 0 to {}, got '{}'",
                           count - 1, region));
  orbits.push_back(static_cast<int>(floor_to_int64(r)));
  return orbits;
}

// One simplex's BB-coefficients: appended to `text` and returned as JSON.
nlohmann::json simplex_coefficients(const SimplexBBForm& sx, int degree, std::string& text) {
  nlohmann::json js{{"vertices", nlohmann::json::array()},
                    {"coefficients", nlohmann::json::array()}};
  text += "  simplex:";
  for (const auto& v : sx.vertices) {
    js["vertices"].push_back(rational_list(v));
    text += " " + vertex_text(v);
  }
  text += fmt::format("\n  {} BB-coefficients of degree {}:\n", sx.indices.size(), degree);
  for (size_t b = 0; b < sx.indices.size(); ++b) {
    nlohmann::json terms = nlohmann::json::array();
    std::string line;
    for (size_t k = 0; k < sx.weights[b].size(); ++k) {
      const Rational& w = sx.weights[b][k];
      if (cln::zerop(w)) continue;
      terms.push_back({{"stencil", k}, {"weight", to_string(w)}});
      line +=
          fmt::format("{}{} V_{}",
                      line.empty() ? (cln::minusp(w) ? "-" : "") : (cln::minusp(w) ? " - " : " + "),
                      to_string(cln::abs(w)), k);
    }
    js["coefficients"].push_back({{"index", sx.indices[b]}, {"terms", terms}});
    std::string idx;
    for (int v : sx.indices[b]) idx += std::to_string(v);
    text += fmt::format("    c_{} = {}\n", idx, line.empty() ? "0" : line);
  }
  return js;
}

}  // namespace

BBFormOutput bbform_output(const Common& c, const std::string& region) {
  const BoxSplineSpec spec = parse_spec(c.spec, c.lattice);
  const PiecewiseForm form =
      derive_piecewise(spec, DerivationMethod::TruncatedPower, {}, derivation_budget(c));
  const SplineStructure s = spline_structure(form);
  const std::vector<int> orbits = selected_orbits(region, s.references.size());
  const int degree = box_spline_properties(spec).degree;
  nlohmann::json regions = nlohmann::json::array();
  std::string text;
  for (int o : orbits) {
    const ReferenceRegion& ref = s.references[o];
    const RegionBBForm bb = region_bb_form(ref, degree);
    nlohmann::json r{{"orbit", o},
                     {"regions_in_orbit", ref.regions_in_orbit},
                     {"triangulated", bb.triangulated}};
    r["vertices"] = nlohmann::json::array();
    for (const auto& v : ref.vertices) r["vertices"].push_back(rational_list(v));
    r["stencil"] = bb.stencil;
    text += fmt::format("reference region {} ({} regions per fundamental region map onto it)\n", o,
                        ref.regions_in_orbit);
    text += "  vertices:";
    for (const auto& v : ref.vertices) text += " " + vertex_text(v);
    text += fmt::format("\n  stencil ({} points, V_k = V(j_k)):\n", bb.stencil.size());
    for (size_t k = 0; k < bb.stencil.size(); ++k)
      text += fmt::format("    j_{:<3} {}\n", k, format_point(bb.stencil[k]));
    if (bb.triangulated)
      text += fmt::format(
          "  the region is not a simplex: BB-form on each of the {} simplices of a triangulation\n",
          bb.simplices.size());
    nlohmann::json simplices = nlohmann::json::array();
    for (const auto& sx : bb.simplices) simplices.push_back(simplex_coefficients(sx, degree, text));
    r["simplices"] = simplices;
    regions.push_back(r);
  }
  return {{{"degree", degree}, {"regions", regions}}, text};
}

int run_bbform(const Common& c, const std::string& region) {
  const BBFormOutput out = bbform_output(c, region);
  if (c.json)
    print_json(out.json);
  else
    fmt::print("{}", out.text);
  return 0;
}

}  // namespace boxgen::frontend
