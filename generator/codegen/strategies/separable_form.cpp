#include "generator/codegen/strategies/separable_form.h"

#include <algorithm>
#include <map>

namespace boxgen::generator {

namespace {

// p = scale * prod_i factors[i](x_i), each factor with leading coefficient 1.
struct RankOne {
  Rational scale;
  std::vector<UnivariatePoly> factors;
};

void trim(UnivariatePoly& f) {
  while (f.size() > 1 && cln::zerop(f.back())) f.pop_back();
}

// The coefficient tensor of p has rank one exactly when p is a product of univariate factors:
// then every coefficient is prod_i f_i[e_i] / c0^(n-1), f_i the fibres through a nonzero c0.
std::optional<RankOne> rank_one(const Poly& p, int n) {
  const int cap = p.capacity();
  const auto& exps = monomial_exponents(n, cap);
  const auto& c = p.coefficients();
  std::size_t pivot = 0;
  while (pivot < c.size() && cln::zerop(c[pivot])) ++pivot;
  if (pivot == c.size()) return std::nullopt;
  const Exponent e0 = exps[pivot];
  const Rational c0 = c[pivot];
  auto coefficient = [&](const Exponent& e) {
    int total = 0;
    for (int i = 0; i < n; ++i) total += e[i];
    return total <= cap ? p.coefficient(e) : Rational(0);
  };
  std::vector<UnivariatePoly> f(n, UnivariatePoly(cap + 1, 0));
  for (int i = 0; i < n; ++i)
    for (int a = 0; a <= cap; ++a) {
      Exponent e = e0;
      e[i] = a;
      f[i][a] = coefficient(e);
    }
  Rational c0_power = 1;
  for (int i = 1; i < n; ++i) c0_power = c0_power * c0;
  Exponent e{0, 0, 0};
  for (;;) {  // every exponent in [0, cap]^n
    Rational product = 1;
    for (int i = 0; i < n; ++i) product = product * f[i][e[i]];
    if (coefficient(e) * c0_power != product) return std::nullopt;
    int i = 0;
    while (i < n && e[i] == cap) e[i++] = 0;
    if (i == n) break;
    ++e[i];
  }
  RankOne out{Rational(1) / c0_power, {}};
  for (auto& fi : f) {
    trim(fi);
    const Rational lead = fi.back();
    for (auto& x : fi) x = x / lead;
    out.scale = out.scale * lead;
    out.factors.push_back(fi);
  }
  return out;
}

Poly univariate_as_poly(const UnivariatePoly& f, int axis, int n) {
  Poly p(n, static_cast<int>(f.size()) - 1);
  for (std::size_t a = 0; a < f.size(); ++a) {
    Exponent e{0, 0, 0};
    e[axis] = static_cast<int>(a);
    p.set_coefficient(e, f[a]);
  }
  return p;
}

std::optional<TensorGrid> grid_of(const ReferenceRegion& ref, const std::vector<RankOne>& factored,
                                  const std::vector<int>& members, int n) {
  TensorGrid grid;
  std::vector<std::vector<std::int64_t>> values(n);
  for (int i = 0; i < n; ++i) {
    for (int k : members) values[i].push_back(ref.stencil[k][i]);
    std::sort(values[i].begin(), values[i].end());
    values[i].erase(std::unique(values[i].begin(), values[i].end()), values[i].end());
    grid.sizes.push_back(static_cast<int>(values[i].size()));
  }
  std::size_t cells = 1;
  for (int s : grid.sizes) cells *= static_cast<std::size_t>(s);
  if (cells != members.size()) return std::nullopt;  // not a full grid
  grid.stencil.assign(cells, -1);
  std::vector<std::vector<int>> position(members.size(), std::vector<int>(n));
  for (std::size_t m = 0; m < members.size(); ++m) {
    int flat = 0;
    for (int i = n - 1; i >= 0; --i) {
      const auto& v = values[i];
      position[m][i] = static_cast<int>(
          std::lower_bound(v.begin(), v.end(), ref.stencil[members[m]][i]) - v.begin());
      flat = flat * grid.sizes[i] + position[m][i];
    }
    grid.stencil[flat] = members[m];
  }
  // Each axis factor may depend only on its own coordinate of j.
  grid.weights.assign(n, {});
  for (int i = 0; i < n; ++i) grid.weights[i].assign(grid.sizes[i], {});
  for (std::size_t m = 0; m < members.size(); ++m)
    for (int i = 0; i < n; ++i) {
      auto& w = grid.weights[i][position[m][i]];
      const auto& f = factored[members[m]].factors[i];
      if (w.empty())
        w = f;
      else if (w != f)
        return std::nullopt;
    }
  // The scales must factor as C prod_i alpha_i(a_i): read them off the axes through grid point 0.
  auto scale_at = [&](const std::vector<int>& a) {
    int flat = 0;
    for (int i = n - 1; i >= 0; --i) flat = flat * grid.sizes[i] + a[i];
    return factored[grid.stencil[flat]].scale;
  };
  const Rational c = scale_at(std::vector<int>(n, 0));
  std::vector<std::vector<Rational>> alpha(n);
  for (int i = 0; i < n; ++i)
    for (int a = 0; a < grid.sizes[i]; ++a) {
      std::vector<int> at(n, 0);
      at[i] = a;
      alpha[i].push_back(scale_at(at) / c);
    }
  for (std::size_t m = 0; m < members.size(); ++m) {
    Rational product = c;
    for (int i = 0; i < n; ++i) product = product * alpha[i][position[m][i]];
    if (product != factored[members[m]].scale) return std::nullopt;
  }
  for (int i = 0; i < n; ++i)
    for (int a = 0; a < grid.sizes[i]; ++a)
      for (auto& x : grid.weights[i][a]) x = x * alpha[i][a] * (i == n - 1 ? c : Rational(1));
  return grid;
}

}  // namespace

std::optional<std::vector<TensorGrid>> separable_form(const ReferenceRegion& ref, int n) {
  std::vector<RankOne> factored;
  for (const auto& p : ref.basis) {
    auto f = rank_one(p, n);
    if (!f) return std::nullopt;
    factored.push_back(*f);
  }
  // One grid for the whole stencil (Cartesian lattices), else one per parity class of j (the
  // cosets of BCC and FCC in the doubled integer lattice).
  std::vector<int> all(ref.stencil.size());
  for (std::size_t k = 0; k < all.size(); ++k) all[k] = static_cast<int>(k);
  std::vector<std::vector<int>> partitions[2];
  partitions[0] = {all};
  std::map<std::vector<int>, std::vector<int>> by_parity;
  for (int k : all) {
    std::vector<int> parity;
    for (int i = 0; i < n; ++i) parity.push_back(static_cast<int>(ref.stencil[k][i] & 1));
    by_parity[parity].push_back(k);
  }
  for (auto& [parity, members] : by_parity) partitions[1].push_back(members);
  for (const auto& partition : partitions) {
    std::vector<TensorGrid> grids;
    for (const auto& members : partition) {
      auto g = grid_of(ref, factored, members, n);
      if (!g) break;
      grids.push_back(std::move(*g));
    }
    if (grids.size() != partition.size()) continue;
    // The exact identity, term by term.
    for (const auto& g : grids)
      for (std::size_t flat = 0; flat < g.stencil.size(); ++flat) {
        Poly product = Poly::constant(n, 1);
        std::size_t rest = flat;
        for (int i = 0; i < n; ++i) {
          product = product * univariate_as_poly(g.weights[i][rest % g.sizes[i]], i, n);
          rest /= g.sizes[i];
        }
        if (!(product - ref.basis[g.stencil[flat]]).is_zero()) return std::nullopt;
      }
    return grids;
  }
  return std::nullopt;
}

}  // namespace boxgen::generator
