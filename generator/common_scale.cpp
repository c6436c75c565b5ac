#include "generator/common_scale.h"

namespace boxgen::generator {

namespace {

IntColumns divided(IntColumns columns, std::int64_t k) {
  for (auto& column : columns)
    for (auto& v : column) v /= k;
  return columns;
}

RatVec times(RatVec v, const Rational& f) {
  for (auto& x : v) x = x * f;
  return v;
}

IntVec times(IntVec v, std::int64_t k) {
  for (auto& x : v) x *= k;
  return v;
}

}  // namespace

BoxSplineSpec reduced_spec(const BoxSplineSpec& spec, std::int64_t k) {
  BoxSplineSpec out = spec;
  out.directions = divided(spec.directions, k);
  out.lattice = Lattice(spec.lattice.name(), divided(spec.lattice.generator(), k));
  return out;
}

PiecewiseForm scaled_down(const PiecewiseForm& form, std::int64_t k) {
  PiecewiseForm out(reduced_spec(form.spec, k), form.method, form.knots.scaled_down(k),
                    form.complex.scaled_down(k));
  // M_{Xi/k}(y) = k^n M_Xi(k y): both integrate to 1.
  Rational volume = 1;
  for (int i = 0; i < form.dimension(); ++i) volume = volume * Rational(k);
  out.polys.reserve(form.polys.size());
  for (const auto& p : form.polys) out.polys.push_back(p.stretched(Rational(k)) * volume);
  out.seconds = form.seconds;
  return out;
}

SplineStructure scaled_up(const SplineStructure& s, std::int64_t k) {
  const Rational f = Rational(k), shrink = Rational(1) / Rational(k);
  SplineStructure out = s;
  out.scale = s.scale * k;
  out.centre = times(s.centre, f);
  for (auto& fc : out.cells) {
    for (auto& v : fc.cell.vertices) v = times(v, f);
    fc.cell.interior = times(fc.cell.interior, f);
    fc.placement = times(fc.placement, k);
  }
  auto scale_planes = [&](std::vector<Plane>& planes) {
    for (auto& p : planes) p.level = p.level * f;
  };
  for (auto& r : out.regions) {
    for (auto& v : r.vertices) v = times(v, f);
    scale_planes(r.planes);
    r.centroid = times(r.centroid, f);
    r.to_reference.l = times(r.to_reference.l, k);
  }
  for (auto& ref : out.references) {
    for (auto& v : ref.vertices) v = times(v, f);
    scale_planes(ref.planes);
    ref.interior = times(ref.interior, f);
    for (auto& j : ref.stencil) j = times(j, k);
    // M(x - j) = M'(x / k - j / k): the reduced basis at x / k.
    for (auto& b : ref.basis) b = b.stretched(shrink);
  }
  return out;
}

}  // namespace boxgen::generator
