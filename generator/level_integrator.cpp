#include "generator/level_integrator.h"

#include <algorithm>
#include <cstdlib>

#include "generator/error.h"
#include "generator/knot_normals.h"

namespace boxgen::generator {

namespace {

struct Crossing {
  Rational t;
  int normal;
  std::int64_t level;
};

}  // namespace

LevelIntegrator::LevelIntegrator(IntColumns columns, int n, IntegrationPath path)
    : n_(n), columns_(std::move(columns)), path_(path) {
  const int m = static_cast<int>(columns_.size());
  IntColumns basis(columns_.begin(), columns_.begin() + n_);
  const std::int64_t d = det(basis);
  if (d == 0) fail_internal("LevelIntegrator: the first n columns are not a basis");
  basis_inverse_ = inverse(basis);
  base_value_ = Rational(1) / Rational(std::llabs(d));
  for (int k = n_; k <= m; ++k) {
    // Level n: the parallelepiped (or cone) is bounded by the planes spanned by n-1 basis columns.
    Level level;
    level.planes = knot_planes(IntColumns(columns_.begin(), columns_.begin() + k), n_);
    levels_.push_back(std::move(level));
  }
}

CellKey LevelIntegrator::key(int level, const RatVec& p) const {
  return path_ == IntegrationPath::UnitSegment ? interval_key(levels_[level].planes, p)
                                               : sign_key(levels_[level].planes.normals, p);
}

const Poly& LevelIntegrator::top(const RatVec& p) {
  return cell(static_cast<int>(levels_.size()) - 1, p).poly;
}

const Poly& LevelIntegrator::top(const CellKey& k, const RatVec& p) {
  const int level = static_cast<int>(levels_.size()) - 1;
  auto& cells = levels_[level].cells;
  if (auto it = cells.find(k); it != cells.end()) return it->second.poly;
  Poly poly = derive(level, p);
  auto [it, inserted] = cells.emplace(k, Cell{});
  it->second.poly = std::move(poly);
  return it->second.poly;
}

LevelIntegrator::Cell& LevelIntegrator::cell(int level, const RatVec& p) {
  return cell(level, key(level, p), [&] { return p; });
}

Poly LevelIntegrator::base(const RatVec& p) const {
  for (int i = 0; i < n_; ++i) {
    Rational a = 0;
    for (int j = 0; j < n_; ++j) a = a + basis_inverse_[i][j] * p[j];
    if (!cln::plusp(a)) return Poly::constant(n_, 0);
    if (path_ == IntegrationPath::UnitSegment && a >= 1) return Poly::constant(n_, 0);
  }
  return Poly::constant(n_, base_value_);
}

RatVec LevelIntegrator::perturbed(int level, const RatVec& p, int attempt) const {
  // A tiny move with large-prime denominators keeps p in its cell but breaks coincidences.
  static const long primes[] = {1000003, 1000033, 1000037, 1000039, 1000081, 1000099};
  const CellKey k = key(level, p);
  for (int shrink = 0; shrink < 200; ++shrink) {
    RatVec q = p;
    const Rational scale = Rational(1) / cln::expt(Rational(2), 16 + shrink);
    for (int i = 0; i < n_; ++i)
      q[i] = q[i] + scale * Rational(1 + attempt) / Rational(primes[(i + attempt) % 6]);
    const bool generic =
        path_ == IntegrationPath::UnitSegment ? off_knot_planes(levels_[level].planes, q) : true;
    if (generic && key(level, q) == k) return q;
  }
  fail_internal("could not perturb a point inside its cell");
}

Poly LevelIntegrator::derive(int level, RatVec p) {
  if (level == 0) return base(p);
  const IntVec& xi = columns_[n_ + level - 1];
  const auto& lower = levels_[level - 1].planes.normals;
  const auto& lower_levels = levels_[level - 1].planes.levels;
  std::vector<Crossing> crossings;
  for (int attempt = 0;; ++attempt) {
    crossings.clear();
    for (int i = 0; i < static_cast<int>(lower.size()); ++i) {
      const std::int64_t d = dot(lower[i], xi);
      if (d == 0) continue;
      const Rational s0 = dot(lower[i], p);
      if (path_ == IntegrationPath::Ray) {
        const Rational t = s0 / Rational(d);
        if (cln::plusp(t)) crossings.push_back({t, i, 0});
      } else {
        const Rational s1 = s0 - Rational(d);
        const Rational lo = cln::min(s0, s1), hi = cln::max(s0, s1);
        for (std::int64_t c : lower_levels[i])
          if (Rational(c) > lo && Rational(c) < hi)
            crossings.push_back({(s0 - Rational(c)) / Rational(d), i, c});
      }
    }
    std::sort(crossings.begin(), crossings.end(),
              [](const Crossing& a, const Crossing& b) { return a.t < b.t; });
    bool distinct = true;
    for (size_t j = 1; j < crossings.size(); ++j)
      if (crossings[j].t == crossings[j - 1].t) distinct = false;
    if (distinct) break;
    if (attempt > 20) fail_internal("no generic point found in a cell");
    p = perturbed(level, p, attempt);
  }

  // Cells of the lower level along the path, in order. Only the first key is located; at each
  // crossing the path passes one plane nu.x = c of the lower level (the parameters are distinct),
  // so one entry of the key moves by one: down if nu.x decreases along -xi (nu.xi > 0), else up.
  const RatVec xi_r = to_ratvec(xi);
  auto point_at = [&](const Rational& t) {
    RatVec q = p;
    for (int i = 0; i < n_; ++i) q[i] = q[i] - t * xi_r[i];
    return q;
  };
  std::vector<Rational> mid_t;
  Rational prev = 0;
  for (const auto& c : crossings) {
    mid_t.push_back((prev + c.t) / 2);
    prev = c.t;
  }
  mid_t.push_back(path_ == IntegrationPath::Ray ? prev + 1 : (prev + 1) / 2);
  std::vector<CellKey> keys{key(level - 1, point_at(mid_t[0]))};
  for (const auto& c : crossings) {
    CellKey next = keys.back();
    next[static_cast<size_t>(c.normal)] +=
        dot(lower[static_cast<size_t>(c.normal)], xi) > 0 ? -1 : 1;
    keys.push_back(std::move(next));
  }
  std::vector<Cell*> cells;
  for (size_t j = 0; j < keys.size(); ++j)
    cells.push_back(&cell(level - 1, keys[j], [&] { return point_at(mid_t[j]); }));
  if (path_ == IntegrationPath::Ray && !cells.back()->poly.is_zero())
    fail_internal("truncated power: the integrand does not vanish at infinity");

  Poly result(n_, 0);
  for (size_t j = 0; j < crossings.size(); ++j) {
    const auto& c = crossings[j];
    const IntVec& nu = lower[c.normal];
    const Rational d = Rational(dot(nu, xi));
    RatVec tau(n_ + 1);
    tau[0] = Rational(-c.level) / d;
    for (int i = 0; i < n_; ++i) tau[i + 1] = Rational(nu[i]) / d;
    result += jump(level - 1, keys[j], *cells[j], keys[j + 1], *cells[j + 1], tau);
  }
  if (path_ == IntegrationPath::UnitSegment) {
    for (const auto& g : integrated(level - 1, *cells.back())) result += g;  // G_last(x, 1)
  }
  result.trim();
  return result;
}

const std::vector<Poly>& LevelIntegrator::integrated(int level, Cell& c) {
  if (c.has_integrated) return c.integrated;
  const IntVec& xi = columns_[n_ + level];
  c.integrated.clear();
  if (!c.poly.is_zero()) {
    auto q = c.poly.along_direction(xi);
    c.integrated.emplace_back(n_, 0);
    for (size_t e = 0; e < q.size(); ++e)
      c.integrated.push_back(q[e] * (Rational(1) / Rational(static_cast<long>(e + 1))));
  }
  c.has_integrated = true;
  return c.integrated;
}

const Poly& LevelIntegrator::jump(int level, const CellKey& a, Cell& ca, const CellKey& b, Cell& cb,
                                  const RatVec& tau) {
  auto& memo = levels_[level].jumps;
  auto memo_key = std::make_pair(a, b);
  if (auto it = memo.find(memo_key); it != memo.end()) return it->second;
  const auto& ga = integrated(level, ca);
  const auto& gb = integrated(level, cb);
  const size_t top = std::max(ga.size(), gb.size());
  Poly r(n_, 0);
  // Horner in t with t = tau(x): r = sum_e (Ga_e - Gb_e) tau^e
  for (size_t e = top; e-- > 0;) {
    r = r.times_affine(tau);
    if (e < ga.size()) r += ga[e];
    if (e < gb.size()) r -= gb[e];
  }
  r.trim();
  return memo.emplace(std::move(memo_key), std::move(r)).first->second;
}

}  // namespace boxgen::generator
