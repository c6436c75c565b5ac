#include "generator/codegen/strategies/shifted_strategy.h"

#include <fmt/format.h>

#include <algorithm>
#include <utility>
#include <vector>

#include "generator/codegen/code_text.h"
#include "generator/codegen/strategies/horner_strategy.h"
#include "generator/embedded_templates.h"

namespace boxgen::generator::strategies {

namespace {

// Candidate origins of the shifted form, exact points of the reference region: its centroid, its
// vertices, and the midpoints of every pair of vertices (edges, and diagonals of faces or of the
// region), without repeats and without 0 itself (monomials about 0 are the Horner form).
std::vector<RatVec> shift_origins(const ReferenceRegion& ref, int n) {
  std::vector<RatVec> out;
  auto add = [&](const RatVec& p) {
    const bool zero =
        std::all_of(p.begin(), p.end(), [](const Rational& r) { return cln::zerop(r); });
    if (!zero && std::find(out.begin(), out.end(), p) == out.end()) out.push_back(p);
  };
  RatVec centroid(n, Rational(0));
  for (const auto& v : ref.vertices)
    for (int i = 0; i < n; ++i)
      centroid[i] = centroid[i] + v[i] / Rational(static_cast<long>(ref.vertices.size()));
  add(centroid);
  for (const auto& v : ref.vertices) add(v);
  for (std::size_t a = 0; a < ref.vertices.size(); ++a)
    for (std::size_t b = a + 1; b < ref.vertices.size(); ++b) {
      RatVec mid(n);
      for (int i = 0; i < n; ++i) mid[i] = (ref.vertices[a][i] + ref.vertices[b][i]) / Rational(2);
      add(mid);
    }
  return out;
}

// The Horner form in y = x - o, the stencil polynomials rewritten exactly about o and
// y_i = x[i] - o_i computed once (named y<i>) where o_i != 0.
OrbitCode shifted_form(const ReferenceRegion& ref, const RatVec& origin, int orbit,
                       std::size_t candidates, int n, int degree) {
  Build b;
  RatVec minus(n);
  for (int i = 0; i < n; ++i) minus[i] = -origin[i];
  std::vector<Poly> basis;
  for (const auto& p : ref.basis) basis.push_back(p.translated(minus));  // q(y) = p(y + o)
  std::vector<NodeId> vars = b.coordinates(n);
  for (int i = 0; i < n; ++i) {
    vars[i] = generator::sum(b.g, vars[i], b.g.constant(-origin[i]));
    b.name(vars[i], fmt::format("y{}", i));
  }
  const HornerNodes h = horner_nodes(b, basis, n, degree, vars);
  OrbitCode code = finish(std::move(b), EmissionStrategy::Shifted, h.value, h.derivatives, n,
                          {templates::orbit_shifted,
                           {{"orbit", std::to_string(orbit)},
                            {"vertices", orbit_vertices(ref)},
                            {"origin", code::vertex_text(origin)},
                            {"candidates", std::to_string(candidates)},
                            {"monomials", std::to_string(h.monomials)},
                            {"shared", std::to_string(h.shared_sums)},
                            {"stencil", std::to_string(ref.stencil.size())}}});
  code.form = "about " + code::vertex_text(origin);
  return code;
}

}  // namespace

// The cheapest origin's code by value + gradient (the first among equals); nullopt without a
// candidate (a region has points other than 0, so only a degenerate input gets there).
std::optional<OrbitCode> shifted_code(const ReferenceRegion& ref, int orbit, int n, int degree) {
  std::optional<OrbitCode> best;
  const std::vector<RatVec> origins = shift_origins(ref, n);
  for (const RatVec& o : origins) {
    OrbitCode code = shifted_form(ref, o, orbit, origins.size(), n, degree);
    if (!best || code.gradient.total() < best->gradient.total()) best = std::move(code);
  }
  return best;
}

}  // namespace boxgen::generator::strategies
