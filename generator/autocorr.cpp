#include "generator/autocorr.h"

#include <algorithm>
#include <cstdlib>
#include <map>
#include <string>

#include "generator/error.h"
#include "generator/recurrence.h"
#include "generator/symmetry.h"

namespace boxgen {

namespace {

IntVec column_sum(const IntColumns& w, int n) {
  IntVec s(n, 0);
  for (const auto& c : w)
    for (int i = 0; i < n; ++i) s[i] += c[i];
  return s;
}

// Half-widths of the bounding box of the centred support sum_w [-w/2, w/2], doubled to stay in
// integers: the box is |x_i| <= twice_half_width[i] / 2.
IntVec twice_half_width(const IntColumns& w, int n) {
  IntVec h(n, 0);
  for (const auto& c : w)
    for (int i = 0; i < n; ++i) h[i] += std::llabs(c[i]);
  return h;
}

std::vector<IntVec> lattice_points_in_centred_box(const IntColumns& w, const Lattice& lattice) {
  const int n = lattice.dimension();
  const IntVec h = twice_half_width(w, n);
  IntVec lo(n), hi(n);
  for (int i = 0; i < n; ++i) hi[i] = h[i] / 2, lo[i] = -hi[i];
  return lattice.points_in_box(lo, hi);
}

// Lattice points strictly inside the centred zonotope sum_w [-w/2, w/2]. Its facet normals are
// the knot-plane normals nu, and its extent along nu is sum_w |nu.w| / 2.
std::vector<IntVec> interior_lattice_points(const IntColumns& w, const Lattice& lattice) {
  const auto normals = knot_plane_normals(w);
  std::vector<std::int64_t> twice_extent;
  for (const auto& nu : normals) {
    std::int64_t e = 0;
    for (const auto& c : w) e += std::llabs(dot(nu, c));
    twice_extent.push_back(e);
  }
  std::vector<IntVec> out;
  for (const auto& y : lattice_points_in_centred_box(w, lattice)) {
    bool inside = true;
    for (std::size_t k = 0; k < normals.size() && inside; ++k) inside = 2 * std::llabs(dot(normals[k], y)) < twice_extent[k];
    if (inside) out.push_back(y);
  }
  return out;
}

// Centred refinement mask c'(z) = 2^(n-|W|) z^(-sum(W)/2) prod_w (1 + z^w): M^c(x) = sum_b c'_b M^c(2x - b).
std::map<IntVec, Rational> centred_mask(const IntColumns& w, const Lattice& lattice) {
  const int n = lattice.dimension();
  std::map<IntVec, Integer> product{{IntVec(n, 0), 1}};
  for (const auto& c : w) {
    std::map<IntVec, Integer> next = product;
    for (const auto& [e, coeff] : product) {
      IntVec shifted = e;
      for (int i = 0; i < n; ++i) shifted[i] += c[i];
      next[shifted] = next[shifted] + coeff;  // absent keys start at 0
    }
    product = std::move(next);
  }
  IntVec centre = column_sum(w, n);
  for (auto& v : centre) {
    if (v % 2 != 0) fail_internal("refinement: the centre of the doubled matrix is not integer");
    v /= 2;
  }
  if (!lattice.contains(centre)) fail_internal("refinement: the centre of the doubled matrix is not a lattice point");
  const Rational scale = Rational(1) / cln::expt(Rational(2), static_cast<long>(w.size()) - n);
  std::map<IntVec, Rational> mask;
  for (const auto& [e, coeff] : product) {
    IntVec b = e;
    for (int i = 0; i < n; ++i) b[i] -= centre[i];
    mask[b] = Rational(coeff) * scale;
  }
  return mask;
}

// Exact null space of a dense rational matrix by reduced row echelon form.
std::vector<RatVec> null_space(std::vector<RatVec> a, std::size_t cols) {
  std::vector<std::size_t> pivot_cols;
  std::size_t row = 0;
  for (std::size_t col = 0; col < cols && row < a.size(); ++col) {
    std::size_t pivot = row;
    while (pivot < a.size() && cln::zerop(a[pivot][col])) ++pivot;
    if (pivot == a.size()) continue;
    std::swap(a[pivot], a[row]);
    const Rational inv = Rational(1) / a[row][col];
    for (std::size_t j = col; j < cols; ++j) a[row][j] = a[row][j] * inv;
    for (std::size_t i = 0; i < a.size(); ++i) {
      if (i == row || cln::zerop(a[i][col])) continue;
      const Rational f = a[i][col];
      for (std::size_t j = col; j < cols; ++j)
        if (!cln::zerop(a[row][j])) a[i][j] = a[i][j] - f * a[row][j];
    }
    pivot_cols.push_back(col);
    ++row;
  }
  std::vector<RatVec> basis;
  std::vector<char> is_pivot(cols, 0);
  for (auto c : pivot_cols) is_pivot[c] = 1;
  for (std::size_t free = 0; free < cols; ++free) {
    if (is_pivot[free]) continue;
    RatVec v(cols, 0);
    v[free] = 1;
    for (std::size_t r = 0; r < pivot_cols.size(); ++r) v[pivot_cols[r]] = -a[r][free];
    basis.push_back(std::move(v));
  }
  return basis;
}

Autocorrelation finish(std::vector<AutocorrSample> samples, int n) {
  std::sort(samples.begin(), samples.end(), [](const auto& a, const auto& b) { return a.point < b.point; });
  Autocorrelation out;
  const IntVec origin(n, 0);
  auto it = std::find_if(samples.begin(), samples.end(), [&](const auto& s) { return s.point == origin; });
  if (it == samples.end()) fail_internal("autocorrelation: no sample at the origin");
  out.integral_squared = it->value;
  out.samples = std::move(samples);
  return out;
}

// Newton divided differences through (x_k, y_k), k < count: the interpolating polynomial's value at `at`.
Rational newton_value(const RatVec& x, RatVec y, std::size_t count, const Rational& at) {
  for (std::size_t level = 1; level < count; ++level)
    for (std::size_t k = count - 1; k >= level; --k) y[k] = (y[k] - y[k - 1]) / (x[k] - x[k - level]);
  Rational value = y[count - 1];
  for (std::size_t k = count - 1; k-- > 0;) value = value * (at - x[k]) + y[k];
  return value;
}

}  // namespace

BoxSplineSpec doubled_spec(const BoxSplineSpec& spec) {
  BoxSplineSpec d = spec;
  d.name = spec.name + " doubled";
  d.directions.insert(d.directions.end(), spec.directions.begin(), spec.directions.end());
  return d;
}

Autocorrelation autocorrelation_refinement(const BoxSplineSpec& spec, const RefinementOptions& options) {
  const BoxSplineSpec doubled = doubled_spec(spec);
  const int n = spec.dimension();
  const IntColumns& w = doubled.directions;
  const std::vector<IntVec> points = interior_lattice_points(w, spec.lattice);
  std::map<IntVec, std::size_t> index;
  for (std::size_t k = 0; k < points.size(); ++k) index[points[k]] = k;

  // The true samples are invariant under the group, so one unknown per orbit suffices.
  std::vector<SignedPermutation> group;
  if (options.reduce_by_symmetry) group = symmetry_group(doubled);
  std::vector<std::size_t> orbit_of(points.size(), SIZE_MAX);
  std::vector<std::size_t> representative, orbit_size;
  for (std::size_t k = 0; k < points.size(); ++k) {
    if (orbit_of[k] != SIZE_MAX) continue;
    const std::size_t id = representative.size();
    representative.push_back(k);
    orbit_size.push_back(0);
    orbit_of[k] = id;
    ++orbit_size[id];
    for (const auto& g : group) {
      auto it = index.find(g.apply(points[k]));
      if (it == index.end()) fail_internal("refinement: the symmetry group does not preserve the support");
      if (orbit_of[it->second] == SIZE_MAX) {
        orbit_of[it->second] = id;
        ++orbit_size[id];
      }
    }
  }
  const std::size_t unknowns = representative.size();

  // Row of orbit O, from its representative y: sum_b c'_b u(orbit(2y - b)) - u_O = 0; terms with
  // 2y - b outside the open support vanish because M^c is continuous and zero there.
  const auto mask = centred_mask(w, spec.lattice);
  std::vector<RatVec> system(unknowns, RatVec(unknowns, 0));
  for (std::size_t o = 0; o < unknowns; ++o) {
    const IntVec& y = points[representative[o]];
    IntVec z(n);
    for (const auto& [b, c] : mask) {
      for (int i = 0; i < n; ++i) z[i] = 2 * y[i] - b[i];
      auto it = index.find(z);
      if (it != index.end()) system[o][orbit_of[it->second]] = system[o][orbit_of[it->second]] + c;
    }
    system[o][o] = system[o][o] - 1;
  }
  const auto kernel = null_space(std::move(system), unknowns);
  if (kernel.size() != 1)
    fail_internal("refinement: eigenvalue 1 of the subdivision operator has multiplicity " +
                  std::to_string(kernel.size()) + ", expected 1");

  Rational total = 0;
  for (std::size_t o = 0; o < unknowns; ++o) total = total + rational_from(static_cast<std::int64_t>(orbit_size[o])) * kernel[0][o];
  if (cln::zerop(total)) fail_internal("refinement: the eigenvector sums to zero");
  const Rational scale = Rational(1) / (rational_from(spec.lattice.det_abs()) * total);

  std::vector<AutocorrSample> samples;
  for (std::size_t k = 0; k < points.size(); ++k) {
    const Rational v = kernel[0][orbit_of[k]] * scale;
    // A box spline is positive inside its support: a non-positive sample means a broken solve.
    if (v <= 0) fail_internal("refinement: a sample inside the support is not positive");
    samples.push_back({points[k], v});
  }
  return finish(std::move(samples), n);
}

Autocorrelation autocorrelation_continuity(const BoxSplineSpec& spec) {
  const BoxSplineSpec doubled = doubled_spec(spec);
  const int n = spec.dimension();
  const IntColumns& w = doubled.directions;
  const int degree = static_cast<int>(w.size()) - n;

  // v = (1, P, P^2) with P > 2 max|nu_i| gives nu.v != 0 for every knot normal (balanced base-P
  // digits are unique); then eps |nu.v| < 1 keeps x0 + eps v, eps in (0, eps_max], inside one
  // cell of every integer arrangement, hence generic and on one polynomial piece.
  const auto normals = knot_plane_normals(w);
  std::int64_t max_entry = 1;
  for (const auto& nu : normals)
    for (auto x : nu) max_entry = std::max<std::int64_t>(max_entry, std::llabs(x));
  const std::int64_t p = 2 * max_entry + 1;
  IntVec v(n);
  std::int64_t power = 1;
  for (int i = 0; i < n; ++i, power *= p) v[i] = power;
  std::int64_t max_dot = 0;
  for (const auto& nu : normals) {
    const std::int64_t d = std::llabs(dot(nu, v));
    if (d == 0) fail_internal("continuity: the direction v lies in a knot plane");
    max_dot = std::max(max_dot, d);
  }
  const int samples_needed = degree + 3;  // deg+1 to interpolate, 2 to confirm
  const Rational eps_unit = Rational(1) / rational_from(max_dot * (samples_needed + 1));

  // Uncentred evaluation: M^c(x0 + eps v) = M(x0 + centre + eps v); the centre is integer.
  const IntVec sum_w = column_sum(w, n);
  const std::vector<IntVec> points = lattice_points_in_centred_box(w, spec.lattice);
  RatVec eps(samples_needed);
  std::vector<RatVec> values(points.size(), RatVec(samples_needed));
  for (int k = 0; k < samples_needed; ++k) {
    eps[k] = eps_unit * (k + 1);
    RatVec base(n);
    for (int i = 0; i < n; ++i) base[i] = Rational(rational_from(sum_w[i])) / 2 + eps[k] * rational_from(v[i]);
    BoxSplineRecurrence rec(w, base);  // one memo for all lattice points at this eps
    for (std::size_t j = 0; j < points.size(); ++j) values[j][k] = rec.at_shift(points[j]);
  }

  std::vector<AutocorrSample> samples;
  for (std::size_t j = 0; j < points.size(); ++j) {
    const std::size_t fit = static_cast<std::size_t>(degree) + 1;
    for (std::size_t extra = fit; extra < eps.size(); ++extra)
      if (newton_value(eps, values[j], fit, eps[extra]) != values[j][extra])
        fail_internal("continuity: the samples along x0 + eps v are not one polynomial of degree " +
                      std::to_string(degree));
    const Rational limit = newton_value(eps, values[j], fit, 0);
    if (!cln::zerop(limit)) samples.push_back({points[j], limit});
  }
  return finish(std::move(samples), n);
}

}  // namespace boxgen
