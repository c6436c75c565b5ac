#include "generator/autocorr.h"

#include <algorithm>
#include <cstdlib>
#include <map>
#include <string>

#include "generator/error.h"
#include "generator/rational_linear_systems.h"
#include "generator/recurrence.h"
#include "generator/symmetry.h"

namespace boxgen::generator {

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
    for (std::size_t k = 0; k < normals.size() && inside; ++k)
      inside = 2 * std::llabs(dot(normals[k], y)) < twice_extent[k];
    if (inside) out.push_back(y);
  }
  return out;
}

// Centred refinement mask c'(z) = 2^(n-|W|) z^(-sum(W)/2) prod_w (1 + z^w), so that
// M^c(x) = sum_b c'_b M^c(2x - b). Kept as the integer coefficients of the product (exponents
// already centred) and the power 2^(|W|-n) that divides them.
struct CentredMask {
  std::map<IntVec, Integer> integer_coefficients;
  Integer denominator;
};

CentredMask centred_mask(const IntColumns& w, const Lattice& lattice) {
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
  if (!lattice.contains(centre))
    fail_internal("refinement: the centre of the doubled matrix is not a lattice point");
  CentredMask mask;
  mask.denominator = cln::expt_pos(Integer(2), static_cast<unsigned>(w.size() - n));
  for (const auto& [e, coeff] : product) {
    IntVec b = e;
    for (int i = 0; i < n; ++i) b[i] -= centre[i];
    mask.integer_coefficients[b] = coeff;
  }
  return mask;
}

// Rank of an integer matrix modulo the prime p (dense elimination, skipping zeros of the pivot
// row).
std::size_t rank_mod_p(std::vector<std::vector<std::uint64_t>> a, std::size_t cols,
                       std::uint64_t p) {
  auto power = [p](std::uint64_t b, std::uint64_t e) {
    std::uint64_t r = 1;
    for (b %= p; e; e >>= 1, b = b * b % p)
      if (e & 1) r = r * b % p;
    return r;
  };
  std::size_t row = 0;
  std::vector<std::size_t> support;
  for (std::size_t col = 0; col < cols && row < a.size(); ++col) {
    std::size_t pivot = row;
    while (pivot < a.size() && a[pivot][col] == 0) ++pivot;
    if (pivot == a.size()) continue;
    std::swap(a[pivot], a[row]);
    const std::uint64_t inv = power(a[row][col], p - 2);
    support.clear();
    for (std::size_t j = col; j < cols; ++j)
      if (a[row][j] != 0) support.push_back(j);
    for (std::size_t i = row + 1; i < a.size(); ++i) {
      if (a[i][col] == 0) continue;
      const std::uint64_t f = a[i][col] * inv % p;
      for (auto j : support) a[i][j] = (a[i][j] + (p - f) * a[row][j]) % p;
    }
    ++row;
  }
  return row;
}

Autocorrelation finish(std::vector<AutocorrSample> samples, int n) {
  std::sort(samples.begin(), samples.end(),
            [](const auto& a, const auto& b) { return a.point < b.point; });
  Autocorrelation out;
  const IntVec origin(n, 0);
  auto it = std::find_if(samples.begin(), samples.end(),
                         [&](const auto& s) { return s.point == origin; });
  if (it == samples.end()) fail_internal("autocorrelation: no sample at the origin");
  out.integral_squared = it->value;
  out.samples = std::move(samples);
  return out;
}

// Newton divided differences through (x_k, y_k), k < count: the interpolating polynomial's value at
// `at`.
Rational newton_value(const RatVec& x, RatVec y, std::size_t count, const Rational& at) {
  for (std::size_t level = 1; level < count; ++level)
    for (std::size_t k = count - 1; k >= level; --k)
      y[k] = (y[k] - y[k - 1]) / (x[k] - x[k - level]);
  Rational value = y[count - 1];
  for (std::size_t k = count - 1; k-- > 0;) value = value * (at - x[k]) + y[k];
  return value;
}

// The subdivision operator restricted to the lattice points in the open support.
struct Subdivision {
  std::vector<IntVec> points;
  std::map<IntVec, std::size_t> index;
  CentredMask mask;

  // Calls f(k, c) for every term c'_b v(2y - b) = (c / mask.denominator) v(points[k]) of the
  // operator at y; terms with 2y - b outside the open support vanish because M^c is continuous.
  template <class F>
  void for_each_term(const IntVec& y, F&& f) const {
    IntVec z(y.size());
    for (const auto& [b, c] : mask.integer_coefficients) {
      for (std::size_t i = 0; i < y.size(); ++i) z[i] = 2 * y[i] - b[i];
      if (auto it = index.find(z); it != index.end()) f(it->second, c);
    }
  }
};

// Confirms on every lattice point, without symmetry, that v is an eigenvector of eigenvalue 1
// (exactly) and that the eigenvalue is simple. The rank of S - I over Q is at least its rank
// modulo a prime, so nullity 1 modulo p proves nullity <= 1 over Q; v != 0 makes it exactly 1.
// A few primes guard against an unlucky one.
void verify_on_all_points(const Subdivision& s, const std::vector<Rational>& v) {
  const std::size_t count = s.points.size();
  for (std::size_t k = 0; k < count; ++k) {
    Rational image = 0;
    s.for_each_term(s.points[k],
                    [&](std::size_t j, const Integer& c) { image = image + Rational(c) * v[j]; });
    if (image / Rational(s.mask.denominator) != v[k])
      fail_internal("refinement: the samples are not an eigenvector of the subdivision operator");
  }
  std::size_t nullity = 0;
  for (std::uint64_t p : {2147483647ULL, 2147483629ULL, 2147483587ULL}) {
    const auto residue = [p](const Integer& x) {
      return static_cast<std::uint64_t>(cln::cl_I_to_UQ(cln::mod(x, Integer(p))));
    };
    std::vector<std::vector<std::uint64_t>> a(count, std::vector<std::uint64_t>(count, 0));
    for (std::size_t k = 0; k < count; ++k) {
      s.for_each_term(s.points[k], [&](std::size_t j, const Integer& c) {
        a[k][j] = (a[k][j] + residue(c)) % p;
      });
      a[k][k] = (a[k][k] + p - residue(s.mask.denominator)) % p;
    }
    nullity = count - rank_mod_p(std::move(a), count, p);
    if (nullity == 1) return;
  }
  fail_internal("refinement: eigenvalue 1 of the subdivision operator is not simple (nullity " +
                std::to_string(nullity) + " modulo three primes)");
}

// Both methods rely on the columns lying in the lattice: then the centre sum(Xi) and every mask
// exponent are lattice vectors, and the refinement equations close on lattice points.
BoxSplineSpec checked_doubled_spec(const BoxSplineSpec& spec) {
  for (const auto& c : spec.directions)
    if (static_cast<int>(c.size()) != spec.dimension() || !spec.lattice.contains(c))
      fail_input("autocorrelation: a direction is not a vector of the " + spec.lattice.name() +
                 " lattice");
  return doubled_spec(spec);
}

}  // namespace

BoxSplineSpec doubled_spec(const BoxSplineSpec& spec) {
  BoxSplineSpec d = spec;
  d.name = spec.name + " doubled";
  d.directions.insert(d.directions.end(), spec.directions.begin(), spec.directions.end());
  return d;
}

Autocorrelation autocorrelation_refinement(const BoxSplineSpec& spec,
                                           const RefinementOptions& options) {
  const BoxSplineSpec doubled = checked_doubled_spec(spec);
  const int n = spec.dimension();
  const IntColumns& w = doubled.directions;
  Subdivision s;
  s.points = interior_lattice_points(w, spec.lattice);
  for (std::size_t k = 0; k < s.points.size(); ++k) s.index[s.points[k]] = k;
  s.mask = centred_mask(w, spec.lattice);

  // The true samples are invariant under the group, so one unknown per orbit suffices.
  std::vector<SignedPermutation> group;
  if (options.reduce_by_symmetry) group = symmetry_group(doubled);
  std::vector<std::size_t> orbit_of(s.points.size(), SIZE_MAX);
  std::vector<std::size_t> representative, orbit_size;
  for (std::size_t k = 0; k < s.points.size(); ++k) {
    if (orbit_of[k] != SIZE_MAX) continue;
    const std::size_t id = representative.size();
    representative.push_back(k);
    orbit_size.push_back(1);
    orbit_of[k] = id;
    for (const auto& g : group) {
      auto it = s.index.find(g.apply(s.points[k]));
      if (it == s.index.end())
        fail_internal("refinement: the symmetry group does not preserve the support");
      if (orbit_of[it->second] == SIZE_MAX) {
        orbit_of[it->second] = id;
        ++orbit_size[id];
      }
    }
  }
  const std::size_t unknowns = representative.size();

  // Row of orbit O, from its representative y: sum_b c'_b u(orbit(2y - b)) - u_O = 0.
  const Rational inverse_denominator = Rational(1) / Rational(s.mask.denominator);
  std::vector<RatVec> system(unknowns, RatVec(unknowns, 0));
  for (std::size_t o = 0; o < unknowns; ++o) {
    s.for_each_term(s.points[representative[o]], [&](std::size_t j, const Integer& c) {
      Rational& entry = system[o][orbit_of[j]];
      entry = entry + Rational(c) * inverse_denominator;
    });
    system[o][o] = system[o][o] - 1;
  }
  const auto kernel = null_space(std::move(system), static_cast<int>(unknowns));
  if (kernel.size() != 1)
    fail_internal("refinement: eigenvalue 1 of the subdivision operator has multiplicity " +
                  std::to_string(kernel.size()) +
                  (options.reduce_by_symmetry ? " on symmetric vectors" : "") + ", expected 1");

  Rational total = 0;
  for (std::size_t o = 0; o < unknowns; ++o)
    total = total + rational_from(static_cast<std::int64_t>(orbit_size[o])) * kernel[0][o];
  if (cln::zerop(total)) fail_internal("refinement: the eigenvector sums to zero");
  const Rational scale = Rational(1) / (rational_from(spec.lattice.det_abs()) * total);

  std::vector<Rational> values(s.points.size());
  for (std::size_t k = 0; k < s.points.size(); ++k) {
    values[k] = kernel[0][orbit_of[k]] * scale;
    // A box spline is positive inside its support: a non-positive sample means a broken solve.
    if (values[k] <= 0) fail_internal("refinement: a sample inside the support is not positive");
  }
  if (options.reduce_by_symmetry && options.verify_on_all_points) verify_on_all_points(s, values);

  std::vector<AutocorrSample> samples;
  for (std::size_t k = 0; k < s.points.size(); ++k) samples.push_back({s.points[k], values[k]});
  return finish(std::move(samples), n);
}

Autocorrelation autocorrelation_continuity(const BoxSplineSpec& spec) {
  const BoxSplineSpec doubled = checked_doubled_spec(spec);
  const int n = spec.dimension();
  const IntColumns& w = doubled.directions;
  const int degree = static_cast<int>(w.size()) - n;
  // The recurrence's work grows with the number of sub-multisets of the columns; beyond this
  // bound (M7 and cart7 have 2187 and take seconds, M12 has 15625 and takes many minutes) the
  // method would look like a hang, so refuse clearly instead.
  std::map<IntVec, std::uint64_t> multiplicity;
  for (const auto& c : w) ++multiplicity[c];
  std::uint64_t sub_multisets = 1;
  for (const auto& [c, count] : multiplicity)
    sub_multisets = std::min<std::uint64_t>(sub_multisets * (count + 1), 1u << 30);
  if (sub_multisets > kContinuityMaxSubMultisets)
    fail_input("the continuity method is limited to " + std::to_string(kContinuityMaxSubMultisets) +
               " sub-multisets of the doubled directions (this spline has " +
               (sub_multisets >= (1u << 30) ? std::string("more than 2^30")
                                            : std::to_string(sub_multisets)) +
               "); use the refinement method");

  // v = (1, P, P^2) with P > max|nu_i| gives nu.v != 0 for every knot normal (nu_0 = 0 mod P,
  // then nu_1 = 0 mod P, ...); then eps |nu.v| < 1 keeps x0 + eps v, eps in (0, eps_max], inside
  // one cell of every integer arrangement, hence generic and on one polynomial piece.
  const auto normals = knot_plane_normals(w);
  std::int64_t max_entry = 1;
  for (const auto& nu : normals)
    for (auto x : nu) max_entry = std::max<std::int64_t>(max_entry, std::llabs(x));
  const std::int64_t p = max_entry + 1;
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
  BoxSplineRecurrence rec(w);
  for (int k = 0; k < samples_needed; ++k) {
    eps[k] = eps_unit * (k + 1);
    RatVec base(n);
    for (int i = 0; i < n; ++i)
      base[i] = Rational(rational_from(sum_w[i])) / 2 + eps[k] * rational_from(v[i]);
    rec.set_base(base);  // one memo for all lattice points at this eps
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

}  // namespace boxgen::generator
