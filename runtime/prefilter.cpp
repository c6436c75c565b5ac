#include "runtime/prefilter.h"

#include "runtime/batch_threads.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <stdexcept>

#include "runtime/lattice_limits.h"
#include "support/integer_math.h"

namespace boxgen::runtime {

using support::floor_div;

namespace {

void validate_on(const PrefilterTaps& q, const CosetLattice& lattice) {
  if (q.empty()) throw std::invalid_argument("prefilter has no taps");
  for (const auto& [o, w] : q) {
    for (int x : o)
      if (x < -kMaxLatticeEntry || x > kMaxLatticeEntry)
        throw std::invalid_argument(
            fmt::format("prefilter offset ({}, {}, {}) is too far out (at most {} per coordinate)",
                        o[0], o[1], o[2], kMaxLatticeEntry));
    if (!lattice.contains(o[0], o[1], o[2]))
      throw std::invalid_argument(
          fmt::format("prefilter offset ({}, {}, {}) is not a {} lattice vector", o[0], o[1], o[2],
                      lattice.label()));
    if (!std::isfinite(w))
      throw std::invalid_argument(fmt::format(
          "prefilter weight {} at offset ({}, {}, {}) is not finite", w, o[0], o[1], o[2]));
  }
}

}  // namespace

TapStep tap_step(const CosetLattice& lattice, int c, const std::array<int, 3>& o) {
  const Offset& from = lattice.offsets()[static_cast<std::size_t>(c)];
  const std::int64_t p[3] = {static_cast<std::int64_t>(from[0]) - o[0],
                             static_cast<std::int64_t>(from[1]) - o[1],
                             static_cast<std::int64_t>(from[2]) - o[2]};
  TapStep step{lattice.coset_of(p[0], p[1], p[2]), {}};
  const Offset& to = lattice.offsets()[static_cast<std::size_t>(step.coset)];
  for (int a = 0; a < 3; ++a) step.delta[a] = floor_div(p[a] - to[a], lattice.period());  // exact
  return step;
}

int prefilter_margin(const PrefilterTaps& q, const CosetLattice& lattice) {
  const PrefilterShrink s = prefilter_shrink(q, lattice);
  int margin = 0;
  for (int a = 0; a < 3; ++a) margin = std::max({margin, s.lower[a], s.upper[a]});
  return margin;
}

PrefilterShrink prefilter_shrink(const PrefilterTaps& q, const CosetLattice& lattice) {
  validate_on(q, lattice);
  std::array<std::int64_t, 3> lowest{0, 0, 0}, highest{0, 0, 0};
  for (int c = 0; c < lattice.coset_count(); ++c)
    for (const auto& tap : q) {
      const TapStep step = tap_step(lattice, c, tap.first);
      for (int a = 0; a < 3; ++a) {
        lowest[a] = std::min(lowest[a], step.delta[a]);
        highest[a] = std::max(highest[a], step.delta[a]);
      }
    }
  PrefilterShrink shrink{};
  for (int a = 0; a < 3; ++a) {
    shrink.lower[a] = static_cast<int>(-lowest[a]);  // |delta| <= 2^20 + 1: fits
    shrink.upper[a] = static_cast<int>(highest[a]);
  }
  return shrink;
}

template <class T>
LatticeVolume<T> prefilter(const LatticeVolume<T>& volume, const PrefilterTaps& q) {
  const CosetLattice& lattice = volume.lattice();
  const PrefilterShrink shrink = prefilter_shrink(q, lattice);
  const Sizes& n = volume.sizes();
  Sizes out_sizes{};
  Vec3 out_origin{};
  for (int a = 0; a < 3; ++a) {
    out_sizes[a] = n[a] - shrink.lower[a] - shrink.upper[a];
    if (out_sizes[a] < 1)
      throw std::invalid_argument(
          fmt::format("volume of {} x {} x {} samples per coset is too small for the prefilter (it "
                      "needs more than {} per axis to keep any sample)",
                      n[0], n[1], n[2], shrink.lower[a] + shrink.upper[a]));
    out_origin[a] =
        volume.origin()[a] + lattice.period() * volume.axis_spacing()[a] * shrink.lower[a];
  }
  LatticeVolume<T> out(lattice, out_sizes, volume.axis_spacing(), out_origin,
                       std::vector<T>(static_cast<std::size_t>(volume.coset_count()) *
                                      static_cast<std::size_t>(out_sizes[0]) *
                                      static_cast<std::size_t>(out_sizes[1]) *
                                      static_cast<std::size_t>(out_sizes[2])));

  // Tap t of output coset c reads input coset c' at index (i + s + delta): a fixed step in storage
  // from the input sample (c, i + s, j + s, k + s).
  const int k_count = volume.coset_count();
  const std::size_t taps = q.size();
  std::vector<std::ptrdiff_t> step(static_cast<std::size_t>(k_count) * taps);
  const std::ptrdiff_t stride_i = k_count, stride_j = stride_i * n[0], stride_k = stride_j * n[1];
  for (int c = 0; c < k_count; ++c)
    for (std::size_t t = 0; t < taps; ++t) {
      const TapStep s = tap_step(lattice, c, q[t].first);
      step[static_cast<std::size_t>(c) * taps + t] =
          (s.coset - c) + stride_i * s.delta[0] + stride_j * s.delta[1] + stride_k * s.delta[2];
    }
  const T* in = volume.samples().data();
  // Slices are independent: on batch_threads() threads (a 35 M-sample scan in a second).
#pragma omp parallel for schedule(dynamic, 1) num_threads(batch_threads())
  for (int k = 0; k < out_sizes[2]; ++k)
    for (int j = 0; j < out_sizes[1]; ++j)
      for (int i = 0; i < out_sizes[0]; ++i)
        for (int c = 0; c < k_count; ++c) {
          const auto base = static_cast<std::ptrdiff_t>(
              volume.index(c, i + shrink.lower[0], j + shrink.lower[1], k + shrink.lower[2]));
          const std::ptrdiff_t* steps = &step[static_cast<std::size_t>(c) * taps];
          double sum = 0;
          for (std::size_t t = 0; t < taps; ++t)
            sum += q[t].second * static_cast<double>(in[base + steps[t]]);
          out(c, i, j, k) = to_sample<T>(sum);
        }
  return out;
}

template <class T>
LatticeVolume<T> gaussian_smooth(const LatticeVolume<T>& volume, double sigma) {
  if (volume.coset_count() != 1 || volume.period() != 1)
    throw std::invalid_argument(fmt::format(
        "a Gaussian low-pass needs a Cartesian volume, not a {} one", volume.lattice().label()));
  if (!std::isfinite(sigma) || sigma <= 0 || sigma > 1000)
    throw std::invalid_argument(
        fmt::format("Gaussian width {} must be finite, > 0 and at most 1000 samples", sigma));
  const int radius = static_cast<int>(std::ceil(3 * sigma));
  std::vector<double> weights;
  double total = 0;
  for (int t = -radius; t <= radius; ++t) {
    weights.push_back(std::exp(-0.5 * t * t / (sigma * sigma)));
    total += weights.back();
  }
  for (double& w : weights) w /= total;
  Sizes n = volume.sizes();
  Vec3 origin = volume.origin();
  std::vector<T> data(volume.samples().begin(), volume.samples().end());
  for (int axis = 0; axis < 3; ++axis) {
    Sizes m = n;
    m[axis] -= 2 * radius;
    if (m[axis] < 1)
      throw std::invalid_argument(fmt::format(
          "volume of {} x {} x {} samples is too small for a Gaussian of width {} (it needs more "
          "than {} samples per axis)",
          volume.sizes()[0], volume.sizes()[1], volume.sizes()[2], sigma, 2 * radius));
    const std::ptrdiff_t stride[3] = {1, n[0], static_cast<std::ptrdiff_t>(n[0]) * n[1]};
    std::vector<T> next(static_cast<std::size_t>(m[0]) * static_cast<std::size_t>(m[1]) *
                        static_cast<std::size_t>(m[2]));
#pragma omp parallel for schedule(dynamic, 1) num_threads(batch_threads())
    for (int k = 0; k < m[2]; ++k)
      for (int j = 0; j < m[1]; ++j)
        for (int i = 0; i < m[0]; ++i) {
          const int p[3] = {i, j, k};
          std::ptrdiff_t centre = 0;  // the input sample under output (i, j, k)
          for (int a = 0; a < 3; ++a) centre += (p[a] + (a == axis ? radius : 0)) * stride[a];
          double sum = 0;
          // Tap w reads the sample w - radius steps along the axis from the centre.
          const std::ptrdiff_t first = centre - static_cast<std::ptrdiff_t>(radius) * stride[axis];
          for (std::size_t w = 0; w < weights.size(); ++w)
            sum += weights[w] * static_cast<double>(data[static_cast<std::size_t>(
                                    first + static_cast<std::ptrdiff_t>(w) * stride[axis])]);
          next[static_cast<std::size_t>(i) +
               static_cast<std::size_t>(m[0]) *
                   (static_cast<std::size_t>(j) +
                    static_cast<std::size_t>(m[1]) * static_cast<std::size_t>(k))] =
              to_sample<T>(sum);
        }
    data = std::move(next);
    n = m;
    origin[axis] += radius * volume.axis_spacing()[axis];
  }
  return LatticeVolume<T>(volume.lattice(), n, volume.axis_spacing(), origin, std::move(data));
}

template LatticeVolume<float> gaussian_smooth<float>(const LatticeVolume<float>&, double);
template LatticeVolume<double> gaussian_smooth<double>(const LatticeVolume<double>&, double);
template LatticeVolume<float> prefilter<float>(const LatticeVolume<float>&, const PrefilterTaps&);
template LatticeVolume<double> prefilter<double>(const LatticeVolume<double>&,
                                                 const PrefilterTaps&);

}  // namespace boxgen::runtime
