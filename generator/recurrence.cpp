#include "generator/recurrence.h"

#include <algorithm>
#include <array>
#include <map>
#include <set>
#include <string>
#include <unordered_map>

#include "generator/error.h"

namespace boxgen::generator {

namespace {

constexpr int kMaxDimension = 3;
using Shift = std::array<std::int64_t, kMaxDimension>;  // unused trailing entries are 0

bool has_integer_value(const Rational& r) { return cln::denominator(r) == 1; }

IntColumns distinct_columns(const IntColumns& xi) {
  IntColumns out;
  for (const auto& c : xi)
    if (std::find(out.begin(), out.end(), c) == out.end()) out.push_back(c);
  return out;
}

void validate_columns(const IntColumns& xi) {
  if (xi.empty()) fail_input("box spline recurrence: the direction matrix has no columns");
  const std::size_t n = xi[0].size();
  if (n < 1 || n > kMaxDimension) fail_input("box spline recurrence: dimension must be 1, 2 or 3");
  for (const auto& c : xi) {
    if (c.size() != n) fail_input("box spline recurrence: columns of different lengths");
    if (std::all_of(c.begin(), c.end(), [](std::int64_t v) { return v == 0; }))
      fail_input("box spline recurrence: zero column");
  }
  if (rank(xi, static_cast<int>(n)) != static_cast<int>(n))
    fail_input("box spline recurrence: the columns do not span R^" + std::to_string(n));
}

}  // namespace

std::vector<IntVec> knot_plane_normals(const IntColumns& xi) {
  validate_columns(xi);
  const int n = static_cast<int>(xi[0].size());
  if (n == 1) return {IntVec{1}};
  const IntColumns d = distinct_columns(xi);
  std::set<IntVec> normals;
  if (n == 2) {
    for (const auto& c : d)
      if (auto nu = hyperplane_normal({c}, 2)) normals.insert(*nu);
  } else {
    for (std::size_t a = 0; a < d.size(); ++a)
      for (std::size_t b = a + 1; b < d.size(); ++b)
        if (auto nu = hyperplane_normal({d[a], d[b]}, 3)) normals.insert(*nu);
  }
  return {normals.begin(), normals.end()};
}

bool is_generic_point(const IntColumns& xi, const RatVec& x) {
  for (const auto& nu : knot_plane_normals(xi))
    if (has_integer_value(dot(nu, x))) return false;
  return true;
}

// State of the recursion: the multiset of remaining columns, coded in mixed radix as a count per
// distinct column (repeated columns are interchangeable, so the multiset is all that matters).
struct BoxSplineRecurrence::Impl {
  struct Basis {  // t = adjugate * x / det solves (basis) t = x
    IntColumns adjugate_rows;
    Rational inverse_det;
  };
  struct StateInfo {
    std::vector<int> counts;
    int total = 0;
    std::size_t basis_id = 0;
    std::vector<int> basis_position;  // per distinct column: its index in the basis, or -1
    std::vector<char> removable;      // removing one copy leaves columns that span R^n
    IntVec lo, hi;                    // extent of the support along each prune direction
    Rational parallelepiped_value;    // 1/|det| when total == n
  };
  struct Key {
    std::uint64_t code;
    Shift shift;
    bool operator==(const Key&) const = default;
  };
  struct KeyHash {
    static std::uint64_t mix(std::uint64_t z) {  // splitmix64 finaliser
      z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ULL;
      z = (z ^ (z >> 27)) * 0x94D049BB133111EBULL;
      return z ^ (z >> 31);
    }
    std::size_t operator()(const Key& k) const {
      std::uint64_t h = mix(k.code);
      for (auto s : k.shift) h = mix(h ^ static_cast<std::uint64_t>(s));
      return static_cast<std::size_t>(h);
    }
  };
  static constexpr std::uint64_t kDenseStates = std::uint64_t{1} << 22;

  // Structure of Xi (independent of the point).
  IntColumns xi;
  int n = 0;
  IntColumns distinct;
  std::vector<int> full_counts;
  std::vector<std::uint64_t> stride;
  std::uint64_t full_code = 0, state_count = 0;
  // The support of every sub-spline lies in the slabs lo <= dir.x <= hi for these directions
  // (coordinate axes and knot normals: the zonotope's own facets, so the prune is tight).
  IntColumns prune_dirs;
  std::vector<Basis> bases;
  std::map<IntColumns, std::size_t> basis_ids;
  std::vector<std::unique_ptr<StateInfo>> dense_states;  // indexed by code when few enough
  std::unordered_map<std::uint64_t, StateInfo> sparse_states;

  // Per base point.
  bool has_base = false;
  RatVec base;
  IntVec base_floor, base_ceil;  // floor / ceil of dir.base per prune direction
  std::vector<RatVec> t_base;    // per basis id: t for shift 0 (empty until needed)
  std::unordered_map<Key, Rational, KeyHash> memo;

  std::size_t basis_id_of(const IntColumns& basis) {
    if (auto it = basis_ids.find(basis); it != basis_ids.end()) return it->second;
    const std::int64_t basis_det = det(basis);
    const RatMatrix inv = inverse(basis);
    Basis b;
    b.inverse_det = Rational(1) / rational_from(basis_det);
    b.adjugate_rows.assign(n, IntVec(n));
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i)
        b.adjugate_rows[j][i] = floor_to_int64(inv[j][i] * rational_from(basis_det));
    bases.push_back(std::move(b));
    basis_ids.emplace(basis, bases.size() - 1);
    return bases.size() - 1;
  }

  StateInfo make_state(std::uint64_t code) {
    StateInfo s;
    const std::size_t p = distinct.size();
    s.counts.resize(p);
    for (std::size_t d = 0; d < p; ++d) {
      s.counts[d] =
          static_cast<int>((code / stride[d]) % static_cast<std::uint64_t>(full_counts[d] + 1));
      s.total += s.counts[d];
    }
    // The first independent columns, in a fixed order, give t with Xi t = x (t = 0 elsewhere).
    IntColumns basis;
    s.basis_position.assign(p, -1);
    for (std::size_t d = 0; d < p && static_cast<int>(basis.size()) < n; ++d) {
      if (s.counts[d] == 0) continue;
      IntColumns trial = basis;
      trial.push_back(distinct[d]);
      if (rank(trial, n) == static_cast<int>(trial.size())) {
        s.basis_position[d] = static_cast<int>(basis.size());
        basis = std::move(trial);
      }
    }
    if (static_cast<int>(basis.size()) != n)
      fail_internal("box spline recurrence reached a rank-deficient state");
    s.basis_id = basis_id_of(basis);
    s.removable.assign(p, 0);
    for (std::size_t d = 0; d < p; ++d) {
      if (s.counts[d] == 0) continue;
      if (s.counts[d] > 1) {
        s.removable[d] = 1;
        continue;
      }
      IntColumns rest;
      for (std::size_t e = 0; e < p; ++e)
        if (e != d && s.counts[e] > 0) rest.push_back(distinct[e]);
      s.removable[d] = static_cast<char>(!rest.empty() && rank(rest, n) == n);
    }
    s.lo.assign(prune_dirs.size(), 0);
    s.hi.assign(prune_dirs.size(), 0);
    for (std::size_t k = 0; k < prune_dirs.size(); ++k)
      for (std::size_t d = 0; d < p; ++d) {
        const std::int64_t v = s.counts[d] * dot(prune_dirs[k], distinct[d]);
        (v < 0 ? s.lo[k] : s.hi[k]) += v;
      }
    if (s.total == n) s.parallelepiped_value = Rational(1) / rational_from(std::llabs(det(basis)));
    return s;
  }

  const StateInfo& state(std::uint64_t code) {
    if (state_count <= kDenseStates) {
      if (dense_states.empty()) dense_states.resize(state_count);
      auto& slot = dense_states[code];
      if (!slot) slot = std::make_unique<StateInfo>(make_state(code));
      return *slot;
    }
    if (auto it = sparse_states.find(code); it != sparse_states.end()) return it->second;
    return sparse_states.emplace(code, make_state(code)).first->second;
  }

  const RatVec& t_at_base(std::size_t id) {
    if (t_base.size() < bases.size()) t_base.resize(bases.size());
    RatVec& t = t_base[id];
    if (t.empty()) {
      t.assign(n, 0);
      for (int j = 0; j < n; ++j)
        t[j] = dot(bases[id].adjugate_rows[j], base) * bases[id].inverse_det;
    }
    return t;
  }

  Rational value(std::uint64_t code, const Shift& shift) {
    const StateInfo& s = state(code);
    // Outside the slabs the value is 0. floor/ceil of dir.(base + shift) are exact integers, and
    // pruning only points strictly outside a closed slab is safe even at non-generic points.
    for (std::size_t k = 0; k < prune_dirs.size(); ++k) {
      std::int64_t along = 0;
      for (int i = 0; i < n; ++i) along += prune_dirs[k][i] * shift[i];
      if (base_floor[k] + along < s.lo[k] || base_ceil[k] + along > s.hi[k]) return 0;
    }
    const Key key{code, shift};
    if (auto it = memo.find(key); it != memo.end()) return it->second;

    const Basis& basis = bases[s.basis_id];
    RatVec t = t_at_base(s.basis_id);
    for (int j = 0; j < n; ++j) {
      std::int64_t numerator = 0;
      for (int i = 0; i < n; ++i) numerator += basis.adjugate_rows[j][i] * shift[i];
      if (numerator != 0) t[j] = t[j] + rational_from(numerator) * basis.inverse_det;
    }

    Rational result = 0;
    if (s.total == n) {
      // Half-open parallelepiped: at generic points no t_j is 0 or 1, so the choice of open or
      // closed faces does not matter.
      const bool inside =
          std::all_of(t.begin(), t.end(), [](const Rational& v) { return v >= 0 && v < 1; });
      result = inside ? s.parallelepiped_value : Rational(0);
    } else {
      // (m-n) M_Xi(x) = sum_k t_k M_{Xi\k}(x) + (1-t_k) M_{Xi\k}(x - xi_k); the copies of one
      // distinct column share M_{Xi\k}, and only the basis copy carries t_k != 0.
      for (std::size_t d = 0; d < distinct.size(); ++d) {
        if (s.counts[d] == 0 || !s.removable[d]) continue;  // non-spanning: zero at generic points
        const std::uint64_t child = code - stride[d];
        const Rational td = s.basis_position[d] >= 0 ? t[s.basis_position[d]] : Rational(0);
        if (!cln::zerop(td)) result = result + td * value(child, shift);
        const Rational weight = rational_from(s.counts[d]) - td;
        if (!cln::zerop(weight)) {
          Shift moved = shift;
          for (int i = 0; i < n; ++i) moved[i] -= distinct[d][i];
          result = result + weight * value(child, moved);
        }
      }
      result = result / rational_from(s.total - n);
    }
    memo.emplace(key, result);
    return result;
  }
};

BoxSplineRecurrence::BoxSplineRecurrence(const IntColumns& xi) : impl_(std::make_unique<Impl>()) {
  validate_columns(xi);
  Impl& m = *impl_;
  m.xi = xi;
  m.n = static_cast<int>(xi[0].size());
  m.distinct = distinct_columns(xi);
  for (const auto& d : m.distinct)
    m.full_counts.push_back(static_cast<int>(std::count(xi.begin(), xi.end(), d)));
  std::uint64_t radix = 1;
  for (std::size_t d = 0; d < m.distinct.size(); ++d) {
    m.stride.push_back(radix);
    m.full_code += radix * static_cast<std::uint64_t>(m.full_counts[d]);
    const std::uint64_t digits = static_cast<std::uint64_t>(m.full_counts[d]) + 1;
    if (radix > (std::uint64_t{1} << 62) / digits)
      fail_input("box spline recurrence: too many distinct directions");
    radix *= digits;
  }
  m.state_count = radix;
  std::set<IntVec> dirs;
  for (int i = 0; i < m.n; ++i) {
    IntVec e(m.n, 0);
    e[i] = 1;
    dirs.insert(e);
  }
  for (const auto& nu : knot_plane_normals(xi)) dirs.insert(nu);
  m.prune_dirs.assign(dirs.begin(), dirs.end());
}

BoxSplineRecurrence::~BoxSplineRecurrence() = default;
BoxSplineRecurrence::BoxSplineRecurrence(BoxSplineRecurrence&&) noexcept = default;
BoxSplineRecurrence& BoxSplineRecurrence::operator=(BoxSplineRecurrence&&) noexcept = default;

void BoxSplineRecurrence::set_base(const RatVec& base) {
  Impl& m = *impl_;
  if (static_cast<int>(base.size()) != m.n)
    fail_input("box spline recurrence: the point has " + std::to_string(base.size()) +
               " coordinates, expected " + std::to_string(m.n));
  if (!is_generic_point(m.xi, base))
    fail_input(
        "box spline recurrence: the point lies on a knot plane; the recurrence needs a generic "
        "point");
  m.base = base;
  m.base_floor.clear();
  m.base_ceil.clear();
  for (const auto& dir : m.prune_dirs) {
    const Rational along = dot(dir, base);
    m.base_floor.push_back(floor_to_int64(along));
    m.base_ceil.push_back(-floor_to_int64(Rational(-along)));
  }
  m.t_base.clear();
  m.memo.clear();
  m.has_base = true;
}

Rational BoxSplineRecurrence::at_shift(const IntVec& shift) {
  if (!impl_->has_base) fail_internal("box spline recurrence: at_shift before set_base");
  if (static_cast<int>(shift.size()) != impl_->n)
    fail_input("box spline recurrence: shift of the wrong dimension");
  Shift s{};
  std::copy(shift.begin(), shift.end(), s.begin());
  return impl_->value(impl_->full_code, s);
}

Rational BoxSplineRecurrence::value(const RatVec& x) {
  set_base(x);
  return at_shift(IntVec(x.size(), 0));
}

Rational box_spline_recurrence(const IntColumns& xi, const RatVec& x) {
  return BoxSplineRecurrence(xi).value(x);
}

Rational box_spline_centred_recurrence(const IntColumns& xi, const RatVec& x) {
  validate_columns(xi);
  if (x.size() != xi[0].size()) fail_input("box spline recurrence: point of the wrong dimension");
  RatVec shifted = x;
  for (const auto& c : xi)
    for (std::size_t i = 0; i < x.size(); ++i)
      shifted[i] = shifted[i] + Rational(rational_from(c[i])) / 2;
  return box_spline_recurrence(xi, shifted);
}

}  // namespace boxgen::generator
