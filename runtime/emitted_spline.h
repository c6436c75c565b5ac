// The one evaluation engine of the runtime (docs/design.md §13): an emitted evaluator (its Traits,
// support/evaluator_support.hpp) on a volume, for one point (at) and for many (batch: OpenMP
// threads capped by batch_threads(), and the SIMD chunks of runtime/simd_batch.h for the filters
// of generated/registry.hpp). Reconstructor (reconstruction.h) reaches it through the
// EvaluationPath a filter makes (emitted_filter.h) with the Stencils that says where a point's
// stencil lies in the volume's storage (stencils.h):
//
//   using Sample = T; using Index = std::int32_t or std::int64_t;
//   const Volume& volume() const;  // to_lattice, spacing, origin
//   double extent(int a) const;    // lattice coordinates beyond extent + kFar are far outside
//   double last(int a) const;      // lattice coordinates of stored samples lie in [0, last]
//   bool contains_box(lo, hi) const;  // does the volume hold every lattice point of the box?
//   bool has_offsets() const;      // false: every fetch goes through sample()
//   std::optional<LinearLayout> linear() const;  // the storage's layout where it is linear
//   const T* samples() const;
//   Fetch<Index> fetch(const std::int64_t* corner, int cell) const;  // the stencil of a cell
//   T sample(const LatticePoint& j, bool inside) const;  // checked unless inside
//
// Border policy: a non-finite coordinate is std::invalid_argument; a point whose stencil leaves
// the volume is std::out_of_range (one line); the volume never invents data. A batch throws the
// first failing point's error, naming its index from 1.
#pragma once
#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <exception>
#include <limits>
#include <optional>
#include <span>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "runtime/batch_threads.h"
#include "runtime/simd_batch.h"
#include "runtime/stencil_steps.h"
#include "runtime/stencils.h"
#include "support/evaluator_support.hpp"

namespace boxgen::runtime {

template <class Tr, class Stencils>
class EmittedSpline {
  using T = typename Stencils::Sample;
  using Offset = typename Stencils::Index;
  static constexpr int kStencil = Tr::kStencilSize;
  static_assert(Tr::kDimension == 3, "volumes are 3-D");

 public:
  // registry_index: the evaluator's position in generated/registry.hpp, whose filters have SIMD
  // kernels (simd_batch.cpp); -1 for any other emitted evaluator (a user's own header, which
  // this header must not clash with: it includes no registry), which takes the scalar path.
  // kernels: the filter's own SIMD kernels (simd_batch.h), which a registry filter need not give.
  explicit EmittedSpline(Stencils stencils, int registry_index = -1,
                         const simd::Kernels* kernels = nullptr)
      : stencils_(std::move(stencils)),
        kernels_(kernels ? kernels : simd::registry_kernels(registry_index)) {
    prepare_chunks();
  }

  // One point; gradient and hessian may be null (not computed).
  T at(const Vec3& world, Vec3* gradient, Hessian* hessian) const {
    if (hessian) return point<generated::support::kHessian>(world, gradient, hessian);
    if (gradient) return point<generated::support::kGradient>(world, gradient, nullptr);
    return point<generated::support::kValue>(world, nullptr, nullptr);
  }

  // Many points; gradients and hessians empty (not computed) or as long as points (hessians need
  // gradients), else std::invalid_argument.
  void batch(std::span<const Vec3> points, std::span<T> values, std::span<Vec3> gradients,
             std::span<Hessian> hessians) const {
    namespace support = generated::support;
    if (values.size() != points.size() ||
        (!gradients.empty() && gradients.size() != points.size()) ||
        (!hessians.empty() &&
         (hessians.size() != points.size() || gradients.size() != points.size())))
      throw std::invalid_argument("evaluate: output sizes differ from the number of points");
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
    namespace support = generated::support;
    for (double c : world)
      if (!std::isfinite(c)) throw std::invalid_argument("point has a non-finite coordinate");
    const Vec3 lattice = stencils_.volume().to_lattice(world);
    for (int a = 0; a < 3; ++a)
      if (!(lattice[a] > -kFar && lattice[a] < stencils_.extent(a) + kFar))
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
    const bool inside = stencils_.contains_box(lo, hi);
    if (inside && stencils_.has_offsets()) {
      const std::int64_t corner[3] = {located.corner[0], located.corner[1], located.corner[2]};
      const Fetch<Offset> f = stencils_.fetch(corner, located.cell);
      const T* samples = stencils_.samples() + f.base;
      for (int k = 0; k < size; ++k) v[k] = samples[f.offsets[k]];
    } else {
      fetch_checked(located, world, inside, size, v);
    }
    T d[3 + 6] = {};
    const T value = support::evaluate_located<Order, Tr>(located, v, d);
    if constexpr (Order >= support::kGradient)
      to_world_derivatives<Order>(d, gradient ? gradient->data() : nullptr,
                                  hessian ? hessian->data() : nullptr);
    return value;
  }

  // The stencil sample by sample: unchecked when `inside`, else each checked (a sample outside
  // is std::out_of_range naming the point).
  void fetch_checked(const generated::support::Located<3, T>& located, const Vec3& world,
                     bool inside, int size, T* v) const {
    try {
      for (int k = 0; k < size; ++k) {
        LatticePoint j;
        for (int a = 0; a < 3; ++a) j[a] = located.corner[a] + Tr::kOffsets[located.cell][k][a];
        v[k] = stencils_.sample(j, inside);
      }
    } catch (const std::out_of_range& e) {  // name the point the user asked for, then the sample
      throw std::out_of_range(
          fmt::format("world point ({}, {}, {}) needs a sample outside the volume: {}", world[0],
                      world[1], world[2], e.what()));
    }
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

  // The SIMD path serves filters with kernels on volumes whose lattice coordinates it can carry as
  // exact integers in T (below 2^22) and whose stencils it can fetch through offsets.
  bool simd_serves() const {
    if (!kernels_ || !stencils_.has_offsets() || !simd::enabled()) return false;
    for (int a = 0; a < 3; ++a)
      if (!(stencils_.extent(a) + kFar < double(1 << 22))) return false;
    return true;
  }

  template <int Order>
  void loop(std::span<const Vec3> points, std::span<T> values, std::span<Vec3> gradients,
            std::span<Hessian> hessians) const {
    const std::ptrdiff_t count = static_cast<std::ptrdiff_t>(points.size());
    const int threads = batch_threads();
    FirstError error{count, {}};
    if (simd_serves()) {
      // Blocks of consecutive points, each packed into SIMD chunks (chunk_block on linear
      // volumes, else simd_block). Handed out one at a time: a thread that another process
      // slows down takes fewer blocks instead of holding the others up at the end.
      constexpr std::ptrdiff_t kBlock = 1024;
      const std::ptrdiff_t blocks = (count + kBlock - 1) / kBlock;
      const bool chunks = !linear_rows_.empty();
#pragma omp parallel for schedule(dynamic, 1) num_threads(threads) if (count > 256)
      for (std::ptrdiff_t b = 0; b < blocks; ++b) {
        const std::ptrdiff_t first = b * kBlock, last = std::min(count, (b + 1) * kBlock);
        if (chunks)
          chunk_block<Order>(first, last, points, values, gradients, hessians, error);
        else
          simd_block<Order>(first, last, points, values, gradients, hessians, error);
      }
    } else {
#pragma omp parallel for schedule(static) num_threads(threads) if (count > 256)
      for (std::ptrdiff_t i = 0; i < count; ++i)
        scalar_point<Order>(i, points, values, gradients, hessians, error);
    }
    if (error.index < count)
      throw std::out_of_range(fmt::format("point {}: {}", error.index + 1, error.what));
  }

  // Points [first, last) in chunks of simd::kChunk consecutive points: their world coordinates
  // converted and located in one SIMD call, then each orbit present in the chunk evaluated in one
  // SIMD call (simd_orbit; fcc6 has two orbits, so a chunk of random points takes two). A point
  // takes the scalar path, point(), with its errors, when it is not finite or far outside, when
  // its stencil box is not inside the volume, or when rounding put it on a knot plane (no cell in
  // the table).
  template <int Order>
  void simd_block(std::ptrdiff_t first, std::ptrdiff_t last, std::span<const Vec3> points,
                  std::span<T> values, std::span<Vec3> gradients, std::span<Hessian> hessians,
                  FirstError& error) const {
    constexpr int kLanes = simd::kChunk;
    constexpr bool kOneOrbit = std::size(Tr::kOrbitStencilSize) == 1;
    alignas(64) double padded[3 * kLanes];
    alignas(64) T located[simd::locate_rows(3) * kLanes];
    const simd::Frame frame = simd_frame();

    for (std::ptrdiff_t next = first; next < last; next += kLanes) {
      const int lanes = static_cast<int>(std::min<std::ptrdiff_t>(kLanes, last - next));
      kernels_->locate(chunk_points(points, next, lanes, padded), frame, located);

      // The lanes of the chunk's first orbit gathered, the lanes of other orbits deferred, the
      // lanes the kernels cannot take on the scalar path now.
      const T* const orbits = located + 7 * kLanes;
      const T* const inside = located + 8 * kLanes;
      int orbit = kOneOrbit ? 0 : -1, deferred = 0;
      int others[kLanes];
      Lanes chunk;
      for (int lane = 0; lane < lanes; ++lane) {
        if (inside[lane] == T(0)) {
          scalar_point<Order>(next + lane, points, values, gradients, hessians, error);
          continue;
        }
        if constexpr (kOneOrbit) {
          chunk.take(lane, located, stencils_);
        } else {
          const int o = static_cast<int>(orbits[lane]);
          if (orbit < 0) orbit = o;
          if (o == orbit)
            chunk.take(lane, located, stencils_);
          else
            others[deferred++] = lane;
        }
      }
      if (chunk.count == 0) continue;
      for (;;) {  // one SIMD call per orbit (fcc6 has two)
        simd_orbit<Order>(orbit, chunk, lanes, located, next, values, gradients, hessians);
        if (kOneOrbit || deferred == 0) break;
        orbit = static_cast<int>(orbits[others[0]]);  // the next orbit, the rest kept deferred
        chunk = Lanes{};
        int kept = 0;
        for (int k = 0; k < deferred; ++k) {
          if (static_cast<int>(orbits[others[k]]) == orbit)
            chunk.take(others[k], located, stencils_);
          else
            others[kept++] = others[k];
        }
        deferred = kept;
      }
    }
  }

  // Lane i of the chunk at `next` is point next + i: the points' coordinates, point after point,
  // where they lie, or copied into `padded` for a partial chunk, which repeats its first point
  // (the kernels compute every lane).
  static const double* chunk_points(std::span<const Vec3> points, std::ptrdiff_t next, int lanes,
                                    double* padded) {
    static_assert(sizeof(Vec3) == 3 * sizeof(double), "points are consecutive coordinates");
    if (lanes == simd::kChunk) return points[static_cast<std::size_t>(next)].data();
    for (int lane = 0; lane < simd::kChunk; ++lane)
      for (int a = 0; a < 3; ++a)
        padded[3 * lane + a] =
            points[static_cast<std::size_t>(next + (lane < lanes ? lane : 0))][a];
    return padded;
  }

  // On a linear volume (prepare_chunks): points [first, last) in chunks of simd::kChunk, each
  // located, gathered and evaluated in one SIMD call (simd::evaluate_chunk); the lanes it cannot
  // take (see simd_block) on the scalar path.
  template <int Order>
  void chunk_block(std::ptrdiff_t first, std::ptrdiff_t last, std::span<const Vec3> points,
                   std::span<T> values, std::span<Vec3> gradients, std::span<Hessian> hessians,
                   FirstError& error) const {
    constexpr int kLanes = simd::kChunk;
    alignas(64) double padded[3 * kLanes];
    alignas(64) T out[simd::kChunkRows * kLanes];
    const simd::Frame frame = simd_frame();
    const LinearLayout& l = linear_layout_;
    const simd::LinearVolume<T> volume{stencils_.samples(),
                                       linear_rows_.data(),
                                       {l.stride[0], l.stride[1], l.stride[2]},
                                       l.coset_shift};
    for (std::ptrdiff_t next = first; next < last; next += kLanes) {
      const int lanes = static_cast<int>(std::min<std::ptrdiff_t>(kLanes, last - next));
      kernels_->chunk(Order, chunk_points(points, next, lanes, padded), frame, volume, out);
      // The common case, every lane evaluated and values only: one copy, no test per lane.
      const T* ok = out + simd::kChunkOkRow * kLanes;
      bool every_lane = true;
      for (int lane = 0; lane < kLanes; ++lane) every_lane &= ok[lane] != T(0);
      if (Order == generated::support::kValue && every_lane) {
        std::copy_n(out, lanes, values.begin() + next);
        continue;
      }
      bool stays[kLanes];
      for (int lane = 0; lane < lanes; ++lane) {
        stays[lane] = out[simd::kChunkOkRow * kLanes + lane] != T(0);
        if (!stays[lane])
          scalar_point<Order>(next + lane, points, values, gradients, hessians, error);
      }
      store<Order>(lanes, stays, next, out + simd::kChunkCellRow * kLanes, out, values, gradients,
                   hessians);
    }
  }

  // The rows of simd::LinearVolume for this volume, where the storage is linear, the filter has
  // chunk kernels and every index fits the gathers' index type; else none (simd_block serves).
  void prepare_chunks() {
    using Index = simd::GatherIndex<T>;
    if (!kernels_ || !kernels_->has_chunk() || !stencils_.has_offsets()) return;
    const std::optional<LinearLayout> layout = stencils_.linear();
    if (!layout) return;
    constexpr auto& steps = kStencilSteps<Tr>;
    if (!steps.consistent || (layout->coset_shift != 0 && !steps.same_parity)) return;
    const std::int64_t* stride = layout->stride;
    const double reach = 16.0 * static_cast<double>(std::abs(stride[0]) + std::abs(stride[1]) +
                                                    std::abs(stride[2]) + layout->coset_shift);
    if (static_cast<double>(stencils_.volume().samples().size()) + reach >=
        static_cast<double>(std::numeric_limits<Index>::max()))
      return;
    std::vector<Index> rows;
    for (int parity = 0; parity < 2; ++parity)
      for (int c = 0; c < Tr::kCellCount; ++c) {
        const auto& first = Tr::kOffsets[c][0];
        const std::int64_t coset = (parity + first[0]) & 1;
        rows.push_back(static_cast<Index>(first[0] * stride[0] + first[1] * stride[1] +
                                          first[2] * stride[2] - coset * layout->coset_shift));
      }
    linear_rows_ = std::move(rows);
    linear_layout_ = *layout;
  }

  // The lanes of one orbit in a chunk, with where each one's stencil lies.
  struct Lanes {
    bool stays[simd::kChunk] = {};
    const T* bases[simd::kChunk];
    const Offset* tables[simd::kChunk];
    int count = 0;
    void take(int lane, const T* located, const Stencils& stencils) {
      constexpr int kLanes = simd::kChunk;
      const std::int64_t corner[3] = {static_cast<std::int64_t>(located[lane]),
                                      static_cast<std::int64_t>(located[kLanes + lane]),
                                      static_cast<std::int64_t>(located[2 * kLanes + lane])};
      const Fetch<Offset> f = stencils.fetch(corner, static_cast<int>(located[3 * kLanes + lane]));
      bases[lane] = stencils.samples() + f.base;
      tables[lane] = f.offsets;
      stays[lane] = true;
      ++count;
    }
    // The lanes not taken repeat a taken lane's stencil (the kernels compute every lane).
    void fill() {
      if (count == simd::kChunk) return;
      int taken = 0;
      while (!stays[taken]) ++taken;
      for (int lane = 0; lane < simd::kChunk; ++lane)
        if (!stays[lane]) {
          bases[lane] = bases[taken];
          tables[lane] = tables[taken];
        }
    }
  };

  // One orbit's lanes of a chunk (lane i is point next + i): their stencils gathered into lanes,
  // the orbit's polynomial evaluated in one SIMD call (runtime/simd_batch.h), the derivatives
  // mapped back per lane.
  template <int Order>
  void simd_orbit(int orbit, Lanes& taken, int lanes, const T* located, std::ptrdiff_t next,
                  std::span<T> values, std::span<Vec3> gradients,
                  std::span<Hessian> hessians) const {
    namespace support = generated::support;
    constexpr int kLanes = simd::kChunk;
    constexpr int kOut =
        1 + (Order == support::kValue ? 0 : 3) + (Order == support::kHessian ? 6 : 0);
    alignas(64) T v[kStencil * kLanes];
    alignas(64) T out[kOut * kLanes];
    taken.fill();
    gather(Tr::kOrbitStencilSize[orbit], taken.bases, taken.tables, v);
    kernels_->orbit(orbit, Order, v, located + 4 * kLanes, out, simd::kChunk);
    store<Order>(lanes, taken.stays, next, located + 3 * kLanes, out, values, gradients, hessians);
  }

  // Derivatives d (lattice units: gradient d[0..2], Hessian's upper triangle d[3..8]) in world
  // units: divided by the spacing of each axis they differentiate along (h_a, or h_a h_b). Either
  // output may be null (not wanted).
  template <int Order>
  void to_world_derivatives(const T* d, double* gradient, double* hessian) const {
    const Vec3& h = stencils_.volume().axis_spacing();
    if (gradient)
      for (int a = 0; a < 3; ++a) gradient[a] = static_cast<double>(d[a]) / h[a];
    if constexpr (Order >= generated::support::kHessian) {
      if (!hessian) return;
      constexpr int kRow[6] = {0, 0, 0, 1, 1, 2}, kColumn[6] = {0, 1, 2, 1, 2, 2};
      for (int i = 0; i < 6; ++i)
        hessian[i] = static_cast<double>(d[3 + i]) / (h[kRow[i]] * h[kColumn[i]]);
    }
  }

  // The world-to-lattice frame and the bounds of locate_chunk.
  simd::Frame simd_frame() const {
    simd::Frame frame{};
    frame.lower = -kFar;
    for (int a = 0; a < 3; ++a) {
      frame.h[a] = stencils_.volume().axis_spacing()[a];
      frame.origin[a] = stencils_.volume().origin()[a];
      frame.upper[a] = stencils_.extent(a) + kFar;
      frame.limit[a] = stencils_.last(a);
    }
    return frame;
  }

  // The first `size` stencil values of every lane into v[k * kChunk + lane].
  static void gather(int size, const T* const* bases, const Offset* const* tables, T* v) {
    constexpr int kLanes = simd::kChunk;
    if constexpr (kStencil < 64) {
      // Sample k of every lane, then k + 1: the lanes' cache misses overlap (M7, M8: 10% less
      // time than lane by lane, bench_instructions ... time).
      for (int k = 0; k < size; ++k) {
        T* const row = v + k * kLanes;
#pragma GCC unroll 16
        for (int lane = 0; lane < kLanes; ++lane) row[lane] = bases[lane][tables[lane][k]];
      }
    } else {
      // Lane by lane: fewer instructions per sample, which wins for large stencils (tricubic: 64,
      // M12: 128).
      for (int lane = 0; lane < kLanes; ++lane) {
        const T* const base = bases[lane];
        const Offset* const table = tables[lane];
#pragma GCC unroll 16
        for (int k = 0; k < size; ++k) v[k * kLanes + lane] = base[table[k]];
      }
    }
  }

  // The chunk's results of the lanes that stayed (lane i is point next + i), derivatives mapped
  // back from the reference frame of each lane's cell and scaled to world units.
  template <int Order>
  void store(int lanes, const bool* stays, std::ptrdiff_t next, const T* cells, const T* out,
             std::span<T> values, std::span<Vec3> gradients, std::span<Hessian> hessians) const {
    namespace support = generated::support;
    constexpr int kLanes = simd::kChunk;
    for (int lane = 0; lane < lanes; ++lane) {
      if (!stays[lane]) continue;
      const std::ptrdiff_t p = next + lane;
      values[p] = out[lane];
      if constexpr (Order >= support::kGradient) {
        T d[3 + 6];
        support::from_reference_frame<Order, Tr>(static_cast<int>(cells[lane]), out + kLanes + lane,
                                                 kLanes, d);
        to_world_derivatives<Order>(d, gradients[p].data(),
                                    Order >= support::kHessian ? hessians[p].data() : nullptr);
      }
    }
  }

  Stencils stencils_;
  const simd::Kernels* kernels_;  // the SIMD kernels of the filter, or null (the scalar path)
  std::vector<simd::GatherIndex<T>> linear_rows_;  // empty: no chunk_block (prepare_chunks)
  LinearLayout linear_layout_{};
};

// An EmittedSpline behind a virtual interface, for Reconstructor, which chooses the filter at run
// time: one virtual call per point or per batch.
template <class T>
class EvaluationPath {
 public:
  virtual ~EvaluationPath() = default;
  // One point; gradient and hessian may be null (not computed).
  virtual T at(const Vec3& world, Vec3* gradient, Hessian* hessian) const = 0;
  virtual void batch(std::span<const Vec3> points, std::span<T> values, std::span<Vec3> gradients,
                     std::span<Hessian> hessians) const = 0;
};

template <class Tr, class Stencils>
class EmittedSplinePath final : public EvaluationPath<typename Stencils::Sample> {
  using T = typename Stencils::Sample;

 public:
  EmittedSplinePath(Stencils stencils, int registry_index, const simd::Kernels* kernels = nullptr)
      : spline_(std::move(stencils), registry_index, kernels) {}
  T at(const Vec3& world, Vec3* gradient, Hessian* hessian) const override {
    return spline_.at(world, gradient, hessian);
  }
  void batch(std::span<const Vec3> points, std::span<T> values, std::span<Vec3> gradients,
             std::span<Hessian> hessians) const override {
    spline_.batch(points, values, gradients, hessians);
  }

 private:
  EmittedSpline<Tr, Stencils> spline_;
};

}  // namespace boxgen::runtime
