#include "runtime/reconstruction.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <exception>
#include <stdexcept>
#include <string>

#include "generated/registry.hpp"
#include "runtime/batch_threads.h"
#include "runtime/lattice_reconstruction.h"
#include "runtime/simd_batch.h"

namespace boxgen::runtime {

namespace generated = boxgen::generated;
namespace support = boxgen::generated::support;

namespace {

// Filter::M7, M8, M12: the registry's first entries (its other filters are on other lattices and
// reach the apps through lattice_filters.h).
constexpr const char* kRegistryOrder[] = {"m7", "m8", "m12"};
static_assert(std::size(kRegistryOrder) <= generated::kFilterCount,
              "Filter must name the registry's first filters");
constexpr int kBccFilterCount = static_cast<int>(std::size(kRegistryOrder));

// The Filter enum is an index into the registry; its names must agree with it.
int registry_index(Filter f) {
  const int index = static_cast<int>(f);
  if (index < 0 || index >= kBccFilterCount) throw std::logic_error("unknown filter");
  return index;
}

}  // namespace

Filter parse_filter(std::string_view name) {
  for (int i = 0; i < kBccFilterCount; ++i)
    if (name == generated::kFilterNames[i]) return static_cast<Filter>(i);
  throw std::invalid_argument(
      fmt::format("unknown filter '{}': expected m7, m8 or m12", name.substr(0, 40)));
}

PrefilterChoice parse_prefilter(std::string_view name) {
  if (name == "none") return PrefilterChoice::None;
  if (name == "q1") return PrefilterChoice::Q1;
  if (name == "q2") return PrefilterChoice::Q2;
  throw std::invalid_argument(
      fmt::format("unknown prefilter '{}': expected none, q1 or q2", name.substr(0, 40)));
}

const char* filter_name(Filter f) {
  const int index = static_cast<int>(f);
  if (index < 0 || index >= kBccFilterCount) return "?";
  if (std::strcmp(generated::kFilterNames[index], kRegistryOrder[index]) != 0)
    throw std::logic_error("registry order");
  return generated::kFilterNames[index];
}

DiscreteFilter prefilter_taps(Filter f, PrefilterChoice q) {
  if (q == PrefilterChoice::None) return {{{0, 0, 0}, 1.0}};
  return generated::with_filter(registry_index(f), [&](auto entry) {
    return q == PrefilterChoice::Q1 ? prefilter_from(entry.q1) : prefilter_from(entry.q2);
  });
}

StencilReach stencil_reach(Filter f) {
  return generated::with_filter(registry_index(f), [](auto entry) {
    return published_reach<typename decltype(entry)::Traits>();
  });
}

int required_margin(Filter f, PrefilterChoice q) {
  // Evaluation needs -lo - c <= x < 2N - hi - c in the volume's lattice coordinates (resample.h).
  // A margin of m coset cells puts [-1,1] at [2m, 2N - 2m - 2], so it needs 2m >= -lo - c and
  // 2m > hi + c - 2; we add one unit of slack to each for rounding at the faces. Then the
  // prefilter's own reach.
  const StencilReach r = stencil_reach(f);
  double need = 0;
  for (int a = 0; a < 3; ++a)
    need = std::max({need, -r.lo[a] - r.centre[a], r.hi[a] + r.centre[a] - 2});
  const int reconstruction = static_cast<int>(std::ceil((need + 1) / 2));
  return reconstruction + (q == PrefilterChoice::None ? 0 : prefilter_margin(prefilter_taps(f, q)));
}

template <class T>
class EvaluationPath {
 public:
  virtual ~EvaluationPath() = default;
  // One point; gradient and hessian may be null (not computed).
  virtual T at(const Vec3& world, Vec3* gradient, Hessian* hessian) const = 0;
  virtual void batch(std::span<const Vec3> points, std::span<T> values, std::span<Vec3> gradients,
                     std::span<Hessian> hessians) const = 0;
};

namespace {

// The generated evaluator of one filter on one volume. The evaluator locates a point (its cell
// and the corner floor(x + c) its stencil is relative to, support::Located); inside the volume
// with the whole published reach around that corner, the stencil is fetched through offsets
// into samples() precomputed per cell; near the border each fetch is checked.
// Offset is std::int32_t where every offset fits (a smaller table stays in the L1 cache), else
// std::int64_t.
template <class Tr, class T, class Offset>
class FilterPath final : public EvaluationPath<T> {
  static constexpr int kStencil = Tr::kStencilSize;

 public:
  FilterPath(const BccVolume<T>& volume, int registry_index)
      : volume_(volume), registry_index_(registry_index) {
    static_assert(Tr::kDimension == 3, "the BCC runtime evaluates 3-D filters");
    // Sample (x, y, z) sits at x + N0 y + N0 N1 z - c (N0 + N0 N1), c = x & 1 its coset
    // (bcc_volume.h): linear in the point apart from the coset term. For j = corner + d the
    // coset is (corner_x & 1) ^ (d_x & 1), so one table per corner parity.
    const std::int64_t n0 = volume.sizes()[0], n1 = volume.sizes()[1];
    stride_ = {1, n0, n0 * n1};
    const std::int64_t coset_shift = n0 + n0 * n1;
    offsets_.resize(2 * Tr::kCellCount * kStencil);
    for (int parity = 0; parity < 2; ++parity)
      for (int cell = 0; cell < Tr::kCellCount; ++cell)
        for (int k = 0; k < kStencil; ++k) {
          const auto& d = Tr::kOffsets[cell][k];
          const int coset = parity ^ (d[0] & 1);
          offsets_[(parity * Tr::kCellCount + cell) * kStencil + k] =
              static_cast<Offset>(d[0] + n0 * d[1] + n0 * n1 * d[2] - coset * coset_shift);
        }
  }

  T at(const Vec3& world, Vec3* gradient, Hessian* hessian) const override {
    if (hessian) return point<support::kHessian>(world, gradient, hessian);
    if (gradient) return point<support::kGradient>(world, gradient, nullptr);
    return point<support::kValue>(world, nullptr, nullptr);
  }

  void batch(std::span<const Vec3> points, std::span<T> values, std::span<Vec3> gradients,
             std::span<Hessian> hessians) const override {
    if (!hessians.empty()) return loop<support::kHessian>(points, values, gradients, hessians);
    if (!gradients.empty()) return loop<support::kGradient>(points, values, gradients, hessians);
    loop<support::kValue>(points, values, gradients, hessians);
  }

 private:
  // Far outside the volume, stop before the evaluator converts floor(x) to an integer (which
  // would overflow for huge coordinates); the stencil's reach is far smaller than kFar.
  static constexpr double kFar = 64;

  template <int Order>
  T point(const Vec3& world, Vec3* gradient, Hessian* hessian) const {
    for (double c : world)
      if (!std::isfinite(c)) throw std::invalid_argument("point has a non-finite coordinate");
    const Vec3 lattice = volume_.to_lattice(world);
    for (int a = 0; a < 3; ++a)
      if (!(lattice[a] > -kFar && lattice[a] < 2.0 * volume_.sizes()[a] + kFar))
        throw std::out_of_range(fmt::format("world point ({}, {}, {}) is outside the volume",
                                            world[0], world[1], world[2]));
    const std::array<T, 3> x{static_cast<T>(lattice[0]), static_cast<T>(lattice[1]),
                             static_cast<T>(lattice[2])};
    const support::Located<3, T> located = support::locate<Tr>(x);
    T v[kStencil];
    const int size = Tr::kOrbitStencilSize[Tr::kCells[located.cell].orbit];
    LatticePoint lo, hi;
    for (int a = 0; a < 3; ++a) {
      lo[a] = located.corner[a] + Tr::kStencilReachLo[a];
      hi[a] = located.corner[a] + Tr::kStencilReachHi[a];
    }
    if (volume_.contains_box(lo, hi)) {
      const T* samples = volume_.samples().data();
      const std::int64_t base = located.corner[0] * stride_[0] + located.corner[1] * stride_[1] +
                                located.corner[2] * stride_[2];
      const Offset* offsets =
          &offsets_[((located.corner[0] & 1) * Tr::kCellCount + located.cell) * kStencil];
      for (int k = 0; k < size; ++k) v[k] = samples[base + offsets[k]];
    } else {
      try {
        for (int k = 0; k < size; ++k) {
          LatticePoint j;
          for (int a = 0; a < 3; ++a) j[a] = located.corner[a] + Tr::kOffsets[located.cell][k][a];
          v[k] = volume_.value(j);
        }
      } catch (const std::out_of_range& e) {  // name the point the user asked for, then the sample
        throw std::out_of_range(
            fmt::format("world point ({}, {}, {}) needs a sample outside the volume: {}", world[0],
                        world[1], world[2], e.what()));
      }
    }
    T d[3 + 6] = {};
    const T value = support::evaluate_located<Order, Tr>(located, v, d);
    const double h = volume_.spacing();
    if constexpr (Order >= support::kGradient)
      if (gradient)
        for (int i = 0; i < 3; ++i) (*gradient)[i] = static_cast<double>(d[i]) / h;
    if constexpr (Order >= support::kHessian)
      for (int i = 0; i < 6; ++i) (*hessian)[i] = static_cast<double>(d[3 + i]) / (h * h);
    return value;
  }

  // The first failing point of a batch and its error (the batch throws it at the end).
  struct FirstError {
    std::ptrdiff_t index;
    std::string what;
  };

  // One point on the scalar path, its error recorded.
  template <int Order>
  void scalar_point(std::ptrdiff_t i, std::span<const Vec3> points, std::span<T> values,
                    std::span<Vec3> gradients, std::span<Hessian> hessians,
                    FirstError& error) const {
    try {
      values[i] = point<Order>(points[i], gradients.empty() ? nullptr : &gradients[i],
                               hessians.empty() ? nullptr : &hessians[i]);
    } catch (const std::exception& e) {
#pragma omp critical(boxgen_batch_error)
      if (i < error.index) {
        error.index = i;
        error.what = e.what();
      }
    }
  }

  template <int Order>
  void loop(std::span<const Vec3> points, std::span<T> values, std::span<Vec3> gradients,
            std::span<Hessian> hessians) const {
    const std::ptrdiff_t count = static_cast<std::ptrdiff_t>(points.size());
    const int threads = batch_threads();
    FirstError error{count, {}};
    // The SIMD locate carries lattice coordinates as T: exact integers need 2N + kFar < 2^22.
    const bool small = std::ranges::all_of(volume_.sizes(), [](auto n) { return n < (1 << 20); });
    if (simd::enabled() && small) {
      // Blocks of consecutive points, each packed into SIMD chunks (simd_block).
      constexpr std::ptrdiff_t kBlock = 1024;
      const std::ptrdiff_t blocks = (count + kBlock - 1) / kBlock;
#pragma omp parallel for schedule(static) num_threads(threads) if (count > 256)
      for (std::ptrdiff_t b = 0; b < blocks; ++b)
        simd_block<Order>(b * kBlock, std::min(count, (b + 1) * kBlock), points, values, gradients,
                          hessians, error);
    } else {
#pragma omp parallel for schedule(static) num_threads(threads) if (count > 256)
      for (std::ptrdiff_t i = 0; i < count; ++i)
        scalar_point<Order>(i, points, values, gradients, hessians, error);
    }
    if (error.index < count)
      throw std::out_of_range(fmt::format("point {}: {}", error.index + 1, error.what));
  }

  // Points [first, last) in chunks of simd::kChunk: their world coordinates converted and located
  // in one SIMD call, their stencils gathered into lanes, the chunk's polynomial evaluated in one
  // SIMD call (runtime/simd_batch.h), the derivatives mapped back per lane. A point takes the
  // scalar path, point(), with its errors, when it is not finite or far outside, when its stencil
  // box is not inside the volume, when rounding put it on a knot plane (no cell in the table), or
  // when its orbit is not the chunk's.
  template <int Order>
  void simd_block(std::ptrdiff_t first, std::ptrdiff_t last, std::span<const Vec3> points,
                  std::span<T> values, std::span<Vec3> gradients, std::span<Hessian> hessians,
                  FirstError& error) const {
    constexpr std::ptrdiff_t kLanes = simd::kChunk;
    constexpr int kLocated = simd::locate_rows(3);
    constexpr int kOut =
        1 + (Order == support::kValue ? 0 : 3) + (Order == support::kHessian ? 6 : 0);
    alignas(64) double world[3 * kLanes];
    alignas(64) T located[kLocated * kLanes];
    alignas(64) T v[kStencil * kLanes];
    alignas(64) T out[kOut * kLanes];
    std::ptrdiff_t index[kLanes];
    const simd::Frame frame = simd_frame();
    const T* samples = volume_.samples().data();

    for (std::ptrdiff_t next = first; next < last;) {
      int lanes = 0;
      for (; next < last && lanes < kLanes; ++next, ++lanes) {
        for (int a = 0; a < 3; ++a) world[a * kLanes + lanes] = points[next][a];
        index[lanes] = next;
      }
      for (int lane = lanes; lane < kLanes; ++lane)  // a partial chunk: repeat lane 0
        for (int a = 0; a < 3; ++a) world[a * kLanes + lane] = world[a * kLanes];
      simd::locate_chunk(registry_index_, world, frame, located);

      // Gather the stencils of the lanes that stay; the others take the scalar path.
      const T* const cells = located + 3 * kLanes;
      const T* const reference = located + 4 * kLanes;
      const T* const orbits = located + 7 * kLanes;
      const T* const inside = located + 8 * kLanes;
      int orbit = -1, size = 0, first_lane = -1;
      bool stays[kLanes] = {};
      const T* bases[kLanes];
      const Offset* tables[kLanes];
      for (int lane = 0; lane < lanes; ++lane) {
        if (inside[lane] == T(0) || (orbit >= 0 && static_cast<int>(orbits[lane]) != orbit)) {
          scalar_point<Order>(index[lane], points, values, gradients, hessians, error);
          continue;
        }
        if (orbit < 0) {
          orbit = static_cast<int>(orbits[lane]);
          size = Tr::kOrbitStencilSize[orbit];
          first_lane = lane;
        }
        stays[lane] = true;
        const std::int64_t c[3] = {static_cast<std::int64_t>(located[lane]),
                                   static_cast<std::int64_t>(located[kLanes + lane]),
                                   static_cast<std::int64_t>(located[2 * kLanes + lane])};
        bases[lane] = samples + (c[0] * stride_[0] + c[1] * stride_[1] + c[2] * stride_[2]);
        tables[lane] =
            &offsets_[((c[0] & 1) * Tr::kCellCount + static_cast<int>(cells[lane])) * kStencil];
      }
      if (orbit < 0) continue;
      for (int lane = 0; lane < kLanes; ++lane)  // lanes that left or were never filled
        if (lane >= lanes || !stays[lane]) {
          bases[lane] = bases[first_lane];
          tables[lane] = tables[first_lane];
        }
      gather(size, bases, tables, v);
      simd::orbit_chunk(registry_index_, orbit, Order, v, reference, out, simd::kChunk);
      store<Order>(lanes, stays, index, cells, out, values, gradients, hessians);
    }
  }

  // The world-to-lattice frame and the bounds of locate_chunk.
  simd::Frame simd_frame() const {
    simd::Frame frame{};
    frame.h = volume_.spacing();
    frame.lower = -kFar;
    for (int a = 0; a < 3; ++a) {
      frame.origin[a] = volume_.origin()[a];
      frame.upper[a] = 2.0 * volume_.sizes()[a] + kFar;
      frame.limit[a] = 2.0 * volume_.sizes()[a] - 1;
    }
    return frame;
  }

  // The first `size` stencil values of every lane into v[k * kChunk + lane].
  static void gather(int size, const T* const* bases, const Offset* const* tables, T* v) {
    constexpr int kLanes = simd::kChunk;
    if constexpr (kStencil <= 64) {
      // Sample k of every lane, then k + 1: the lanes' cache misses overlap (M7, M8: 10% less
      // time than lane by lane, bench_instructions ... time).
      for (int k = 0; k < size; ++k) {
        T* const row = v + k * kLanes;
#pragma GCC unroll 16
        for (int lane = 0; lane < kLanes; ++lane) row[lane] = bases[lane][tables[lane][k]];
      }
    } else {
      // Lane by lane: fewer instructions per sample, which wins for large stencils (M12: 128).
      for (int lane = 0; lane < kLanes; ++lane) {
        const T* const base = bases[lane];
        const Offset* const table = tables[lane];
#pragma GCC unroll 16
        for (int k = 0; k < size; ++k) v[k * kLanes + lane] = base[table[k]];
      }
    }
  }

  // The chunk's results of the lanes that stayed, derivatives mapped back from the reference
  // frame of each lane's cell and scaled to world units.
  template <int Order>
  void store(int lanes, const bool* stays, const std::ptrdiff_t* index, const T* cells,
             const T* out, std::span<T> values, std::span<Vec3> gradients,
             std::span<Hessian> hessians) const {
    constexpr int kLanes = simd::kChunk;
    const double h = volume_.spacing();
    for (int lane = 0; lane < lanes; ++lane) {
      if (!stays[lane]) continue;
      const std::ptrdiff_t p = index[lane];
      values[p] = out[lane];
      if constexpr (Order >= support::kGradient) {
        T d[3 + 6];
        support::from_reference_frame<Order, Tr>(static_cast<int>(cells[lane]), out + kLanes + lane,
                                                 kLanes, d);
        for (int a = 0; a < 3; ++a) gradients[p][a] = static_cast<double>(d[a]) / h;
        if constexpr (Order >= support::kHessian)
          for (int a = 0; a < 6; ++a) hessians[p][a] = static_cast<double>(d[3 + a]) / (h * h);
      }
    }
  }

  const BccVolume<T>& volume_;
  int registry_index_;  // the filter's entry in generated/registry.hpp, for the SIMD kernels
  std::array<std::int64_t, 3> stride_{};
  std::vector<Offset> offsets_;  // [corner parity][cell][k]
};

}  // namespace

template <class T>
Reconstructor<T>::Reconstructor(const BccVolume<T>& volume, Filter filter)
    : path_(generated::with_filter(
          registry_index(filter),
          [&,
           index = registry_index(filter)](auto entry) -> std::shared_ptr<const EvaluationPath<T>> {
            using Tr = typename decltype(entry)::Traits;
            if constexpr (std::string_view(Tr::kLattice) != "bcc") {
              throw std::logic_error("not a BCC filter");  // registry_index() excludes it
            } else {
              // |offset| <= (max reach + 1) (1 + N0 + N0 N1): 32 bits suffice for all but huge
              // slabs.
              int reach = 0;
              for (int a = 0; a < 3; ++a)
                reach = std::max({reach, -Tr::kStencilReachLo[a], Tr::kStencilReachHi[a]});
              const double n0 = volume.sizes()[0], n1 = volume.sizes()[1];
              if ((reach + 1.0) * (1.0 + n0 + n0 * n1) < 2147483647.0)
                return std::make_shared<FilterPath<Tr, T, std::int32_t>>(volume, index);
              return std::make_shared<FilterPath<Tr, T, std::int64_t>>(volume, index);
            }
          })) {}

template <class T>
T Reconstructor<T>::value(const Vec3& world, Vec3* gradient) const {
  return path_->at(world, gradient, nullptr);
}

template <class T>
T Reconstructor<T>::value_gradient_hessian(const Vec3& world, Vec3& gradient,
                                           Hessian& hessian) const {
  return path_->at(world, &gradient, &hessian);
}

template <class T>
void Reconstructor<T>::evaluate(std::span<const Vec3> points, std::span<T> values,
                                std::span<Vec3> gradients) const {
  evaluate(points, values, gradients, {});
}

template <class T>
void Reconstructor<T>::evaluate(std::span<const Vec3> points, std::span<T> values,
                                std::span<Vec3> gradients, std::span<Hessian> hessians) const {
  if (values.size() != points.size() || (!gradients.empty() && gradients.size() != points.size()) ||
      (!hessians.empty() &&
       (hessians.size() != points.size() || gradients.size() != points.size())))
    throw std::invalid_argument("evaluate: output sizes differ from the number of points");
  path_->batch(points, values, gradients, hessians);
}

template class Reconstructor<float>;
template class Reconstructor<double>;

}  // namespace boxgen::runtime
