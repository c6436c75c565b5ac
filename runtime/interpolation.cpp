#include "runtime/interpolation.h"

#include <fftw3.h>
#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <complex>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <mutex>
#include <new>
#include <stdexcept>
#include <utility>
#include <vector>

#include "runtime/batch_threads.h"
#include "runtime/reconstruction.h"
#include "runtime/resample.h"
#include "support/fourier_sums.h"
#include "support/integer_math.h"
#include "support/lattice_regulariser.h"

namespace boxgen::runtime {

namespace {

using Complex = std::complex<double>;
using support::BoxKernel;
using support::FourierSums;

// Complex products by the textbook formula. The library's (C99 Annex G) also checks each result
// for NaN parts to recover infinities, a cost the per-frequency systems (finite numbers of order
// 1) do not need: callgrind counts 455 million instructions in the solve of m7 on 2 x 40^3
// samples with it, 309 million without. Found by ordinary lookup here and preferred to the
// library's template.
Complex operator*(const Complex& a, const Complex& b) { return support::product(a, b); }

// An index or size computed in int (the kernels' boxes, K^2: small), as a std::size_t.
std::size_t index_of(int i) { return static_cast<std::size_t>(i); }

// ---------------------------------------------------------------------------------------------
// The coset system: h_ab(t) = M(d t + off_a - off_b).

struct CosetSystem {
  int k = 1;                       // K
  std::vector<BoxKernel> kernels;  // the distinct kernels, on one common box
  std::vector<std::size_t> pair;   // pair[a * K + b]: the kernel of h_ab (h_aa are all M(d t))
};

CosetSystem coset_system(const PrefilterTaps& values, const CosetLattice& lattice) {
  const int k_count = lattice.coset_count();
  const int d = lattice.period();
  struct Tap {
    int a, b;
    std::array<int, 3> t;
    double w;
  };
  std::vector<Tap> taps;
  std::array<int, 3> lo{0, 0, 0}, hi{0, 0, 0};
  for (const auto& [v, w] : values)
    for (int a = 0; a < k_count; ++a) {
      const Offset& oa = lattice.offsets()[static_cast<std::size_t>(a)];
      const int b = lattice.coset_of(oa[0] - v[0], oa[1] - v[1], oa[2] - v[2]);
      const Offset& ob = lattice.offsets()[static_cast<std::size_t>(b)];
      Tap tap{a, b, {}, w};
      for (std::size_t x = 0; x < 3; ++x) {
        tap.t[x] = (v[x] - oa[x] + ob[x]) / d;  // exact: v - off_a + off_b is in d Z^3
        lo[x] = std::min(lo[x], tap.t[x]);
        hi[x] = std::max(hi[x], tap.t[x]);
      }
      taps.push_back(tap);
    }
  CosetSystem system{k_count, {}, {}};
  BoxKernel empty;
  empty.lo = lo;
  for (std::size_t x = 0; x < 3; ++x) empty.width[x] = hi[x] - lo[x] + 1;
  empty.values.assign(index_of(empty.width[0] * empty.width[1] * empty.width[2]), 0.0);
  system.kernels.assign(index_of(k_count * k_count), empty);
  for (const Tap& tap : taps)
    system.kernels[index_of(tap.a * k_count + tap.b)].at(tap.t[0], tap.t[1], tap.t[2]) += tap.w;
  // Equal kernels share their Fourier sums (every h_aa; on BCC also nothing else).
  std::vector<BoxKernel> distinct;
  for (const BoxKernel& kernel : system.kernels) {
    std::size_t at = 0;
    while (at < distinct.size() && distinct[at].values != kernel.values) ++at;
    if (at == distinct.size()) distinct.push_back(kernel);
    system.pair.push_back(at);
  }
  system.kernels = std::move(distinct);
  return system;
}

// Solves the K x K system per frequency in place: x holds V(w) on entry, c(w) on exit.
// mu = 0: H c = V (Gaussian elimination, partial pivoting); mu > 0: (H* H + mu D* D) c = H* V,
// D the regulariser's coset matrix.
class FrequencySolver {
 public:
  FrequencySolver(int k, double mu)
      : k_(k),
        mu_(mu),
        h_(static_cast<std::size_t>(k * k)),
        d_(h_.size()),
        a_(h_.size()),
        b_(static_cast<std::size_t>(k)) {}
  Complex& h(int a, int b) { return h_[index_of(a * k_ + b)]; }
  Complex& d(int a, int b) { return d_[index_of(a * k_ + b)]; }
  // x: K values (coset a at x[a * stride]).
  void solve(Complex* x, std::ptrdiff_t stride) {
    if (k_ == 1) {
      const Complex hv = h_[0];
      x[0] = x[0] * (std::conj(hv) / (std::norm(hv) + mu_ * std::norm(d_[0])));
      return;
    }
    if (k_ == 2) return solve2(x, stride);
    const auto n = static_cast<std::size_t>(k_);
    if (mu_ == 0) {
      a_ = h_;
      for (std::size_t a = 0; a < n; ++a) b_[a] = x[static_cast<std::ptrdiff_t>(a) * stride];
    } else {
      for (std::size_t a = 0; a < n; ++a) {
        Complex s = 0;
        for (std::size_t r = 0; r < n; ++r)
          s += std::conj(h_[r * n + a]) * x[static_cast<std::ptrdiff_t>(r) * stride];
        b_[a] = s;
        for (std::size_t b = 0; b < n; ++b) {
          Complex t = 0, u = 0;
          for (std::size_t r = 0; r < n; ++r) {
            t += std::conj(h_[r * n + a]) * h_[r * n + b];
            u += std::conj(d_[r * n + a]) * d_[r * n + b];
          }
          a_[a * n + b] = t + mu_ * u;
        }
      }
    }
    for (std::size_t col = 0; col < n; ++col) {
      std::size_t pivot = col;
      for (std::size_t r = col + 1; r < n; ++r)
        if (std::norm(a_[r * n + col]) > std::norm(a_[pivot * n + col])) pivot = r;
      if (pivot != col) {
        for (std::size_t c = 0; c < n; ++c) std::swap(a_[col * n + c], a_[pivot * n + c]);
        std::swap(b_[col], b_[pivot]);
      }
      const Complex inv = reciprocal(a_[col * n + col]);
      for (std::size_t r = col + 1; r < n; ++r) {
        const Complex f = a_[r * n + col] * inv;
        if (f == Complex(0)) continue;
        for (std::size_t c = col; c < n; ++c) a_[r * n + c] -= f * a_[col * n + c];
        b_[r] -= f * b_[col];
      }
    }
    for (std::size_t r = n; r-- > 0;) {
      Complex s = b_[r];
      for (std::size_t c = r + 1; c < n; ++c) s -= a_[r * n + c] * b_[c];
      b_[r] = s * reciprocal(a_[r * n + r]);
    }
    for (std::size_t a = 0; a < n; ++a) x[static_cast<std::ptrdiff_t>(a) * stride] = b_[a];
  }

 private:
  // 1 / z without the library's scaling for extreme exponents (the systems' entries are of
  // order 1): a plain division costs a call of __divdc3 per frequency.
  static Complex reciprocal(Complex z) { return std::conj(z) / std::norm(z); }

  // K = 2 (BCC) by Cramer's rule: H c = V, or (H* H + mu I) c = H* V.
  void solve2(Complex* x, std::ptrdiff_t stride) {
    Complex a = h_[0], b = h_[1], c = h_[2], d = h_[3];
    Complex v0 = x[0], v1 = x[stride];
    if (mu_ != 0) {
      const Complex p = d_[0], q = d_[1], r = d_[2], t = d_[3];
      const Complex a2 = std::norm(a) + std::norm(c) + mu_ * (std::norm(p) + std::norm(r)),
                    b2 = std::conj(a) * b + std::conj(c) * d +
                         mu_ * (std::conj(p) * q + std::conj(r) * t),
                    d2 = std::norm(b) + std::norm(d) + mu_ * (std::norm(q) + std::norm(t));
      const Complex w0 = std::conj(a) * v0 + std::conj(c) * v1,
                    w1 = std::conj(b) * v0 + std::conj(d) * v1;
      a = a2;
      b = b2;
      c = std::conj(b2);
      d = d2;
      v0 = w0;
      v1 = w1;
    }
    const Complex inv = reciprocal(a * d - b * c);
    x[0] = (d * v0 - b * v1) * inv;
    x[stride] = (a * v1 - c * v0) * inv;
  }

  int k_;
  double mu_;
  std::vector<Complex> h_, d_, a_, b_;
};

// ---------------------------------------------------------------------------------------------
// FFTW: K real volumes of n0 x n1 x n2 transformed in place (x fastest; rows padded to
// 2 (n0/2 + 1) doubles), on batch_threads() threads.

struct FftwFree {
  void operator()(double* p) const noexcept { fftw_free(p); }
};
struct PlanDestroy {
  void operator()(fftw_plan_s* p) const noexcept { fftw_destroy_plan(p); }
};
using Plan = std::unique_ptr<fftw_plan_s, PlanDestroy>;

std::mutex& planner_mutex() {
  static std::mutex m;  // FFTW's planner is not thread-safe
  return m;
}

class CosetTransform {
 public:
  CosetTransform(int k, const Sizes& n) : n_(n), row_(2 * (n[0] / 2 + 1)) {
    per_coset_ = static_cast<std::size_t>(row_) * static_cast<std::size_t>(n[1]) *
                 static_cast<std::size_t>(n[2]);
    data_.reset(static_cast<double*>(
        fftw_malloc(sizeof(double) * per_coset_ * static_cast<std::size_t>(k))));
    if (!data_) throw std::bad_alloc();
    const std::lock_guard<std::mutex> lock(planner_mutex());
    static std::once_flag threads_ready;
    std::call_once(threads_ready, [] { fftw_init_threads(); });
    fftw_plan_with_nthreads(batch_threads());
    const int dims[3] = {n[2], n[1], n[0]};
    const int real_embed[3] = {n[2], n[1], row_};
    const int complex_embed[3] = {n[2], n[1], row_ / 2};
    auto* complex_data = reinterpret_cast<fftw_complex*>(data_.get());
    const int dist = static_cast<int>(per_coset_);
    forward_.reset(fftw_plan_many_dft_r2c(3, dims, k, data_.get(), real_embed, 1, dist,
                                          complex_data, complex_embed, 1, dist / 2, FFTW_ESTIMATE));
    backward_.reset(fftw_plan_many_dft_c2r(3, dims, k, complex_data, complex_embed, 1, dist / 2,
                                           data_.get(), real_embed, 1, dist, FFTW_ESTIMATE));
    if (!forward_ || !backward_) throw std::runtime_error("FFTW could not plan the transform");
  }
  // Real sample (c, i, j, k) before the forward and after the backward transform.
  double& real(int c, int i, int j, int k) noexcept {
    return data_.get()[static_cast<std::size_t>(c) * per_coset_ + static_cast<std::size_t>(i) +
                       static_cast<std::size_t>(row_) *
                           (static_cast<std::size_t>(j) +
                            static_cast<std::size_t>(n_[1]) * static_cast<std::size_t>(k))];
  }
  // Frequency (k0, k1, k2) of coset c, 0 <= k0 <= n0 / 2, between the transforms.
  Complex* spectrum(int c, int k0, int k1, int k2) noexcept {
    return reinterpret_cast<Complex*>(data_.get() + static_cast<std::size_t>(c) * per_coset_) +
           static_cast<std::size_t>(k0) +
           static_cast<std::size_t>(row_ / 2) *
               (static_cast<std::size_t>(k1) +
                static_cast<std::size_t>(n_[1]) * static_cast<std::size_t>(k2));
  }
  // Complex values between two cosets at the same frequency.
  std::ptrdiff_t coset_stride() const noexcept {
    return static_cast<std::ptrdiff_t>(per_coset_ / 2);
  }
  void forward() { fftw_execute(forward_.get()); }
  void backward() { fftw_execute(backward_.get()); }
  const Sizes& sizes() const noexcept { return n_; }

 private:
  Sizes n_;
  int row_;
  std::size_t per_coset_ = 0;
  std::unique_ptr<double, FftwFree> data_;
  Plan forward_, backward_;
};

// What is solved per frequency: the filter's coset system H and, where regularised (mu > 0), the
// regulariser's D.
struct Problem {
  CosetSystem h, d;
  double mu = 0;
};

// Solves the coset system at every frequency of the transform (between forward and backward),
// then scales by 1 / (n0 n1 n2) for FFTW's unnormalised backward transform.
void solve_all(CosetTransform& x, const Problem& problem) {
  const CosetSystem& system = problem.h;
  const double mu = problem.mu;
  const Sizes& n = x.sizes();
  const std::array<int, 3> count{n[0] / 2 + 1, n[1], n[2]};
  const double scale = 1.0 / (static_cast<double>(n[0]) * n[1] * n[2]);
  const int k_count = system.k;
  const std::ptrdiff_t stride = x.coset_stride();
  std::exception_ptr failure;
#pragma omp parallel num_threads(batch_threads())
  {
    try {
      FourierSums sums(system.kernels, {n[0], n[1], n[2]}, count);
      std::optional<FourierSums> regulariser;
      if (mu > 0)
        regulariser.emplace(problem.d.kernels, std::array<int, 3>{n[0], n[1], n[2]}, count);
      FrequencySolver solver(k_count, mu);
      std::vector<Complex> h(system.kernels.size()), d(problem.d.kernels.size());
#pragma omp for schedule(dynamic, 1)
      for (int k2 = 0; k2 < n[2]; ++k2) {
        sums.set_k2(k2);
        if (regulariser) regulariser->set_k2(k2);
        for (int k1 = 0; k1 < n[1]; ++k1) {
          sums.set_k1(k1);
          if (regulariser) regulariser->set_k1(k1);
          for (int k0 = 0; k0 < count[0]; ++k0) {
            for (std::size_t u = 0; u < system.kernels.size(); ++u) h[u] = sums.at_k0(u, k0);
            if (regulariser)
              for (std::size_t u = 0; u < problem.d.kernels.size(); ++u)
                d[u] = regulariser->at_k0(u, k0);
            for (int a = 0; a < k_count; ++a)
              for (int b = 0; b < k_count; ++b) {
                const auto p = index_of(a * k_count + b);
                solver.h(a, b) = h[system.pair[p]];
                if (regulariser) solver.d(a, b) = d[problem.d.pair[p]];
              }
            Complex* v = x.spectrum(0, k0, k1, k2);
            solver.solve(v, stride);
            for (int a = 0; a < k_count; ++a) v[a * stride] *= scale;
          }
        }
      }
    } catch (...) {
#pragma omp critical
      failure = std::current_exception();
    }
  }
  if (failure) std::rethrow_exception(failure);
}

// The smallest n' >= n whose prime factors are 2, 3, 5 and 7 (FFTW's fast sizes).
int smooth_size(int n) {
  for (int m = std::max(n, 1);; ++m) {
    int r = m;
    for (int p : {2, 3, 5, 7})
      while (r % p == 0) r /= p;
    if (r == 1) return m;
  }
}

// Coset cells beyond which the inverse filter (its response to a delta at coset 0, on a periodic
// grid of 64 cells per axis) stays below `tolerance` times its largest value. At most 31 (the
// grid's half).
int decay_radius(const Problem& problem, double tolerance) {
  const CosetSystem& system = problem.h;
  constexpr int kGrid = 64;
  CosetTransform x(system.k, {kGrid, kGrid, kGrid});
  for (int c = 0; c < system.k; ++c)
    for (int k = 0; k < kGrid; ++k)
      for (int j = 0; j < kGrid; ++j)
        for (int i = 0; i < kGrid; ++i) x.real(c, i, j, k) = 0;
  x.real(0, 0, 0, 0) = 1;
  x.forward();
  solve_all(x, problem);
  x.backward();
  std::vector<double> largest_at(kGrid / 2 + 1, 0.0);  // by periodic Chebyshev distance
  double largest = 0;
  for (int c = 0; c < system.k; ++c)
    for (int k = 0; k < kGrid; ++k)
      for (int j = 0; j < kGrid; ++j)
        for (int i = 0; i < kGrid; ++i) {
          const int r =
              std::max({std::min(i, kGrid - i), std::min(j, kGrid - j), std::min(k, kGrid - k)});
          const double v = std::abs(x.real(c, i, j, k));
          largest_at[static_cast<std::size_t>(r)] =
              std::max(largest_at[static_cast<std::size_t>(r)], v);
          largest = std::max(largest, v);
        }
  for (int r = kGrid / 2; r > 0; --r)
    if (largest_at[static_cast<std::size_t>(r)] > tolerance * largest)
      return std::min(r, kGrid / 2 - 1);
  return 0;
}

// The padding of the transform keeps the wrap-around below 1e-10 of the data in the coefficients
// of the samples where interpolation is exact, below 1e-6 where it is regularised (whose residual
// at the samples is far larger: 1e-3 of the data and more); the sampling margin
// (interpolation_margin) keeps the faces' influence below 1e-6 at the region of interest.
constexpr double kPaddingDecay = 1e-10;
constexpr double kRegularisedPaddingDecay = 1e-6;
constexpr double kMarginDecay = 1e-6;

void require_few_cosets(const CosetLattice& lattice) {
  if (lattice.coset_count() > kMaxInterpolationCosets)
    throw std::invalid_argument(fmt::format(
        "interpolation takes lattices of at most {} cosets of d Z^3; the {} lattice has {}",
        kMaxInterpolationCosets, lattice.label(), lattice.coset_count()));
}

// The problem of f's interpolation with lambda (support::regularisation: D and mu).
struct Setup {
  support::Regularisation regular;
  Problem problem;
};
Setup setup(const SplineFilter& f, const PrefilterTaps& values, std::optional<double> lambda) {
  const IntRows& g = f.lattice().rows();  // L = G Z^3: G's columns are a basis of L
  std::vector<std::vector<std::int64_t>> basis;
  for (std::size_t col = 0; col < 3; ++col) basis.push_back({g[0][col], g[1][col], g[2][col]});
  Setup s{support::regularisation(values, basis, f.approximation_order(), lambda, f.name()), {}};
  s.problem.h = coset_system(values, f.lattice());
  if (s.regular.lambda > 0) {
    s.problem.d = coset_system(s.regular.regulariser, f.lattice());
    s.problem.mu = s.regular.mu;
  }
  return s;
}

}  // namespace

// ---------------------------------------------------------------------------------------------

PrefilterTaps lattice_values(const SplineFilter& f) {
  const CosetLattice& lattice = f.lattice();
  const StencilReach r = f.reach();
  const int d = lattice.period();
  // M(k - j0) != 0 needs j0 in the stencil of k, floor(k + c) + [lo, hi]: k lies within the
  // reach of j0. A volume of three reaches per axis holds every such k with its own stencil.
  int span = 0;
  for (int a = 0; a < 3; ++a) span = std::max(span, r.hi[a] - r.lo[a] + 2);
  const int cells = (3 * span + d - 1) / d + 2;
  LatticeVolume<double> delta(lattice, {cells, cells, cells}, 1.0, {0, 0, 0});
  const int middle = cells / 2;
  delta(0, middle, middle, middle) = 1;
  const LatticePoint j0 = delta.lattice_point(0, middle, middle, middle);
  const Box region = evaluable_region(delta, f);
  std::vector<Vec3> points;
  std::vector<LatticePoint> at;
  for (int k = 0; k < cells; ++k)
    for (int j = 0; j < cells; ++j)
      for (int i = 0; i < cells; ++i)
        for (int c = 0; c < lattice.coset_count(); ++c) {
          const LatticePoint p = delta.lattice_point(c, i, j, k);
          const Vec3 x{static_cast<double>(p[0]), static_cast<double>(p[1]),
                       static_cast<double>(p[2])};
          bool inside = true;
          for (int a = 0; a < 3; ++a)
            inside = inside && x[a] >= region.min[a] && x[a] < region.max[a];
          if (!inside) continue;
          points.push_back(x);
          at.push_back(p);
        }
  std::vector<double> values(points.size());
  Reconstructor<double>(delta, f).evaluate(points, values);
  double largest = 0;
  for (double v : values) largest = std::max(largest, std::abs(v));
  PrefilterTaps out;
  for (std::size_t p = 0; p < values.size(); ++p)
    if (std::abs(values[p]) > 1e-13 * largest)
      out.push_back({{static_cast<int>(at[p][0] - j0[0]), static_cast<int>(at[p][1] - j0[1]),
                      static_cast<int>(at[p][2] - j0[2])},
                     values[p]});
  if (out.empty())
    throw std::invalid_argument(fmt::format("filter {} is zero at every lattice point", f.name()));
  return out;
}

namespace {

// s(k) = sum_o M(o) c(k - o) at every sample, read from the transform (sample index i at
// transform index i + padding), against the samples: the residual's max and RMS relative to
// max |V|.
template <class T>
void residual_at_samples(CosetTransform& x, const LatticeVolume<T>& samples,
                         const PrefilterTaps& values, InterpolationReport& r) {
  const CosetLattice& lattice = samples.lattice();
  const int k_count = lattice.coset_count();
  // Each tap of coset c reads a fixed step in the transform's storage from the sample (0, i, j, k)
  // at transform index (i, j, k) + padding: the read's coset, and its delta (|delta| <= padding).
  struct Read {
    std::ptrdiff_t step;
    double weight;
  };
  const double* origin = &x.real(0, r.padding, r.padding, r.padding);
  std::vector<std::vector<Read>> reads(static_cast<std::size_t>(k_count));
  for (int c = 0; c < k_count; ++c)
    for (const auto& [o, w] : values) {
      const TapStep step = tap_step(lattice, c, o);
      const int at[3] = {r.padding + static_cast<int>(step.delta[0]),
                         r.padding + static_cast<int>(step.delta[1]),
                         r.padding + static_cast<int>(step.delta[2])};
      reads[static_cast<std::size_t>(c)].push_back(
          {&x.real(step.coset, at[0], at[1], at[2]) - origin, w});
    }
  const Sizes& n = samples.sizes();
  double largest = 0, worst = 0, sum2 = 0;
#pragma omp parallel for schedule(dynamic, 1) num_threads(batch_threads()) \
    reduction(max : largest, worst) reduction(+ : sum2)
  for (int k = 0; k < n[2]; ++k)
    for (int j = 0; j < n[1]; ++j)
      for (int c = 0; c < k_count; ++c) {
        const double* row = &x.real(0, r.padding, j + r.padding, k + r.padding);
        const std::vector<Read>& taps = reads[static_cast<std::size_t>(c)];
        for (int i = 0; i < n[0]; ++i) {
          double s = 0;
          for (const Read& read : taps) s += read.weight * row[i + read.step];
          const double v = static_cast<double>(samples(c, i, j, k));
          largest = std::max(largest, std::abs(v));
          worst = std::max(worst, std::abs(s - v));
          sum2 += (s - v) * (s - v);
        }
      }
  const double count = static_cast<double>(samples.sample_count());
  r.residual_max = largest > 0 ? worst / largest : 0;
  r.residual_rms = largest > 0 ? std::sqrt(sum2 / count) / largest : 0;
}

}  // namespace

int interpolation_margin(const SplineFilter& f, std::optional<double> lambda) {
  require_few_cosets(f.lattice());
  const PrefilterTaps values = lattice_values(f);
  return f.required_margin(PrefilterChoice::None) +
         decay_radius(setup(f, values, lambda).problem, kMarginDecay);
}

template <class T>
LatticeVolume<T> interpolate(LatticeVolume<T> samples, const SplineFilter& f,
                             const InterpolationOptions& options, InterpolationReport* report) {
  f.check_lattice(samples.lattice());
  const CosetLattice lattice = samples.lattice();
  const Sizes n = samples.sizes();
  require_few_cosets(lattice);
  for (int a = 0; a < 3; ++a)
    if (n[a] < 2)
      throw std::invalid_argument(fmt::format(
          "volume of {} x {} x {} samples per coset is too small for interpolation (it needs at "
          "least 2 per axis)",
          n[0], n[1], n[2]));
  const PrefilterTaps values = lattice_values(f);
  InterpolationReport r;
  const Setup s = setup(f, values, options.lambda);
  r.symbol = s.regular.symbol;
  r.lambda = s.regular.lambda;

  // Padding: the inverse filter's decay, and at least the margins the result and the residual
  // keep beyond the samples.
  const int reconstruction = f.required_margin(PrefilterChoice::None);
  const int residual_margin = prefilter_margin(values, lattice);  // the reads of the residual
  const bool want_residual = options.residual || r.lambda > 0;
  r.margin = options.boundary == Boundary::Strict ? 0 : reconstruction;
  r.padding =
      std::max({decay_radius(s.problem, r.lambda > 0 ? kRegularisedPaddingDecay : kPaddingDecay),
                r.margin, want_residual ? residual_margin : 0});
  int extra = 0;
  for (int a = 0; a < 3; ++a) {
    const std::int64_t want = std::int64_t{n[a]} + 2 * std::int64_t{r.padding};
    if (want > LatticeVolume<T>::kMaxSize)
      throw std::invalid_argument(fmt::format(
          "volume of {} samples per coset along an axis is too large for interpolation", n[a]));
    r.transform[a] = smooth_size(static_cast<int>(want));
    extra = std::max(extra, r.transform[a] - static_cast<int>(want));
  }
  // Transform index i holds sample index i - padding; the extension reaches the far side.
  const Extension e(lattice, n, r.padding + extra,
                    options.boundary == Boundary::Clamp ? Boundary::Clamp : Boundary::Mirror);
  r.extension = e.applied();
  const int shift = extra;  // extension index = transform index + shift
  const int k_count = lattice.coset_count();
  CosetTransform x(k_count, r.transform);
  {
    const std::span<const T> in = samples.samples();
    const int first = r.padding, last = r.padding + n[0];  // transform indices of samples along x
#pragma omp parallel for schedule(dynamic, 1) num_threads(batch_threads())
    for (int k = 0; k < r.transform[2]; ++k)
      for (int j = 0; j < r.transform[1]; ++j)
        for (int c = 0; c < k_count; ++c) {
          double* row = &x.real(c, 0, j, k);
          for (int i = 0; i < first; ++i)
            row[i] = static_cast<double>(in[e.source(c, i + shift, j + shift, k + shift)]);
          // Along x inside the samples the extension reads one coset at steps of K.
          const T* run = &in[e.source(c, first + shift, j + shift, k + shift)];
          for (int i = first; i < last; ++i)
            row[i] = static_cast<double>(
                run[static_cast<std::size_t>(k_count) * static_cast<std::size_t>(i - first)]);
          for (int i = last; i < r.transform[0]; ++i)
            row[i] = static_cast<double>(in[e.source(c, i + shift, j + shift, k + shift)]);
        }
  }
  x.forward();
  solve_all(x, s.problem);
  x.backward();
  if (want_residual) residual_at_samples(x, samples, values, r);
  // The coefficients of the samples and r.margin coset cells around them; the samples' memory
  // goes back first.
  Vec3 origin = samples.origin();
  const Vec3 spacing = samples.axis_spacing();
  (void)std::move(samples).release();
  Sizes sizes{};
  for (int a = 0; a < 3; ++a) {
    sizes[a] = n[a] + 2 * r.margin;
    origin[a] -= lattice.period() * spacing[a] * r.margin;
  }
  LatticeVolume<T> out(
      lattice, sizes, spacing, origin,
      std::vector<T>(static_cast<std::size_t>(k_count) * static_cast<std::size_t>(sizes[0]) *
                     static_cast<std::size_t>(sizes[1]) * static_cast<std::size_t>(sizes[2])));
  const int from = r.padding - r.margin;
#pragma omp parallel for schedule(dynamic, 1) num_threads(batch_threads())
  for (int k = 0; k < sizes[2]; ++k)
    for (int j = 0; j < sizes[1]; ++j)
      for (int i = 0; i < sizes[0]; ++i)
        for (int c = 0; c < k_count; ++c)
          out(c, i, j, k) = to_sample<T>(x.real(c, i + from, j + from, k + from));
  if (report) *report = r;
  return out;
}

template LatticeVolume<float> interpolate<float>(LatticeVolume<float>, const SplineFilter&,
                                                 const InterpolationOptions&, InterpolationReport*);
template LatticeVolume<double> interpolate<double>(LatticeVolume<double>, const SplineFilter&,
                                                   const InterpolationOptions&,
                                                   InterpolationReport*);

}  // namespace boxgen::runtime
