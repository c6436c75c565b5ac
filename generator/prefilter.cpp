#include "generator/prefilter.h"

#include <algorithm>
#include <cctype>
#include <map>
#include <optional>
#include <set>

#include "generator/approximation_order.h"
#include "generator/error.h"
#include "generator/rational_linear_systems.h"
#include "generator/symmetry.h"
#include "support/fir_prefilter.hpp"

// The FIR solver's arithmetic on exact rationals: pivots by magnitude, zero is zero.
template <>
struct boxgen::support::FirArithmetic<boxgen::generator::Rational> {
  using Rational = boxgen::generator::Rational;
  static Rational magnitude(const Rational& x) { return cln::abs(x); }
  static bool negligible(const Rational& x, const Rational& /*scale*/) { return cln::zerop(x); }
  static Rational from_int(std::int64_t v) { return boxgen::generator::rational_from(v); }
};

namespace boxgen::generator {

namespace {

// ---- Exact truncated power series in w_1..w_n --------------------------------------------------
// 1/hat(M^c)(w) is a product, and hat(q)(w) a sum, of even functions of linear forms in w, so the
// only operation needed is "multiply by a linear form", done on dense coefficient vectors over
// all monomials of total degree < bound. Own code rather than GiNaC series: it stays exact and
// takes milliseconds for the presets.

class MonomialIndex {
 public:
  MonomialIndex(int n, int bound) : n_(n) {
    std::map<IntVec, int> position;
    IntVec e(n, 0);
    add_monomials(e, 0, bound - 1, position);
    raised_.assign(exponents_.size(), std::vector<int>(n, -1));
    for (size_t k = 0; k < exponents_.size(); ++k)
      for (int i = 0; i < n; ++i) {
        IntVec up = exponents_[k];
        ++up[i];
        if (auto it = position.find(up); it != position.end()) raised_[k][i] = it->second;
      }
  }
  int dimension() const { return n_; }
  size_t size() const { return exponents_.size(); }
  // Index of the monomial w^e * w_i, or -1 when its degree reaches the bound.
  int raised(size_t k, int i) const { return raised_[k][i]; }

 private:
  // All exponents with coordinates i.. summing to at most `budget`.
  void add_monomials(IntVec& e, int i, int budget, std::map<IntVec, int>& position) {
    if (budget < 0) return;
    if (i == n_) {
      position[e] = static_cast<int>(exponents_.size());
      exponents_.push_back(e);
      return;
    }
    for (int a = 0; a <= budget; ++a) {
      e[i] = a;
      add_monomials(e, i + 1, budget - a, position);
    }
    e[i] = 0;
  }

  int n_;
  std::vector<IntVec> exponents_;
  std::vector<std::vector<int>> raised_;
};

using Series = std::vector<Rational>;  // coefficients, indexed by a MonomialIndex

Series unit_series(const MonomialIndex& index) {
  Series s(index.size(), Rational(0));
  s[0] = 1;  // the zero exponent is enumerated first
  return s;
}

bool is_zero(const Series& s) {
  return std::all_of(s.begin(), s.end(), [](const Rational& c) { return cln::zerop(c); });
}

Series times_linear_form(const MonomialIndex& index, const Series& s, const RatVec& form) {
  Series out(s.size(), Rational(0));
  for (size_t k = 0; k < s.size(); ++k) {
    if (cln::zerop(s[k])) continue;
    for (int i = 0; i < index.dimension(); ++i) {
      const int target = index.raised(k, i);
      if (target >= 0 && !cln::zerop(form[i])) out[target] = out[target] + s[k] * form[i];
    }
  }
  return out;
}

// s * g(t) with t = form.w, for an even univariate series g(t) = sum_k g[k] t^(2k).
Series times_even_series(const MonomialIndex& index, const Series& s, const RatVec& form,
                         const RatVec& g) {
  Series out(s.size(), Rational(0)), power = s;
  for (size_t k = 0; k < g.size() && !is_zero(power); ++k) {
    for (size_t i = 0; i < out.size(); ++i) out[i] = out[i] + g[k] * power[i];
    power = times_linear_form(index, times_linear_form(index, power, form), form);
  }
  return out;
}

// Univariate even series in u = t^2, truncated to `terms` coefficients.
RatVec multiply(const RatVec& a, const RatVec& b) {
  RatVec out(a.size(), Rational(0));
  for (size_t i = 0; i < a.size(); ++i)
    for (size_t j = 0; i + j < out.size(); ++j) out[i + j] = out[i + j] + a[i] * b[j];
  return out;
}

RatVec cos_coefficients(int terms) {  // cos t = sum (-1)^k t^(2k) / (2k)!
  RatVec c(terms);
  Rational factorial = 1;
  for (int k = 0; k < terms; ++k) {
    if (k > 0) factorial = factorial * (2 * k - 1) * (2 * k);
    c[k] = (k % 2 == 0 ? Rational(1) : Rational(-1)) / factorial;
  }
  return c;
}

RatVec reciprocal_sinc_coefficients(int terms) {
  // sinc t = sum (-1)^k t^(2k) / (2k+1)!; its reciprocal b solves sum_i a_i b_(k-i) = [k = 0].
  RatVec a(terms), b(terms, Rational(0));
  Rational factorial = 1;
  for (int k = 0; k < terms; ++k) {
    if (k > 0) factorial = factorial * (2 * k) * (2 * k + 1);
    a[k] = (k % 2 == 0 ? Rational(1) : Rational(-1)) / factorial;
  }
  b[0] = 1;
  for (int k = 1; k < terms; ++k)
    for (int i = 1; i <= k; ++i) b[k] = b[k] - a[i] * b[k - i];
  return b;
}

// ---- The order conditions -----------------------------------------------------------------------

// hat(q) hat(M^c) = 1 + O(|w|^order) as linear equations on the weights of parameter groups
// (each group of lattice points shares one weight).
class OrderConditions {
 public:
  OrderConditions(const IntColumns& directions, int n, int order)
      : index_(n, order), terms_(order / 2 + 1), target_(unit_series(index_)) {
    // 1/hat(M^c)(w) = prod_xi 1/sinc(xi.w/2); equal directions up to sign share one power of
    // 1/sinc.
    std::map<IntVec, int> multiplicity;
    for (const auto& xi : directions) ++multiplicity[sign_canonical(xi)];
    const RatVec reciprocal = reciprocal_sinc_coefficients(terms_);
    for (const auto& [xi, count] : multiplicity) {
      RatVec power(terms_, Rational(0));
      power[0] = 1;
      for (int c = 0; c < count; ++c) power = multiply(power, reciprocal);
      RatVec half(n);
      for (int i = 0; i < n; ++i) half[i] = rational_from(xi[i]) / 2;
      target_ = times_even_series(index_, target_, half, power);
    }
  }

  // Weights per group solving the conditions, or nullopt.
  std::optional<LinearSolution> fit(const std::vector<std::vector<IntVec>>& groups) const {
    return solve_exactly(rows(groups), static_cast<int>(groups.size()));
  }

  // The conditions as augmented rows [A | b] on the weights of the groups.
  std::vector<RatVec> rows(const std::vector<std::vector<IntVec>>& groups) const {
    // hat(q)(w) = sum_j q_j cos(w.j) for symmetric q (every group is closed under j -> -j).
    const RatVec cosine = cos_coefficients(terms_);
    std::vector<Series> columns;
    for (const auto& group : groups) {
      Series column(index_.size(), Rational(0));
      for (const auto& j : group) {
        const Series c = times_even_series(index_, unit_series(index_), to_ratvec(j), cosine);
        for (size_t k = 0; k < column.size(); ++k) column[k] = column[k] + c[k];
      }
      columns.push_back(std::move(column));
    }
    const int unknowns = static_cast<int>(groups.size());
    std::vector<RatVec> out;
    for (size_t k = 0; k < index_.size(); ++k) {
      RatVec row(unknowns + 1);
      bool any = !cln::zerop(target_[k]);
      for (int p = 0; p < unknowns; ++p) {
        row[p] = columns[p][k];
        any = any || !cln::zerop(row[p]);
      }
      row[unknowns] = target_[k];
      if (any) out.push_back(std::move(row));
    }
    return out;
  }

 private:
  MonomialIndex index_;
  int terms_;  // even univariate terms needed below the degree bound
  Series target_;
};

// ---- Parametrisations ---------------------------------------------------------------------------

struct ShellPoint {
  int shell;
  IntVec offset;
};

struct Parametrisation {
  std::string name;
  std::vector<std::string> labels;          // one per parameter, for notes
  std::vector<std::vector<IntVec>> groups;  // points sharing each parameter
  std::vector<int> parameter_of_point;      // parallel to the requested points
};

std::string point_text(const IntVec& p) {
  std::string s = "(";
  for (size_t i = 0; i < p.size(); ++i) {
    if (i) s += ',';
    s += std::to_string(p[i]);
  }
  return s + ")";
}

std::string shells_text(const std::vector<int>& shells) {
  std::string s;
  for (size_t i = 0; i < shells.size(); ++i) {
    if (i) s += ',';
    s += std::to_string(shells[i]);
  }
  return s;
}

// Builds a parametrisation from a key per point: points with equal keys share a weight.
Parametrisation group_by(std::string name, const std::vector<ShellPoint>& points,
                         const std::vector<std::string>& key_of_point) {
  Parametrisation par{std::move(name), {}, {}, {}};
  std::map<std::string, int> parameter;
  for (size_t i = 0; i < points.size(); ++i) {
    auto [it, added] = parameter.emplace(key_of_point[i], static_cast<int>(par.labels.size()));
    if (added) {
      par.labels.push_back(key_of_point[i]);
      par.groups.emplace_back();
    }
    par.groups[it->second].push_back(points[i].offset);
    par.parameter_of_point.push_back(it->second);
  }
  return par;
}

Parametrisation common_weight(const std::vector<ShellPoint>& points) {
  std::vector<std::string> keys;
  for (const auto& p : points)
    keys.push_back(p.shell == 0 ? "the origin" : "the common neighbour weight");
  return group_by("common", points, keys);
}

Parametrisation weight_per_shell(const std::vector<ShellPoint>& points) {
  std::vector<std::string> keys;
  for (const auto& p : points) keys.push_back("shell " + std::to_string(p.shell));
  return group_by("per_shell", points, keys);
}

// Signed permutations preserve the norm, so orbits never leave a shell.
Parametrisation weight_per_orbit(const std::vector<ShellPoint>& points,
                                 const std::vector<SignedPermutation>& group) {
  std::map<IntVec, std::string> orbit_of;
  for (const auto& p : points) {  // points are sorted: the first of an orbit names it
    if (orbit_of.count(p.offset)) continue;
    const std::string name =
        "shell " + std::to_string(p.shell) + " orbit of " + point_text(p.offset);
    for (const auto& g : group) orbit_of[g.apply(p.offset)] = name;
  }
  std::vector<std::string> keys;
  for (const auto& p : points) keys.push_back(orbit_of.at(p.offset));
  return group_by("per_orbit", points, keys);
}

std::vector<ShellPoint> points_of(const std::vector<std::vector<IntVec>>& all_shells,
                                  const std::vector<int>& shells) {
  std::vector<ShellPoint> points;
  for (int s : shells) {
    std::vector<IntVec> offsets = all_shells[s];
    std::sort(offsets.begin(), offsets.end());
    for (auto& o : offsets) points.push_back({s, std::move(o)});
  }
  return points;
}

void validate_shells(const std::vector<int>& shells) {
  if (shells.empty()) fail_input("--shells: expected a list of shell indices such as 0,1,2");
  std::set<int> seen;
  for (int s : shells) {
    if (s < 0 || s > kMaxPrefilterShell)
      fail_input("--shells: shell " + std::to_string(s) + " is out of range (shells 0 to " +
                 std::to_string(kMaxPrefilterShell) + ")");
    if (!seen.insert(s).second)
      fail_input("--shells: shell " + std::to_string(s) + " is listed twice");
  }
  if (!seen.count(0)) fail_input("--shells: shell 0 (the origin) is required, e.g. --shells 0,1");
}

// The error for an unsolvable request: the best order these shells reach (per orbit is the most
// general parametrisation, so its failure is final) and the fewest leading shells that suffice.
[[noreturn]] void fail_unsupported(const BoxSplineSpec& spec,
                                   const std::vector<std::vector<IntVec>>& all_shells,
                                   const std::vector<int>& shells,
                                   const std::vector<SignedPermutation>& group,
                                   const OrderConditions& conditions, int order) {
  const auto points = points_of(all_shells, shells);
  int reached = 1;
  for (int r = order - 1; r >= 1; --r)
    if (OrderConditions(spec.directions, spec.dimension(), r)
            .fit(weight_per_orbit(points, group).groups)) {
      reached = r;
      break;
    }
  std::string hint = "not even --shells 0,...,";
  hint += std::to_string(kMaxPrefilterShell);
  hint += " reaches it";
  for (int k = 1; k <= kMaxPrefilterShell; ++k) {
    std::vector<int> leading(k + 1);
    for (int s = 0; s <= k; ++s) leading[s] = s;
    if (conditions.fit(weight_per_orbit(points_of(all_shells, leading), group).groups)) {
      hint = "--shells " + shells_text(leading) + " reaches it";
      break;
    }
  }
  fail_input("no prefilter of approximation order " + std::to_string(order) + " for " + spec.name +
             " is supported on shells " + shells_text(shells) + " (only order " +
             std::to_string(reached) + " is reachable there; " + hint + ")");
}

}  // namespace

std::vector<int> parse_shells(std::string_view text) {
  std::vector<int> shells;
  size_t start = 0;
  for (;;) {
    const size_t comma = text.find(',', start);
    std::string_view item = text.substr(
        start, comma == std::string_view::npos ? std::string_view::npos : comma - start);
    while (!item.empty() && std::isspace(static_cast<unsigned char>(item.front())))
      item.remove_prefix(1);
    while (!item.empty() && std::isspace(static_cast<unsigned char>(item.back())))
      item.remove_suffix(1);
    const bool digits =
        !item.empty() && item.size() <= 2 && std::all_of(item.begin(), item.end(), [](char c) {
          return std::isdigit(static_cast<unsigned char>(c));
        });
    if (!digits || std::stoi(std::string(item)) > kMaxPrefilterShell)
      fail_input("--shells: '" + std::string(item) + "' is not a shell index (expected 0 to " +
                 std::to_string(kMaxPrefilterShell) + ", as in --shells 0,1,2)");
    shells.push_back(std::stoi(std::string(item)));
    if (comma == std::string_view::npos) break;
    start = comma + 1;
  }
  validate_shells(shells);
  std::sort(shells.begin(), shells.end());
  return shells;
}

Prefilter derive_prefilter(const BoxSplineSpec& spec, const std::vector<int>& requested) {
  validate_shells(requested);
  std::vector<int> shells = requested;
  std::sort(shells.begin(), shells.end());

  const int n = spec.dimension();
  const int order = approximation_order(spec.directions, n);
  if (order == 0)
    fail_input("the directions of " + spec.name + " do not span R^" + std::to_string(n));

  const auto all_shells = spec.lattice.shells(kMaxPrefilterShell + 1);
  const auto points = points_of(all_shells, shells);
  const auto group = symmetry_group(spec);
  const OrderConditions conditions(spec.directions, n, order);

  std::vector<Parametrisation> candidates{common_weight(points)};
  // A finer parametrisation that induces the same partition would give the same system: skip it.
  for (auto finer : {weight_per_shell(points), weight_per_orbit(points, group)})
    if (finer.groups.size() > candidates.back().groups.size())
      candidates.push_back(std::move(finer));

  for (const auto& par : candidates) {
    const auto solution = conditions.fit(par.groups);
    if (!solution) continue;
    Prefilter q{order, shells, par.name, "", {}};
    if (!solution->free_columns.empty()) {
      q.note = "the weights are not unique on these shells; set to zero:";
      for (size_t i = 0; i < solution->free_columns.size(); ++i) {
        q.note += i ? "; " : " ";
        q.note += par.labels[solution->free_columns[i]];
      }
    }
    for (size_t i = 0; i < points.size(); ++i)
      q.weights.push_back({points[i].offset, solution->values[par.parameter_of_point[i]]});
    return q;
  }
  fail_unsupported(spec, all_shells, shells, group, conditions, order);
}

std::vector<int> quasi_interpolation_shells(const BoxSplineSpec& spec, int which) {
  const int n = spec.dimension();
  const int order = approximation_order(spec.directions, n);
  if (order == 0)
    fail_input("the directions of " + spec.name + " do not span R^" + std::to_string(n));
  const auto all_shells = spec.lattice.shells(kMaxPrefilterShell + 1);
  const auto group = symmetry_group(spec);
  const OrderConditions conditions(spec.directions, n, order);
  // One weight per orbit is the most general parametrisation: where it fails, all fail.
  for (int k = 0; k + (which == 2 ? 1 : 0) <= kMaxPrefilterShell; ++k) {
    std::vector<int> leading(k + 1);
    for (int s = 0; s <= k; ++s) leading[s] = s;
    if (conditions.fit(weight_per_orbit(points_of(all_shells, leading), group).groups)) {
      if (which == 2) leading.push_back(k + 1);
      return leading;
    }
  }
  fail_input("no prefilter q" + std::to_string(which) + " of approximation order " +
             std::to_string(order) + " for " + spec.name + ": none exists on the shells 0 to " +
             std::to_string(kMaxPrefilterShell));
}

Prefilter derive_fir_prefilter(const BoxSplineSpec& spec, int last_shell,
                               const std::vector<LatticeSample>& samples) {
  if (last_shell < 0 || last_shell > kMaxPrefilterShell)
    fail_input("qfir:" + std::to_string(last_shell) + ": the last shell must be 0 to " +
               std::to_string(kMaxPrefilterShell));
  const int n = spec.dimension();
  const int order = approximation_order(spec.directions, n);
  std::vector<int> shells(static_cast<std::size_t>(last_shell) + 1);
  for (int s = 0; s <= last_shell; ++s) shells[static_cast<std::size_t>(s)] = s;
  const auto all_shells = spec.lattice.shells(kMaxPrefilterShell + 1);
  const auto points = points_of(all_shells, shells);
  const Parametrisation par = weight_per_orbit(points, symmetry_group(spec));

  support::FirPrefilterProblem<Rational> problem;
  problem.order = order;
  for (const auto& s : samples) problem.samples.push_back({s.point, s.value});
  problem.groups = par.groups;
  problem.smoothing = support::kQfirSmoothing;
  const auto weights = support::solve_fir_prefilter(problem);
  if (!weights) {
    const int least = quasi_interpolation_shells(spec, 1).back();
    fail_input("qfir:" + std::to_string(last_shell) + ": no prefilter of approximation order " +
               std::to_string(order) + " for " + spec.name + " lies on shells 0 to " +
               std::to_string(last_shell) + " (the least is qfir:" + std::to_string(least) + ")");
  }
  Prefilter q{order, shells, "fir", "", {}};
  for (size_t i = 0; i < points.size(); ++i)
    q.weights.push_back({points[i].offset, (*weights)[par.parameter_of_point[i]]});
  return q;
}

PrefilterFamily prefilter_family(const BoxSplineSpec& spec, const std::vector<int>& requested) {
  // derive_prefilter validates the shells and names the order they reach when there is none.
  const Prefilter solvable = derive_prefilter(spec, requested);
  const int n = spec.dimension();
  const auto all_shells = spec.lattice.shells(kMaxPrefilterShell + 1);
  const auto points = points_of(all_shells, solvable.shells);
  const Parametrisation par = weight_per_orbit(points, symmetry_group(spec));
  const OrderConditions conditions(spec.directions, n, solvable.order);
  const int unknowns = static_cast<int>(par.groups.size());
  std::vector<RatVec> rows = conditions.rows(par.groups);
  const auto solution = solve_exactly(rows, unknowns);
  if (!solution) fail_input("no prefilter of full order for " + spec.name + " on these shells");
  for (auto& row : rows) row.pop_back();  // the homogeneous system
  PrefilterFamily family{solvable.order,
                         solvable.shells,
                         par.groups,
                         par.labels,
                         solution->values,
                         null_space(std::move(rows), unknowns),
                         solution->free_columns,
                         {},
                         par.parameter_of_point};
  for (const auto& p : points) family.points.push_back(p.offset);
  return family;
}

Prefilter family_member(const PrefilterFamily& family, const RatVec& t) {
  RatVec weight = family.particular;
  for (size_t i = 0; i < family.basis.size(); ++i)
    for (size_t g = 0; g < weight.size(); ++g) weight[g] = weight[g] + t[i] * family.basis[i][g];
  Prefilter q{family.order, family.shells, "per_orbit", "", {}};
  for (size_t i = 0; i < family.points.size(); ++i)
    q.weights.push_back({family.points[i], weight[family.orbit_of_point[i]]});
  return q;
}

Prefilter named_prefilter(const BoxSplineSpec& spec, std::string_view name) {
  if (name == "q1" || name == "q2") {
    const int which = name == "q1" ? 1 : 2;
    return derive_prefilter(spec, quasi_interpolation_shells(spec, which));
  }
  if (name.starts_with("qfir:")) {
    const std::string_view k = name.substr(5);
    const bool digit = k.size() == 1 && std::isdigit(static_cast<unsigned char>(k.front()));
    if (!digit || k.front() - '0' > kMaxPrefilterShell)
      fail_input("prefilter '" + std::string(name.substr(0, 40)) +
                 "': K in qfir:K must be a shell index 0 to " + std::to_string(kMaxPrefilterShell));
    return derive_fir_prefilter(spec, k.front() - '0', lattice_samples(spec));
  }
  fail_input("unknown prefilter '" + std::string(name.substr(0, 40)) + "': expected " +
             kPrefilterNames);
}

}  // namespace boxgen::generator
