// The SIMD batch path of Reconstructor::evaluate
// (runtime/simd_batch.h, runtime/emitted_spline.h) against the scalar path (value() with and
// without derivatives, and evaluate() with BOXGEN_SIMD=0): for every filter of
// generated/registry.hpp on BCC volumes and on volumes of its own lattice, float and double, the
// results agree bit for bit (the SIMD code runs the
// same generated operations in the same order, without fused multiply-adds), at random points,
// at points on and near knot planes, near the volume's faces (where some lanes of a chunk fall
// back to the scalar path), and for counts that leave a partial chunk. Errors are the scalar
// path's, for the first failing point. BCC volumes with the usual cosets and Cartesian volumes
// take the chunk kernels (evaluate_chunk: vector gathers from a linear layout); BCC volumes with
// the cosets swapped and FCC volumes take the table path (locate_chunk, per-lane tables,
// orbit_chunk), so both are compared with the scalar path.
#include "runtime/simd_batch.h"

#include <hwy/highway.h>

#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <limits>
#include <random>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

#include "generated/registry.hpp"
#include "runtime/batch_threads.h"
#include "runtime/emitted_filter.h"
#include "runtime/lattice_volume.h"
#include "runtime/reconstruction.h"
#include "runtime/resample.h"
#include "runtime/simd_kernels-inl.h"
#include "runtime/stencil_steps.h"
#include "runtime/stencils.h"
#include "support/evaluator_support.hpp"
#include "tests/support/bcc_volumes.h"

namespace boxgen::runtime {
namespace {

constexpr int kSize = 12;  // N^3 x 2 samples
constexpr double kSpacing = 0.37;
const Vec3 kSpacings{kSpacing, kSpacing, kSpacing};
const Vec3 kOrigin{-1.1, 0.3, 2.0};

template <class T>
LatticeVolume<T> random_volume(std::uint64_t seed) {
  LatticeVolume<T> volume(CosetLattice::bcc(), {kSize, kSize, kSize}, kSpacing, kOrigin);
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (auto& s : volume.samples()) s = static_cast<T>(u(rng));
  return volume;
}

Vec3 world(const Vec3& lattice, const Vec3& h) {
  return {kOrigin[0] + h[0] * lattice[0], kOrigin[1] + h[1] * lattice[1],
          kOrigin[2] + h[2] * lattice[2]};
}

// Lattice coordinates inside the volume, one in eight also near or beyond a face (some points
// evaluate through checked fetches, some are refused); a third of them on the planes x_i = k/4 and
// x_i +- x_j = k/4, where the knot planes of every filter lie, exactly or moved by about 1e-7.
// h: the volume's spacings.
std::vector<Vec3> candidate_points(int count, std::uint64_t seed, const Vec3& h = kSpacings) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> inner(4.0, 2.0 * kSize - 5.0);
  std::uniform_real_distribution<double> wide(-4.0, 2.0 * kSize + 3.0);
  std::uniform_int_distribution<int> pick(0, 5);
  std::vector<Vec3> out(count);
  for (int i = 0; i < count; ++i) {
    Vec3 x{inner(rng), inner(rng), inner(rng)};
    if (i % 8 == 0) x[i % 3] = wide(rng);  // near or beyond a face
    switch (pick(rng)) {
      case 0:
        x[0] = std::round(4 * x[0]) / 4;
        break;
      case 1:
        x[1] = std::round(4 * x[1]) / 4 + 1e-7;
        break;
      case 2:
        x[2] = x[0] + std::round(4 * (x[2] - x[0])) / 4;
        break;
      case 3:
        x[1] = std::round(4 * (x[1] + x[2])) / 4 - x[2] - 1e-7;
        break;
      default:
        break;
    }
    out[i] = world(x, h);
  }
  return out;
}

// A volume of the filter's own lattice with as wide a box as random_volume: lattice coordinates
// in [0, 2 kSize - 1] on every lattice (2 kSize / d samples per coset and axis). On BCC the
// cosets are stored the other way round, so that the general lattice tables are used there too.
template <class T>
LatticeVolume<T> random_lattice_volume(const SplineFilter& f, std::uint64_t seed) {
  const CosetLattice& lattice = f.lattice();
  const int n = 2 * kSize / lattice.period();
  LatticeVolume<T> volume(lattice, {n, n, n}, kSpacing, kOrigin);
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (auto& s : volume.samples()) s = static_cast<T>(u(rng));
  return lattice == CosetLattice::bcc() ? test::swapped_cosets(volume) : volume;
}

// The points the scalar path evaluates (value() does not throw).
template <class Spline>
std::vector<Vec3> evaluable(const Spline& r, const std::vector<Vec3>& candidates) {
  std::vector<Vec3> out;
  for (const Vec3& p : candidates) {
    try {
      r.value(p);
      out.push_back(p);
    } catch (const std::exception&) {
    }
  }
  return out;
}

class SimdSwitch {  // BOXGEN_SIMD for one scope
 public:
  explicit SimdSwitch(const char* value) { setenv("BOXGEN_SIMD", value, 1); }
  ~SimdSwitch() { unsetenv("BOXGEN_SIMD"); }
  SimdSwitch(const SimdSwitch&) = delete;
  SimdSwitch& operator=(const SimdSwitch&) = delete;
};

TEST(SimdBatch, DispatchesToAVectorTargetAndCanBeSwitchedOff) {
  EXPECT_STRNE(simd::target_name(), "");
  // Every x86-64 this project supports has at least SSE4 (Highway's smallest vector target here);
  // an emulated target would mean the dispatch is broken.
  EXPECT_TRUE(simd::enabled()) << simd::target_name();
  {
    const SimdSwitch off("0");
    EXPECT_FALSE(simd::enabled());
  }
  {
    const SimdSwitch off("off");
    EXPECT_FALSE(simd::enabled());
  }
  EXPECT_TRUE(simd::enabled());
}

// One point through the scalar path: value, and with gradient and Hessian when asked.
template <class T>
T scalar_value(const Reconstructor<T>& r, const Vec3& p, Vec3* g, Hessian* h) {
  return h ? r.value_gradient_hessian(p, *g, *h) : r.value(p, g);
}

template <class T, class Spline>
void expect_batch_equals_scalar(const Spline& r, std::uint64_t seed,
                                const Vec3& spacing = kSpacings) {
  SCOPED_TRACE(sizeof(T) == 4 ? "float" : "double");
  const std::vector<Vec3> all = evaluable(r, candidate_points(1500, seed + 1, spacing));
  ASSERT_GT(all.size(), 600u);
  // Counts that fill chunks exactly, leave partial chunks, or fit in one.
  for (std::size_t count :
       {all.size(), std::size_t{1}, std::size_t{15}, std::size_t{17}, std::size_t{16 * 9 + 5}}) {
    SCOPED_TRACE(count);
    const std::span<const Vec3> points(all.data(), count);
    std::vector<T> values(count), values_only(count), scalar_batch(count);
    std::vector<Vec3> gradients(count), gradients_h(count);
    std::vector<Hessian> hessians(count);
    r.evaluate(points, values_only);
    r.evaluate(points, values, gradients);
    r.evaluate(points, values, gradients_h, hessians);
    {
      const SimdSwitch off("0");
      r.evaluate(points, scalar_batch);
    }
    EXPECT_EQ(values_only, scalar_batch);
    for (std::size_t i = 0; i < count; ++i) {
      Vec3 g, gh;
      Hessian h;
      EXPECT_EQ(values_only[i], scalar_value(r, points[i], nullptr, nullptr)) << i;
      EXPECT_EQ(values[i], scalar_value(r, points[i], &g, nullptr)) << i;
      EXPECT_EQ(gradients[i], g) << i;
      EXPECT_EQ(values[i], scalar_value(r, points[i], &gh, &h)) << i;
      EXPECT_EQ(gradients_h[i], gh) << i;
      EXPECT_EQ(hessians[i], h) << i;
    }
  }
}

template <class T>
void expect_batch_equals_scalar(const SplineFilter& f, std::uint64_t seed) {
  SCOPED_TRACE(f.name());
  const LatticeVolume<T> volume = random_volume<T>(seed);
  expect_batch_equals_scalar<T>(Reconstructor<T>(volume, f), seed);
}

TEST(SimdBatch, EqualsTheScalarPathForEveryBccSplineFilterInFloat) {
  int tested = 0;
  for (int i = 0; i < generated::kFilterCount; ++i)
    if (std::string_view(generated::kFilterLattices[i]) == "bcc") {
      expect_batch_equals_scalar<float>(SplineFilter::at(i), 10 + i);
      ++tested;
    }
  EXPECT_EQ(tested, 3);  // m7, m8, m12: the filters Reconstructor (BCC) takes
}

// Where every spacing is a power of two the kernels multiply by the inverses instead of dividing
// (lattice_lanes): the same bits. BCC volumes take one spacing; a Cartesian one three different
// ones (so that an axis taking another axis' inverse would show).
template <class T>
void expect_power_of_two_spacings_equal_scalar(std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (const char* name : {"m7", "m12"})
    for (const double h : {0.5, 2.0}) {
      SCOPED_TRACE(testing::Message() << name << ", spacing " << h);
      LatticeVolume<T> volume(CosetLattice::bcc(), {kSize, kSize, kSize}, h, kOrigin);
      for (auto& s : volume.samples()) s = static_cast<T>(u(rng));
      expect_batch_equals_scalar<T>(Reconstructor<T>(volume, SplineFilter::parse(name)), seed,
                                    {h, h, h});
    }
  const Vec3 spacing{0.5, 0.25, 4.0};
  std::vector<T> samples(std::size_t{8} * kSize * kSize * kSize);
  for (auto& s : samples) s = static_cast<T>(u(rng));
  const LatticeVolume<T> volume(CosetLattice::cartesian(), {2 * kSize, 2 * kSize, 2 * kSize},
                                spacing, kOrigin, std::move(samples));
  expect_batch_equals_scalar<T>(Reconstructor<T>(volume, SplineFilter::parse("tricubic")), seed,
                                spacing);
}

TEST(SimdBatch, PowerOfTwoSpacingsEqualTheScalarPath) {
  expect_power_of_two_spacings_equal_scalar<float>(40);
  expect_power_of_two_spacings_equal_scalar<double>(50);
}

TEST(SimdBatch, EqualsTheScalarPathForEveryBccSplineFilterInDouble) {
  int tested = 0;
  for (int i = 0; i < generated::kFilterCount; ++i)
    if (std::string_view(generated::kFilterLattices[i]) == "bcc") {
      expect_batch_equals_scalar<double>(SplineFilter::at(i), 20 + i);
      ++tested;
    }
  EXPECT_EQ(tested, 3);  // m7, m8, m12: the filters Reconstructor (BCC) takes
}

// Every registry filter, BCC ones included, on a volume of its own lattice through the general
// lattice tables (the SIMD path with LatticeStencils).
template <class T>
void expect_every_lattice_filter_equals_scalar(std::uint64_t seed) {
  for (int i = 0; i < SplineFilter::count(); ++i) {
    const SplineFilter f = SplineFilter::at(i);
    SCOPED_TRACE(f.name());
    const LatticeVolume<T> volume = random_lattice_volume<T>(f, seed + i);
    expect_batch_equals_scalar<T>(Reconstructor<T>(volume, f), seed + i);
  }
}

TEST(SimdBatch, EqualsTheScalarPathForEverySplineFilterOnItsLatticeInFloat) {
  expect_every_lattice_filter_equals_scalar<float>(40);
}

TEST(SimdBatch, EqualsTheScalarPathForEverySplineFilterOnItsLatticeInDouble) {
  expect_every_lattice_filter_equals_scalar<double>(60);
}

// Points in the volume's upper corner, where a run's load (StencilSteps::run_axis) would reach
// beyond the last sample: the chunk kernels gather those lanes' stencils instead, and every
// result stays the scalar path's.
std::vector<Vec3> upper_corner_points(int count, std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> corner(2.0 * kSize - 6.0, 2.0 * kSize - 1.0);
  std::vector<Vec3> out(count);
  for (Vec3& p : out) p = world({corner(rng), corner(rng), corner(rng)}, kSpacings);
  return out;
}

template <class T>
void expect_upper_corner_equals_scalar(const std::string& filter, bool own_lattice) {
  SCOPED_TRACE(filter);
  const SplineFilter f = SplineFilter::parse(filter);
  const LatticeVolume<T> volume =
      own_lattice ? random_lattice_volume<T>(f, 7) : random_volume<T>(7);
  const Reconstructor<T> r(volume, f);
  const std::vector<Vec3> points = evaluable(r, upper_corner_points(4000, 8));
  ASSERT_GT(points.size(), 100u);
  std::vector<T> values(points.size()), scalar(points.size());
  r.evaluate(points, values);
  {
    const SimdSwitch off("0");
    r.evaluate(points, scalar);
  }
  EXPECT_EQ(values, scalar);
}

TEST(SimdBatch, RunLoadsStopAtTheLastSample) {
  expect_upper_corner_equals_scalar<float>("m12", false);
  expect_upper_corner_equals_scalar<double>("m12", false);
  expect_upper_corner_equals_scalar<float>("tricubic", true);
  expect_upper_corner_equals_scalar<double>("tricubic", true);
}

// Two threads split the chunks differently; the results do not change.
TEST(SimdBatch, ThreadCountDoesNotChangeResults) {
  const LatticeVolume<float> volume = random_volume<float>(3);
  const Reconstructor<float> r(volume, SplineFilter::parse("m8"));
  const std::vector<Vec3> points = evaluable(r, candidate_points(5000, 4));
  std::vector<float> one(points.size()), two(points.size());
  set_batch_threads(1);
  r.evaluate(points, one);
  set_batch_threads(2);
  r.evaluate(points, two);
  set_batch_threads(0);
  EXPECT_EQ(one, two);
}

// A batch with refused points (non-finite, outside) reports the first of them, with the scalar
// path's message, whether the other points went through SIMD chunks or not.
TEST(SimdBatch, ReportsTheFirstBadPointAsTheScalarPathDoes) {
  const LatticeVolume<double> volume = random_volume<double>(5);
  const Reconstructor<double> r(volume, SplineFilter::parse("m7"));
  std::vector<Vec3> points = evaluable(r, candidate_points(800, 6));
  ASSERT_GT(points.size(), 300u);
  points[37] = world({-20, 3, 3}, kSpacings);                          // outside
  points[200] = {std::numeric_limits<double>::quiet_NaN(), 0.0, 0.0};  // not finite
  std::vector<double> values(points.size());
  std::string expected;
  try {
    r.value(points[37]);
  } catch (const std::out_of_range& e) {
    expected = "point 38: " + std::string(e.what());
  }
  ASSERT_FALSE(expected.empty());
  for (const char* simd_switch : {"1", "0"}) {
    const SimdSwitch s(simd_switch);
    try {
      r.evaluate(points, values);
      ADD_FAILURE() << "no error with BOXGEN_SIMD=" << simd_switch;
    } catch (const std::out_of_range& e) {
      EXPECT_EQ(e.what(), expected) << "BOXGEN_SIMD=" << simd_switch;
    }
  }
}

// Every registry filter's stencils are its orbit's steps mapped by each cell's signed permutation
// (stencil_steps.h), so every one has chunk kernels; on BCC the steps keep the cosets' parity.
TEST(SimdBatch, EveryRegistryFilterHasChunkKernels) {
  for (int i = 0; i < generated::kFilterCount; ++i) {
    SCOPED_TRACE(generated::kFilterNames[i]);
    EXPECT_TRUE(simd::has_evaluate_chunk(i));
    ASSERT_NE(simd::registry_kernels(i), nullptr);
    EXPECT_TRUE(simd::registry_kernels(i)->has_chunk());
    generated::with_filter(i, [&](auto entry) {
      using Tr = typename decltype(entry)::Traits;
      EXPECT_TRUE(kStencilSteps<Tr>.consistent);
      if (std::string_view(Tr::kLattice) == "bcc") {
        EXPECT_TRUE(kStencilSteps<Tr>.same_parity);
      }
      // Sample 0 is the origin of the steps.
      for (int o = 0; o < StencilSteps<Tr>::kOrbits; ++o)
        for (int a = 0; a < 3; ++a) EXPECT_EQ(kStencilSteps<Tr>.step[o][0][a], 0);
    });
  }
}

// A compiled filter gets chunk kernels (set_kernels_for: chunks_can_serve) exactly where a volume
// of its own lattice can take them: where the stencils its path takes there (stencil_policy) lay
// the samples out linearly, as EmittedSpline::prepare_chunks asks. FCC's general tables (period 2)
// do not, so a compiled FCC filter leaves them out; BCC's parity tables and Cartesian ones do.
TEST(SimdBatch, ChunkKernelsAreCompiledWhereAVolumeCanTakeThem) {
  for (int i = 0; i < generated::kFilterCount; ++i) {
    SCOPED_TRACE(generated::kFilterNames[i]);
    generated::with_filter(i, [&](auto entry) {
      using Tr = typename decltype(entry)::Traits;
      const CosetLattice lattice = CosetLattice::parse(Tr::kLattice);
      const int n = 8 / lattice.period();
      const LatticeVolume<float> volume(lattice, {n, n, n}, 1.0, {0.0, 0.0, 0.0});
      const bool linear = stencil_policy<Tr>(lattice, volume.sizes()) == StencilPolicy::kLattice
                              ? LatticeStencils<Tr, float>(volume).linear().has_value()
                              : BccStencils<Tr, float, std::int32_t>(volume).linear().has_value();
      EXPECT_EQ(simd::HWY_NAMESPACE::chunks_can_serve<Tr>(), linear);
      EXPECT_EQ(linear, std::string_view(Tr::kLattice) != "fcc");
    });
  }
}

// The runs of stencil_steps.h, checked against the emitted offsets themselves: in every cell of
// an orbit with runs, sample kRun g + j lies j run_step samples from sample kRun g along storage
// axis 0, forwards or backwards by the cell's sign, and nowhere else. Which filters have them:
// M12 (4 x 4 x 8 samples, same-coset rows along x) and tricubic (4 x 4 x 4).
TEST(SimdBatch, StencilRunsLieAlongStorageX) {
  for (int i = 0; i < generated::kFilterCount; ++i) {
    SCOPED_TRACE(generated::kFilterNames[i]);
    generated::with_filter(i, [&](auto entry) {
      using Tr = typename decltype(entry)::Traits;
      constexpr auto& s = kStencilSteps<Tr>;
      const std::string_view name = generated::kFilterNames[i];
      EXPECT_EQ(s.run_axis[0] >= 0, name == "m12" || name == "tricubic");
      for (int o = 0; o < StencilSteps<Tr>::kOrbits; ++o) {
        if (s.run_axis[o] < 0) continue;
        const int u = s.run_step[o];
        EXPECT_EQ(u, name == "m12" ? 2 : 1);
        for (int c = 0; c < Tr::kCellCount; ++c) {
          const auto& cell = Tr::kCells[c];
          if (cell.orbit != o) continue;
          const int sign = cell.sign[s.run_axis[o]];
          for (int k = 0; k < Tr::kOrbitStencilSize[o]; ++k) {
            const int j = k % StencilSteps<Tr>::kRun;
            const auto& first = Tr::kOffsets[c][k - j];
            EXPECT_EQ(Tr::kOffsets[c][k][0] - first[0], sign * j * u) << c << " " << k;
            EXPECT_EQ(Tr::kOffsets[c][k][1], first[1]) << c << " " << k;
            EXPECT_EQ(Tr::kOffsets[c][k][2], first[2]) << c << " " << k;
          }
        }
      }
    });
  }
}

// Two cells of one orbit whose stencils are not images of each other under their maps: the steps
// are not consistent (such tables take the table path).
struct SkewedTraits {
  static constexpr int kDimension = 3, kStencilSize = 2, kCellCount = 2;
  static constexpr int kOrbitStencilSize[1] = {2};
  static constexpr generated::support::Cell<3, 0> kCells[2] = {
      {0, 0, {0}, {0, 1, 2}, {1, 1, 1}, {0, 0, 0}}, {0, 0, {0}, {1, 0, 2}, {1, 1, 1}, {0, 0, 0}}};
  // Cell 1 swaps x and y, so its second sample would have to be (0, 1, 0), not (1, 0, 0).
  static constexpr std::int16_t kOffsets[2][2][3] = {{{0, 0, 0}, {1, 0, 0}},
                                                     {{0, 0, 0}, {1, 0, 0}}};
};
struct SwappedTraits : SkewedTraits {
  static constexpr std::int16_t kOffsets[2][2][3] = {{{0, 0, 0}, {1, 1, 1}},
                                                     {{0, 0, 0}, {1, 1, 1}}};
};

TEST(SimdBatch, StencilStepsDetectTablesWithoutTheSymmetry) {
  static_assert(!kStencilSteps<SkewedTraits>.consistent);
  static_assert(!kStencilSteps<SkewedTraits>.same_parity);  // a step (1, 0, 0) changes the coset
  static_assert(kStencilSteps<SwappedTraits>.consistent);
  static_assert(kStencilSteps<SwappedTraits>.same_parity);
  EXPECT_EQ(kStencilSteps<SwappedTraits>.step[0][1][1], 1);
}

}  // namespace
}  // namespace boxgen::runtime
