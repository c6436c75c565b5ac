#include "generator/poly.h"

#include <map>
#include <mutex>

#include "generator/error.h"

namespace boxgen::generator {

namespace {

constexpr int kMaxDegree = 64;

std::size_t binom(int a, int b) {
  if (b < 0 || b > a) return 0;
  std::size_t r = 1;
  for (int i = 1; i <= b; ++i)
    r = r * static_cast<std::size_t>(a - b + i) / static_cast<std::size_t>(i);
  return r;
}

// Monomials of degree < d.
std::size_t offset(int n, int d) { return d <= 0 ? 0 : binom(d - 1 + n, n); }

}  // namespace

std::size_t monomial_count(int n, int degree) { return degree < 0 ? 0 : binom(degree + n, n); }

std::size_t monomial_index(int n, const Exponent& e) {
  if (n == 2) {
    const int d = e[0] + e[1];
    return offset(2, d) + static_cast<std::size_t>(d - e[0]);
  }
  const int d = e[0] + e[1] + e[2];
  const int r = d - e[0];
  return offset(3, d) + static_cast<std::size_t>(r * (r + 1) / 2 + (r - e[1]));
}

const std::vector<Exponent>& monomial_exponents(int n, int degree) {
  static std::mutex mutex;
  static std::map<int, std::vector<Exponent>> cache;  // full list up to kMaxDegree per n
  if (degree > kMaxDegree) fail_internal("polynomial degree above 64");
  std::lock_guard<std::mutex> lock(mutex);
  auto it = cache.find(n);
  if (it == cache.end()) {
    std::vector<Exponent> all;
    for (int d = 0; d <= kMaxDegree; ++d) {
      if (n == 2) {
        for (int a = d; a >= 0; --a) all.push_back({a, d - a, 0});
      } else {
        for (int a = d; a >= 0; --a)
          for (int b = d - a; b >= 0; --b) all.push_back({a, b, d - a - b});
      }
    }
    it = cache.emplace(n, std::move(all)).first;
  }
  // Callers only read the first monomial_count(n, degree) entries: return the shared list.
  return it->second;
}

Poly::Poly(int n, int capacity)
    : n_(n), cap_(capacity), c_(monomial_count(n, capacity), Rational(0)) {}

Poly Poly::constant(int n, const Rational& c) {
  Poly p(n, 0);
  p.c_[0] = c;
  return p;
}

Poly Poly::affine(const RatVec& a) {
  const int n = static_cast<int>(a.size()) - 1;
  Poly p(n, 1);
  p.c_[0] = a[0];
  for (int i = 0; i < n; ++i) {
    Exponent e{0, 0, 0};
    e[i] = 1;
    p.c_[monomial_index(n, e)] = a[i + 1];
  }
  return p;
}

int Poly::degree() const {
  for (std::size_t i = c_.size(); i-- > 0;)
    if (!cln::zerop(c_[i])) {
      const auto& ex = monomial_exponents(n_, cap_)[i];
      return ex[0] + ex[1] + ex[2];
    }
  return -1;
}

bool Poly::is_zero() const {
  for (const auto& v : c_)
    if (!cln::zerop(v)) return false;
  return true;
}

const Rational& Poly::coefficient(const Exponent& e) const {
  static const Rational zero = 0;
  std::size_t i = monomial_index(n_, e);
  return i < c_.size() ? c_[i] : zero;
}

void Poly::set_coefficient(const Exponent& e, const Rational& v) {
  const int d = e[0] + e[1] + e[2];
  if (d > cap_) reserve_degree(d);
  c_[monomial_index(n_, e)] = v;
}

void Poly::reserve_degree(int capacity) {
  if (capacity <= cap_) return;
  cap_ = capacity;
  c_.resize(monomial_count(n_, capacity), Rational(0));
}

void Poly::trim() {
  const int d = degree();
  cap_ = d < 0 ? 0 : d;
  c_.resize(monomial_count(n_, cap_));
}

Poly& Poly::operator+=(const Poly& o) {
  if (n_ == 0) n_ = o.n_;
  reserve_degree(o.cap_);
  for (std::size_t i = 0; i < o.c_.size(); ++i)
    if (!cln::zerop(o.c_[i])) c_[i] = c_[i] + o.c_[i];
  return *this;
}

Poly& Poly::operator-=(const Poly& o) {
  if (n_ == 0) n_ = o.n_;
  reserve_degree(o.cap_);
  for (std::size_t i = 0; i < o.c_.size(); ++i)
    if (!cln::zerop(o.c_[i])) c_[i] = c_[i] - o.c_[i];
  return *this;
}

Poly& Poly::operator*=(const Rational& s) {
  for (auto& v : c_)
    if (!cln::zerop(v)) v = v * s;
  return *this;
}

bool Poly::operator==(const Poly& o) const {
  const std::size_t common = std::min(c_.size(), o.c_.size());
  for (std::size_t i = 0; i < common; ++i)
    if (c_[i] != o.c_[i]) return false;
  for (std::size_t i = common; i < c_.size(); ++i)
    if (!cln::zerop(c_[i])) return false;
  for (std::size_t i = common; i < o.c_.size(); ++i)
    if (!cln::zerop(o.c_[i])) return false;
  return true;
}

Poly Poly::operator*(const Poly& o) const {
  const int da = std::max(degree(), 0), db = std::max(o.degree(), 0);
  Poly r(n_, da + db);
  const auto& ex = monomial_exponents(n_, da + db);
  const std::size_t na = monomial_count(n_, da), nb = monomial_count(o.n_, db);
  for (std::size_t i = 0; i < na && i < c_.size(); ++i) {
    if (cln::zerop(c_[i])) continue;
    for (std::size_t j = 0; j < nb && j < o.c_.size(); ++j) {
      if (cln::zerop(o.c_[j])) continue;
      Exponent e{ex[i][0] + ex[j][0], ex[i][1] + ex[j][1], ex[i][2] + ex[j][2]};
      auto& slot = r.c_[monomial_index(n_, e)];
      slot = slot + c_[i] * o.c_[j];
    }
  }
  return r;
}

Poly Poly::times_affine(const RatVec& a) const {
  const int d = std::max(degree(), 0);
  Poly r(n_, d + 1);
  const auto& ex = monomial_exponents(n_, d);
  const std::size_t count = monomial_count(n_, d);
  for (std::size_t i = 0; i < count && i < c_.size(); ++i) {
    const Rational& v = c_[i];
    if (cln::zerop(v)) continue;
    if (!cln::zerop(a[0])) r.c_[i] = r.c_[i] + v * a[0];
    for (int k = 0; k < n_; ++k) {
      if (cln::zerop(a[k + 1])) continue;
      Exponent e = ex[i];
      ++e[k];
      auto& slot = r.c_[monomial_index(n_, e)];
      slot = slot + v * a[k + 1];
    }
  }
  return r;
}

Rational Poly::eval(const RatVec& x) const {
  const int d = cap_;
  if (d < 0) return 0;
  // Powers of each coordinate, then a sum over monomials.
  std::vector<RatVec> pw(n_, RatVec(d + 1));
  for (int k = 0; k < n_; ++k) {
    pw[k][0] = 1;
    for (int j = 1; j <= d; ++j) pw[k][j] = pw[k][j - 1] * x[k];
  }
  const auto& ex = monomial_exponents(n_, d);
  Rational s = 0;
  for (std::size_t i = 0; i < c_.size(); ++i) {
    if (cln::zerop(c_[i])) continue;
    Rational t = c_[i];
    for (int k = 0; k < n_; ++k)
      if (ex[i][k]) t = t * pw[k][ex[i][k]];
    s = s + t;
  }
  return s;
}

namespace {

// Translation runs in integers: with s = S / q (S integral) and P = N / D (N integral),
//   P(x - s) = R(q x) / (D q^d),  R(z) = sum_e N_e q^(d - |e|) (z - S)^e,
// so the expansion is integer products and sums, and each coefficient of the result is divided
// once (a gcd per coefficient instead of one per product).

// table[k][e][j] = binomial(e, j) (-S_k)^j: the coefficients of (z_k - S_k)^e.
using ShiftTable = std::vector<std::vector<std::vector<Integer>>>;

ShiftTable shift_table(const std::vector<Integer>& s, int n, int d) {
  ShiftTable table(n, std::vector<std::vector<Integer>>(d + 1));
  for (int k = 0; k < n; ++k) {
    std::vector<Integer> negpow(d + 1);
    negpow[0] = 1;
    for (int j = 1; j <= d; ++j) negpow[j] = negpow[j - 1] * (-s[k]);
    for (int e = 0; e <= d; ++e) {
      table[k][e].resize(e + 1);
      for (int j = 0; j <= e; ++j)
        table[k][e][j] = Integer(static_cast<long>(binom(e, j))) * negpow[j];
    }
  }
  return table;
}

// Adds v (z_0 - S_0)^e0 (z_1 - S_1)^e1, expanded, to the coefficients `out` (2 variables).
void add_shifted_monomial_2d(const Integer& v, const Exponent& e, const ShiftTable& table,
                             std::vector<Integer>& out) {
  for (int j0 = 0; j0 <= e[0]; ++j0) {
    const Integer a = v * table[0][e[0]][j0];
    if (cln::zerop(a)) continue;
    for (int j1 = 0; j1 <= e[1]; ++j1) {
      const Integer& b = table[1][e[1]][j1];
      if (cln::zerop(b)) continue;
      auto& slot = out[monomial_index(2, {e[0] - j0, e[1] - j1, 0})];
      slot = slot + a * b;
    }
  }
}

// The same in 3 variables.
void add_shifted_monomial_3d(const Integer& v, const Exponent& e, const ShiftTable& table,
                             std::vector<Integer>& out) {
  for (int j0 = 0; j0 <= e[0]; ++j0) {
    const Integer a = v * table[0][e[0]][j0];
    if (cln::zerop(a)) continue;
    for (int j1 = 0; j1 <= e[1]; ++j1) {
      if (cln::zerop(table[1][e[1]][j1])) continue;
      const Integer b = a * table[1][e[1]][j1];
      for (int j2 = 0; j2 <= e[2]; ++j2) {
        const Integer& c = table[2][e[2]][j2];
        if (cln::zerop(c)) continue;
        auto& slot = out[monomial_index(3, {e[0] - j0, e[1] - j1, e[2] - j2})];
        slot = slot + b * c;
      }
    }
  }
}

}  // namespace

Poly Poly::translated(const RatVec& s) const {
  const int d = std::max(degree(), 0);
  const auto& ex = monomial_exponents(n_, d);
  const std::size_t count = monomial_count(n_, d);
  Integer q = 1, den = 1;
  for (const auto& v : s) q = cln::lcm(q, cln::denominator(v));
  for (std::size_t i = 0; i < count; ++i) den = cln::lcm(den, cln::denominator(c_[i]));
  std::vector<Integer> shift(n_);
  for (int k = 0; k < n_; ++k) shift[k] = cln::numerator(s[k] * q);
  std::vector<Integer> q_pow(d + 1);
  q_pow[0] = 1;
  for (int j = 1; j <= d; ++j) q_pow[j] = q_pow[j - 1] * q;
  const ShiftTable table = shift_table(shift, n_, d);
  std::vector<Integer> r(count, Integer(0));
  for (std::size_t i = 0; i < count; ++i) {
    if (cln::zerop(c_[i])) continue;
    const int degree_i = ex[i][0] + ex[i][1] + ex[i][2];
    // N_e q^(d - |e|), N_e = D c_e
    const Integer v = cln::numerator(c_[i]) * cln::exquo(den, cln::denominator(c_[i])) *
                      q_pow[static_cast<std::size_t>(d - degree_i)];
    if (n_ == 2)
      add_shifted_monomial_2d(v, ex[i], table, r);
    else
      add_shifted_monomial_3d(v, ex[i], table, r);
  }
  Poly out(n_, d);
  for (std::size_t i = 0; i < count; ++i) {
    if (cln::zerop(r[i])) continue;
    const int degree_i = ex[i][0] + ex[i][1] + ex[i][2];
    out.c_[i] = Rational(r[i]) / (den * q_pow[static_cast<std::size_t>(d - degree_i)]);
  }
  return out;
}

Poly Poly::composed_affine(const std::vector<RatVec>& a, const RatVec& b) const {
  // Horner over monomials using powers of the n affine coordinate polynomials.
  const int d = std::max(degree(), 0);
  std::vector<std::vector<Poly>> pw(n_);
  for (int k = 0; k < n_; ++k) {
    RatVec lin(n_ + 1);
    lin[0] = b[k];
    for (int j = 0; j < n_; ++j) lin[j + 1] = a[k][j];
    pw[k].push_back(Poly::constant(n_, 1));
    for (int j = 1; j <= d; ++j) pw[k].push_back(pw[k].back().times_affine(lin));
  }
  Poly r(n_, d);
  const auto& ex = monomial_exponents(n_, d);
  const std::size_t count = monomial_count(n_, d);
  for (std::size_t i = 0; i < count; ++i) {
    if (cln::zerop(c_[i])) continue;
    Poly term = pw[0][ex[i][0]];
    for (int k = 1; k < n_; ++k)
      if (ex[i][k]) term = term * pw[k][ex[i][k]];
    term *= c_[i];
    r += term;
  }
  return r;
}

Poly Poly::derivative(int var) const {
  const int d = std::max(degree(), 0);
  Poly r(n_, std::max(d - 1, 0));
  const auto& ex = monomial_exponents(n_, d);
  const std::size_t count = monomial_count(n_, d);
  for (std::size_t i = 0; i < count; ++i) {
    if (cln::zerop(c_[i]) || ex[i][var] == 0) continue;
    Exponent e = ex[i];
    const int power = e[var]--;
    r.c_[monomial_index(n_, e)] = c_[i] * Rational(power);
  }
  return r;
}

Poly Poly::substituted(int var, const RatVec& a) const {
  // Horner in x_var: P = sum_j x_var^j R_j(other variables).
  const int d = std::max(degree(), 0);
  std::vector<Poly> r(d + 1, Poly(n_, d));
  const auto& ex = monomial_exponents(n_, d);
  const std::size_t count = monomial_count(n_, d);
  for (std::size_t i = 0; i < count; ++i) {
    if (cln::zerop(c_[i])) continue;
    Exponent e = ex[i];
    const int j = e[var];
    e[var] = 0;
    r[j].c_[monomial_index(n_, e)] = c_[i];
  }
  Poly out = r[d];
  for (int j = d - 1; j >= 0; --j) {
    out = out.times_affine(a);
    out += r[j];
  }
  out.trim();
  return out;
}

Poly Poly::signed_permuted(const std::vector<int>& perm, const std::vector<int>& sign) const {
  const int d = std::max(degree(), 0);
  Poly r(n_, d);
  const auto& ex = monomial_exponents(n_, d);
  const std::size_t count = monomial_count(n_, d);
  for (std::size_t i = 0; i < count; ++i) {
    if (cln::zerop(c_[i])) continue;
    Exponent e{0, 0, 0};
    int parity = 0;
    for (int k = 0; k < n_; ++k) {
      e[perm[k]] += ex[i][k];
      if (sign[k] < 0) parity += ex[i][k];
    }
    r.c_[monomial_index(n_, e)] = parity % 2 ? Rational(-c_[i]) : c_[i];
  }
  return r;
}

Poly Poly::stretched(const Rational& f) const {
  const int d = std::max(degree(), 0);
  Poly r(n_, d);
  const auto& ex = monomial_exponents(n_, d);
  std::vector<Rational> power(static_cast<std::size_t>(d) + 1, Rational(1));
  for (int j = 1; j <= d; ++j) power[j] = power[j - 1] * f;
  for (std::size_t i = 0; i < monomial_count(n_, d); ++i)
    if (!cln::zerop(c_[i])) r.c_[i] = c_[i] * power[ex[i][0] + ex[i][1] + ex[i][2]];
  return r;
}

std::vector<Poly> Poly::along_direction(const IntVec& dir) const {
  // (x_k - tau d_k)^{e_k} = sum_j binom(e_k, j) x_k^{e_k - j} (-d_k)^j tau^j
  const int d = std::max(degree(), 0);
  std::vector<Poly> q(d + 1, Poly(n_, d));
  const auto& ex = monomial_exponents(n_, d);
  std::vector<std::vector<Integer>> table(n_, std::vector<Integer>());
  auto coef = [&](int k, int e, int j) {
    Integer p = 1;
    for (int t = 0; t < j; ++t) p = p * Integer(static_cast<long>(-dir[k]));
    return Integer(static_cast<long>(binom(e, j))) * p;
  };
  const std::size_t count = monomial_count(n_, d);
  for (std::size_t i = 0; i < count; ++i) {
    const Rational& v = c_[i];
    if (cln::zerop(v)) continue;
    const Exponent& e = ex[i];
    const int j0max = dir[0] ? e[0] : 0, j1max = dir[1] ? e[1] : 0,
              j2max = (n_ == 3 && dir[2]) ? e[2] : 0;
    for (int j0 = 0; j0 <= j0max; ++j0)
      for (int j1 = 0; j1 <= j1max; ++j1)
        for (int j2 = 0; j2 <= j2max; ++j2) {
          Integer f = coef(0, e[0], j0) * coef(1, e[1], j1);
          if (n_ == 3) f = f * coef(2, e[2], j2);
          Exponent r{e[0] - j0, e[1] - j1, n_ == 3 ? e[2] - j2 : 0};
          auto& slot = q[j0 + j1 + j2].c_[monomial_index(n_, r)];
          slot = slot + v * f;
        }
  }
  return q;
}

}  // namespace boxgen::generator
