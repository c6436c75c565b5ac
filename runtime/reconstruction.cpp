#include "runtime/reconstruction.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <exception>
#include <mutex>
#include <stdexcept>
#include <thread>

#include "generated/m12.hpp"
#include "generated/m12_prefilters.hpp"
#include "generated/m7.hpp"
#include "generated/m7_prefilters.hpp"
#include "generated/m8.hpp"
#include "generated/m8_prefilters.hpp"

namespace boxgen::runtime {

namespace {

template <class Tap, std::size_t N>
DiscreteFilter taps(const Tap (&table)[N]) {
  DiscreteFilter out;
  for (const auto& t : table) out.push_back({{t.offset[0], t.offset[1], t.offset[2]}, t.weight});
  return out;
}

// Calls the generated evaluator of the filter; x in lattice coordinates.
template <class T, class Fetch>
T evaluate_generated(Filter f, const std::array<T, 3>& x, Fetch&& fetch, std::array<T, 3>* g) {
  switch (f) {
    case Filter::M7: return generated::m7::evaluate<T>(x, fetch, g);
    case Filter::M8: return generated::m8::evaluate<T>(x, fetch, g);
    case Filter::M12: return generated::m12::evaluate<T>(x, fetch, g);
  }
  throw std::logic_error("unknown filter");
}

// The reach the generator computed and published with each evaluator (kStencilReachLo/Hi).
template <class Reach>
StencilReach published_reach(const Reach& lo, const Reach& hi, const double (&centre)[3]) {
  StencilReach reach;
  for (int a = 0; a < 3; ++a) {
    reach.lo[a] = lo[a];
    reach.hi[a] = hi[a];
    reach.centre[a] = centre[a];
  }
  return reach;
}

}  // namespace

Filter parse_filter(std::string_view name) {
  if (name == "m7") return Filter::M7;
  if (name == "m8") return Filter::M8;
  if (name == "m12") return Filter::M12;
  throw std::invalid_argument(fmt::format("unknown filter '{}': expected m7, m8 or m12", name.substr(0, 40)));
}

PrefilterChoice parse_prefilter(std::string_view name) {
  if (name == "none") return PrefilterChoice::None;
  if (name == "q1") return PrefilterChoice::Q1;
  if (name == "q2") return PrefilterChoice::Q2;
  throw std::invalid_argument(fmt::format("unknown prefilter '{}': expected none, q1 or q2", name.substr(0, 40)));
}

const char* filter_name(Filter f) {
  switch (f) {
    case Filter::M7: return "m7";
    case Filter::M8: return "m8";
    case Filter::M12: return "m12";
  }
  return "?";
}

DiscreteFilter prefilter_taps(Filter f, PrefilterChoice q) {
  if (q == PrefilterChoice::None) return {{{0, 0, 0}, 1.0}};
  const bool first = q == PrefilterChoice::Q1;
  switch (f) {
    case Filter::M7: return first ? taps(generated::m7::q1) : taps(generated::m7::q2);
    case Filter::M8: return first ? taps(generated::m8::q1) : taps(generated::m8::q2);
    case Filter::M12: return first ? taps(generated::m12::q1) : taps(generated::m12::q2);
  }
  throw std::logic_error("unknown filter");
}

StencilReach stencil_reach(Filter f) {
  switch (f) {
    case Filter::M7: return published_reach(generated::m7::kStencilReachLo, generated::m7::kStencilReachHi, generated::m7::kCentre);
    case Filter::M8: return published_reach(generated::m8::kStencilReachLo, generated::m8::kStencilReachHi, generated::m8::kCentre);
    case Filter::M12: return published_reach(generated::m12::kStencilReachLo, generated::m12::kStencilReachHi, generated::m12::kCentre);
  }
  throw std::logic_error("unknown filter");
}

int required_margin(Filter f, PrefilterChoice q) {
  // Evaluation needs -lo - c <= x < 2N - hi - c in the volume's lattice coordinates (resample.h).
  // A margin of m coset cells puts [-1,1] at [2m, 2N - 2m - 2], so it needs 2m >= -lo - c and
  // 2m > hi + c - 2; we add one unit of slack to each for rounding at the faces. Then the
  // prefilter's own reach.
  const StencilReach r = stencil_reach(f);
  double need = 0;
  for (int a = 0; a < 3; ++a) need = std::max({need, -r.lo[a] - r.centre[a], r.hi[a] + r.centre[a] - 2});
  const int reconstruction = static_cast<int>(std::ceil((need + 1) / 2));
  return reconstruction + (q == PrefilterChoice::None ? 0 : prefilter_margin(prefilter_taps(f, q)));
}

template <class T>
T Reconstructor<T>::value(const Vec3& world, Vec3* gradient) const {
  for (double c : world)
    if (!std::isfinite(c)) throw std::invalid_argument("point has a non-finite coordinate");
  const Vec3 lattice = volume_.to_lattice(world);
  const std::array<T, 3> x{static_cast<T>(lattice[0]), static_cast<T>(lattice[1]), static_cast<T>(lattice[2])};
  // Far outside the volume, stop before the evaluator converts floor(x) to an integer (which
  // would overflow for huge coordinates); the stencil's reach is far smaller than kFar.
  constexpr double kFar = 64;
  for (int a = 0; a < 3; ++a)
    if (!(lattice[a] > -kFar && lattice[a] < 2.0 * volume_.sizes()[a] + kFar))
      throw std::out_of_range(fmt::format("world point ({}, {}, {}) is outside the volume", world[0], world[1], world[2]));
  std::array<T, 3> g{};
  // The evaluator fetches only within reach_ of its unit cube floor(x + c), computed here exactly
  // as it computes it (in T). Inside the volume with that whole box, no fetch needs a check;
  // near the border each fetch is checked, so only a point that really needs outside data fails.
  LatticePoint lo, hi;
  for (int a = 0; a < 3; ++a) {
    const auto corner = static_cast<std::int64_t>(std::floor(x[a] + static_cast<T>(reach_.centre[a])));
    lo[a] = corner + reach_.lo[a];
    hi[a] = corner + reach_.hi[a];
  }
  T v;
  if (volume_.contains_box(lo, hi)) {
    v = evaluate_generated<T>(
        filter_, x, [&](const LatticePoint& j) { return volume_.value_unchecked(j); }, gradient ? &g : nullptr);
  } else {
    try {
      v = evaluate_generated<T>(filter_, x, [&](const LatticePoint& j) { return volume_.value(j); }, gradient ? &g : nullptr);
    } catch (const std::out_of_range& e) {  // name the point the user asked for, then the sample
      throw std::out_of_range(fmt::format("world point ({}, {}, {}) needs a sample outside the volume: {}", world[0], world[1],
                                          world[2], e.what()));
    }
  }
  if (gradient)
    for (int i = 0; i < 3; ++i) (*gradient)[i] = static_cast<double>(g[i]) / volume_.spacing();
  return v;
}

template <class T>
void Reconstructor<T>::evaluate(std::span<const Vec3> points, std::span<T> values, std::span<Vec3> gradients) const {
  if (values.size() != points.size() || (!gradients.empty() && gradients.size() != points.size()))
    throw std::invalid_argument("evaluate: output sizes differ from the number of points");
  const std::size_t workers =
      std::max<std::size_t>(1, std::min<std::size_t>(std::thread::hardware_concurrency(), points.size() / 256 + 1));
  std::mutex mutex;
  std::size_t first_bad = points.size();
  std::string first_error;
  auto work = [&](std::size_t begin, std::size_t end) {
    for (std::size_t i = begin; i < end; ++i) {
      try {
        values[i] = value(points[i], gradients.empty() ? nullptr : &gradients[i]);
      } catch (const std::exception& e) {
        std::lock_guard<std::mutex> lock(mutex);
        if (i < first_bad) first_bad = i, first_error = e.what();
        return;
      }
    }
  };
  std::vector<std::thread> threads;
  const std::size_t chunk = (points.size() + workers - 1) / workers;
  for (std::size_t w = 0; w < workers; ++w) {
    const std::size_t begin = w * chunk, end = std::min(points.size(), begin + chunk);
    if (begin < end) threads.emplace_back(work, begin, end);
  }
  for (auto& t : threads) t.join();
  if (first_bad < points.size()) throw std::out_of_range(fmt::format("point {}: {}", first_bad + 1, first_error));
}

template class Reconstructor<float>;
template class Reconstructor<double>;

}  // namespace boxgen::runtime
