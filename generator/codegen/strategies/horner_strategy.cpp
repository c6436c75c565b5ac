#include "generator/codegen/strategies/horner_strategy.h"

#include <fmt/format.h>

#include <algorithm>
#include <map>
#include <tuple>
#include <utility>

#include "generator/embedded_templates.h"

namespace boxgen::generator::strategies {

namespace {

// The nested Horner form of sum_e c_e y^e and of its partial derivatives, built so that the
// derivatives differentiate the Horner form itself: with P(prefix) the polynomial of the
// monomials whose exponents of y_0..y_(k-1) are the prefix (in y_k..y_(n-1)),
//   P(prefix) = sum_a y_k^a P(prefix, a), so
//   d^D P(prefix) = sum_(a >= D_k) a!/(a - D_k)! y_k^(a - D_k) d^(D without k) P(prefix, a),
// in Horner form in y_k. The inner d^D' P(prefix, a) are memoised: d/dy_0 reuses the value's
// inner polynomials, d^2/dy_0 dy_1 the gradient's d/dy_1 of them, and so on.
class HornerForm {
 public:
  HornerForm(Build& b, const std::map<Exponent, NodeId>& coefficients, std::vector<NodeId> vars)
      : b_(b), c_(coefficients), vars_(std::move(vars)), n_(static_cast<int>(vars_.size())) {}

  NodeId derivative(const Exponent& d) { return partial(Exponent{0, 0, 0}, 0, d); }

 private:
  // d^D P(prefix) where prefix fixes y_0..y_(k-1) and D_i = 0 for i < k.
  NodeId partial(const Exponent& prefix, int k, const Exponent& d) {
    if (k >= n_ || k >= 3) {  // (k < 3 spelled out for the compiler's bounds analysis)
      const auto it = c_.find(prefix);
      return it == c_.end() ? b_.zero() : it->second;
    }
    const auto key = std::make_tuple(prefix, k, d);
    const auto memo = memo_.find(key);
    if (memo != memo_.end()) return memo->second;
    int top = -1;  // the highest power of y_k under the prefix
    for (const auto& [e, node] : c_)
      if (std::equal(e.begin(), e.begin() + k, prefix.begin())) top = std::max(top, e[k]);
    Exponent rest = d;
    rest[k] = 0;
    NodeId acc = b_.zero();
    for (int a = top; a >= d[k]; --a) {
      Exponent next = prefix;
      next[k] = a;
      long factor = 1;
      for (int j = 0; j < d[k]; ++j) factor *= a - j;
      const NodeId term = generator::scaled(b_.g, Rational(factor), partial(next, k + 1, rest));
      acc = a == top ? term : generator::sum(b_.g, term, generator::product(b_.g, vars_[k], acc));
    }
    memo_.emplace(key, acc);
    return acc;
  }

  Build& b_;
  const std::map<Exponent, NodeId>& c_;
  std::vector<NodeId> vars_;
  int n_;
  std::map<std::tuple<Exponent, int, Exponent>, NodeId> memo_;
};

}  // namespace

HornerNodes horner_nodes(Build& b, const std::vector<Poly>& basis, int n, int degree,
                         const std::vector<NodeId>& vars) {
  const Coefficients c = coefficients(b, basis, n, degree, true);
  HornerForm form(b, c.node, vars);
  HornerNodes h{form.derivative({0, 0, 0}), {}, c.node.size(), c.shared_sums};
  for (const auto& e : derivative_indices(n, 2)) h.derivatives.push_back(form.derivative(e));
  return h;
}

std::optional<OrbitCode> horner_code(const ReferenceRegion& ref, int orbit, int n, int degree) {
  Build b;
  const HornerNodes h = horner_nodes(b, ref.basis, n, degree, b.coordinates(n));
  return finish(std::move(b), EmissionStrategy::Horner, h.value, h.derivatives, n,
                {templates::orbit_horner,
                 {{"orbit", std::to_string(orbit)},
                  {"vertices", orbit_vertices(ref)},
                  {"monomials", std::to_string(h.monomials)},
                  {"shared", std::to_string(h.shared_sums)},
                  {"stencil", std::to_string(ref.stencil.size())}}});
}

}  // namespace boxgen::generator::strategies
