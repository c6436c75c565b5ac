#include "generator/derivation.h"

#include <chrono>
#include <sstream>

#include "generator/error.h"

namespace boxgen::generator {

namespace {

double seconds_since(std::chrono::steady_clock::time_point t) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t).count();
}

std::string integer_string(const Integer& i) { return to_string(Rational(i)); }

nlohmann::json int_rows(const IntColumns& cols) {
  nlohmann::json rows = nlohmann::json::array();
  for (const auto& c : cols) rows.push_back(c);
  return rows;
}

}  // namespace

Derivation derive(const BoxSplineSpec& spec, const DerivationOptions& options) {
  const auto start = std::chrono::steady_clock::now();
  const ProgressFn& progress = options.progress;
  auto stage = [&](const char* what) {
    if (progress) progress(what, 0, 0);
  };
  Derivation a{spec,
               box_spline_properties(spec),
               derive_piecewise(
                   spec, DerivationMethod::TruncatedPower, progress,
                   {options.max_seconds, options.max_bytes, options.verify, options.full_checks}),
               {},
               0,
               {},
               0};
  stage("merging pieces");
  a.pieces = count_pieces(a.form);
  stage("spline regions");
  a.structure = spline_structure(a.form);
  if (options.verify) {
    const auto check_start = std::chrono::steady_clock::now();
    a.checks.full = options.full_checks;
    // Symmetry first: the default checks then let the second derivation confirm one cell per
    // orbit, since every other cell's piece is checked to be an image of its representative's
    // (docs/design.md §5); the full checks confirm every cell.
    stage("checking symmetry");
    check_symmetry(a.form, a.structure.group);
    a.checks.symmetric = true;
    const CellOrbits orbits =
        options.full_checks ? CellOrbits{} : cell_orbits(a.form, a.structure.group);
    const std::vector<int>* cells = options.full_checks ? nullptr : &orbits.representatives;
    const std::vector<Poly> other =
        rederive(a.form, DerivationMethod::DirectionalIntegration, progress, cells);
    for (size_t i = 0; i < other.size(); ++i)
      if (other[i] != a.form.polys[cells ? static_cast<size_t>((*cells)[i]) : i])
        fail_internal(
            "the two derivations disagree on a cell (truncated power vs directional integration)");
    a.checks.methods_agree = true;
    const int order = a.properties.approximation_order - 1;
    if (options.full_checks) {
      stage("checking the integral");
      if (total_integral(a.form) != 1) fail_internal("the derived pieces do not integrate to 1");
      stage("checking continuity");
      a.checks.continuity = check_continuity(a.form, order);
    } else {
      stage("checking the integral");
      if (total_integral(a.form, orbits) != 1)
        fail_internal("the derived pieces do not integrate to 1");
      stage("checking continuity");
      a.checks.continuity = check_continuity(a.form, order, orbits.representatives);
    }
    a.checks.integral_is_one = true;
    stage("checking the partition of unity");
    check_partition_of_unity(a.form, a.structure, options.full_checks);
    a.checks.partition_of_unity = true;
    if (!a.checks.continuity.sharp)
      fail_internal("continuity is higher than C^(rho-2) on every face: rho is wrong");
    a.checks.seconds = seconds_since(check_start);
  }
  a.derivation_seconds = seconds_since(start);
  return a;
}

nlohmann::json to_json(const Derivation& a) {
  const auto& p = a.properties;
  nlohmann::json j;
  j["spec"] = a.spec.name;
  j["dimension"] = a.spec.dimension();
  j["directions"] = int_rows(a.spec.directions);
  j["lattice"] = int_rows(a.spec.lattice.generator_rows());
  j["lattice_name"] = a.spec.lattice.name();
  j["degree"] = p.degree;
  j["continuity"] = p.continuity;
  j["approximation_order"] = p.approximation_order;
  j["support_volume"] = integer_string(p.support_volume);
  j["stencil_size"] = cln::cl_I_to_long(p.stencil_size);
  j["stencil_size_min"] = a.structure.stencil_min;
  j["stencil_size_max"] = a.structure.stencil_max;
  j["linearly_independent"] = p.linearly_independent;
  j["pieces"] = a.pieces;
  j["regions_per_fundamental_region"] = a.structure.regions.size();
  j["symmetry_group_order"] = a.structure.group.size();
  j["regions_up_to_symmetry"] = a.structure.references.size();
  j["derivation_seconds"] = a.derivation_seconds;
  nlohmann::json checks;
  checks["verified"] = a.checks.methods_agree;
  if (a.checks.methods_agree) {
    checks["methods_agree"] = a.checks.methods_agree;
    checks["integral_is_one"] = a.checks.integral_is_one;
    checks["symmetric"] = a.checks.symmetric;
    checks["partition_of_unity"] = a.checks.partition_of_unity;
    checks["continuity_faces_checked"] = a.checks.continuity.faces_checked;
    checks["continuity_is_sharp"] = a.checks.continuity.sharp;
    checks["mode"] = a.checks.full ? "full" : "default";
    checks["seconds"] = a.checks.seconds;
  }
  j["checks"] = checks;
  return j;
}

std::string to_table(const Derivation& a) {
  const auto& p = a.properties;
  std::ostringstream os;
  auto row = [&](const std::string& key, const std::string& value) {
    os << "  " << key << std::string(key.size() < 32 ? 32 - key.size() : 1, ' ') << value << '\n';
  };
  os << "box spline " << a.spec.name << " on the " << a.spec.lattice.name() << " lattice\n";
  row("directions", a.spec.directions_text());
  row("dimension", std::to_string(a.spec.dimension()));
  row("degree", std::to_string(p.degree));
  row("continuity", "C^" + std::to_string(p.continuity));
  row("approximation order", std::to_string(p.approximation_order));
  row("support volume", integer_string(p.support_volume));
  row("stencil size", integer_string(p.stencil_size) +
                          " (per region: " + std::to_string(a.structure.stencil_min) + ".." +
                          std::to_string(a.structure.stencil_max) + ")");
  row("linearly independent shifts", p.linearly_independent ? "yes" : "no");
  row("polynomial pieces of M", std::to_string(a.pieces));
  row("regions per fundamental region", std::to_string(a.structure.regions.size()));
  row("symmetry group order", std::to_string(a.structure.group.size()));
  row("regions up to symmetry", std::to_string(a.structure.references.size()));
  row("exact checks", a.checks.methods_agree
                          ? "passed (two derivations agree, integral 1, symmetry, "
                            "partition of unity, C^" +
                                std::to_string(p.continuity) + " on " +
                                std::to_string(a.checks.continuity.faces_checked) + " faces" +
                                (a.checks.full ? "; full)" : "; one cell per symmetry orbit)")
                          : "skipped");
  std::ostringstream t;
  t.precision(3);
  t << std::fixed << a.derivation_seconds << " s";
  row("derivation time", t.str());
  return os.str();
}

}  // namespace boxgen::generator
