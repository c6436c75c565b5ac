// Percentiles of a volume's samples as NumPy computes them by default (np.percentile, method
// "linear"): for a fraction p the value at rank h = p (n - 1) of the sorted samples, linear between
// the two nearest ranks. The one implementation behind render's default iso and slice's default
// window.
#pragma once
#include <algorithm>
#include <cmath>
#include <cstddef>
#include <initializer_list>
#include <span>
#include <stdexcept>
#include <vector>

namespace boxgen::runtime {

// The percentiles at `fractions` (each in [0, 1]) of the samples that are not NaN. Throws
// std::invalid_argument when there are none.
template <class T>
std::vector<double> percentiles(std::span<const T> samples,
                                std::initializer_list<double> fractions) {
  std::vector<T> values;
  values.reserve(samples.size());
  for (const T& s : samples)
    if (!std::isnan(static_cast<double>(s))) values.push_back(s);
  if (values.empty()) throw std::invalid_argument("the volume has no samples");
  std::vector<double> out;
  for (const double p : fractions) {
    const double h = std::clamp(p, 0.0, 1.0) * static_cast<double>(values.size() - 1);
    const auto lo = static_cast<std::size_t>(std::floor(h));
    const auto at = values.begin() + static_cast<std::ptrdiff_t>(lo);
    std::nth_element(values.begin(), at, values.end());
    const auto a = static_cast<double>(*at);
    if (lo + 1 == values.size()) {
      out.push_back(a);
      continue;
    }
    // The next rank: the smallest of the elements after lo.
    const auto b = static_cast<double>(*std::min_element(at + 1, values.end()));
    out.push_back(a + (h - static_cast<double>(lo)) * (b - a));
  }
  return out;
}

}  // namespace boxgen::runtime
