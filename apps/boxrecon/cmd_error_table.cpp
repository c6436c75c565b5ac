#include "apps/boxrecon/cmd_error_table.h"

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include <cmath>
#include <iostream>
#include <random>
#include <stdexcept>
#include <string>
#include <vector>

#include "generated/tricubic.hpp"
#include "generated/tricubic_prefilters.hpp"
#include "runtime/coefficients.h"
#include "runtime/prefilter.h"
#include "runtime/reconstruction.h"
#include "runtime/sampling.h"
#include "runtime/test_functions.h"

namespace boxgen::recon {

namespace {

using namespace boxgen::runtime;
namespace cubic = boxgen::generated::tricubic;

constexpr int kDensities[] = {17, 25, 33, 41, 57};

struct Row {
  int n;
  std::string filter, prefilter;
  double rms, max, gradient_rms;
  std::uint64_t samples;
  int cartesian_n = 0;  // tricubic rows: samples per axis of the Cartesian grid
};

struct Errors {
  double sum2 = 0, worst = 0, gsum2 = 0;
  void add(double value, const Vec3& gradient, const Vec3& p) {
    const double e = value - marschner_lobb(p);
    sum2 += e * e;
    worst = std::max(worst, std::abs(e));
    const Vec3 g = marschner_lobb_gradient(p);
    for (int d = 0; d < 3; ++d) gsum2 += (gradient[d] - g[d]) * (gradient[d] - g[d]);
  }
};

// f on its lattice with `per_axis` samples per coset and axis over [-1,1]^3 (the row of density
// n), after prefilter q (runtime/coefficients.h), with the margin q needs.
Row lattice_row(int n, int per_axis, const SplineFilter& f, PrefilterChoice q,
                const std::vector<Vec3>& points) {
  const LatticeVolume<double> volume = spline_coefficients(
      sample_lattice<double>(marschner_lobb,
                             cube_lattice_grid(f.lattice(), per_axis, f.required_margin(q))),
      f, q);
  std::vector<double> values(points.size());
  std::vector<Vec3> gradients(points.size());
  Reconstructor<double>(volume, f).evaluate(points, values, gradients);
  Errors e;
  for (std::size_t i = 0; i < points.size(); ++i) e.add(values[i], gradients[i], points[i]);
  const double k = static_cast<double>(points.size());
  const int cosets = f.lattice().coset_count();
  return {n,
          f.name(),
          q.text(),
          std::sqrt(e.sum2 / k),
          e.worst,
          std::sqrt(e.gsum2 / k),
          static_cast<std::uint64_t>(cosets) * per_axis * per_axis * per_axis,
          cosets == 1 ? per_axis : 0};
}

// The tricubic B-spline on the Cartesian grid of m^3 samples over [-1,1]^3 (spacing 2/(m-1)),
// evaluated by the evaluator boxgen emits for the preset `tricubic` (the registry's checked-in
// generated/tricubic.hpp), with its emitted prefilter q1 or none.
Row cartesian_row(int n, int m, bool q1, const std::vector<Vec3>& points) {
  const double h = 2.0 / (m - 1);
  const int margin = 4;  // stencil reach 2 (centred cubic) + prefilter 1, rounded up
  const int size = m + 2 * margin;
  auto index = [&](std::int64_t i, std::int64_t j, std::int64_t k) {
    return static_cast<std::size_t>(i + margin) +
           static_cast<std::size_t>(size) *
               (static_cast<std::size_t>(j + margin) +
                static_cast<std::size_t>(size) * static_cast<std::size_t>(k + margin));
  };
  std::vector<double> samples(static_cast<std::size_t>(size) * size * size);
  for (int k = -margin; k < m + margin; ++k)
    for (int j = -margin; j < m + margin; ++j)
      for (int i = -margin; i < m + margin; ++i)
        samples[index(i, j, k)] = marschner_lobb({-1 + h * i, -1 + h * j, -1 + h * k});
  std::vector<double> coefficients = samples;
  if (q1) {
    for (int k = 1 - margin; k < m + margin - 1; ++k)
      for (int j = 1 - margin; j < m + margin - 1; ++j)
        for (int i = 1 - margin; i < m + margin - 1; ++i) {
          double c = 0;
          for (const auto& t : cubic::q1)
            c += t.weight * samples[index(i - t.offset[0], j - t.offset[1], k - t.offset[2])];
          coefficients[index(i, j, k)] = c;
        }
  }
  Errors e;
  for (const Vec3& p : points) {
    const std::array<double, 3> u{(p[0] + 1) / h, (p[1] + 1) / h, (p[2] + 1) / h};
    std::array<double, 3> g{};
    const double v = cubic::evaluate<double>(
        u,
        [&](const cubic::Point& j) {
          for (int d = 0; d < 3; ++d)
            if (j[d] < 1 - margin || j[d] > m + margin - 2)
              throw std::logic_error("tricubic stencil outside the grid");
          return coefficients[index(j[0], j[1], j[2])];
        },
        &g);
    e.add(v, {g[0] / h, g[1] / h, g[2] / h}, p);
  }
  const double k = static_cast<double>(points.size());
  return {n,
          "tricubic",
          q1 ? "q1" : "none",
          std::sqrt(e.sum2 / k),
          e.worst,
          std::sqrt(e.gsum2 / k),
          static_cast<std::uint64_t>(m) * m * m,
          m};
}

}  // namespace

int run_error_table(int points, std::uint64_t seed, bool json) {
  if (points < 1 || points > 10000000)
    throw std::invalid_argument("--points must be between 1 and 10000000");
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  std::vector<Vec3> at(points);
  for (auto& p : at) p = {u(rng), u(rng), u(rng)};  // the same points for every row
  std::vector<Row> rows;
  for (int n : kDensities) {
    for (const char* name : {"m7", "m8", "m12"})
      for (const PrefilterChoice q :
           {PrefilterChoice::None, PrefilterChoice::Q1, PrefilterChoice::Q2, PrefilterChoice::Q2Opt,
            PrefilterChoice::qfir(3), PrefilterChoice::interp()})
        rows.push_back(lattice_row(n, n, SplineFilter::parse(name), q, at));
    const int m = static_cast<int>(std::lround(std::cbrt(2.0) * n));  // the same number of samples
    rows.push_back(cartesian_row(n, m, false, at));
    rows.push_back(cartesian_row(n, m, true, at));
    rows.push_back(
        lattice_row(n, m, SplineFilter::parse("tricubic"), PrefilterChoice::interp(), at));
  }
  if (json) {
    nlohmann::json out{
        {"function", "ml"}, {"points", points}, {"seed", seed}, {"rows", nlohmann::json::array()}};
    for (const auto& r : rows) {
      nlohmann::json j{{"n", r.n},
                       {"filter", r.filter},
                       {"prefilter", r.prefilter},
                       {"rms", r.rms},
                       {"max", r.max},
                       {"gradient_rms", r.gradient_rms},
                       {"samples", r.samples}};
      if (r.cartesian_n) j["cartesian_n"] = r.cartesian_n;
      out["rows"].push_back(j);
    }
    std::cout << out.dump(2) << '\n';
    return 0;
  }
  std::string text = fmt::format(
      "Marschner-Lobb reconstruction error over {} random points of [-1,1]^3 (seed {})\n", points,
      seed);
  text += fmt::format("{:>4} {:<9} {:<6} {:>10} {:>12} {:>12} {:>13}\n", "N", "filter", "pre",
                      "samples", "rms", "max", "gradient_rms");
  for (const auto& r : rows)
    text += fmt::format("{:>4} {:<9} {:<6} {:>10} {:>12.5e} {:>12.5e} {:>13.5e}{}\n", r.n, r.filter,
                        r.prefilter, r.samples, r.rms, r.max, r.gradient_rms,
                        r.cartesian_n ? fmt::format("  (Cartesian {}^3)", r.cartesian_n) : "");
  std::cout << text;
  return 0;
}

}  // namespace boxgen::recon
