// LatticeVolume on the BCC lattice: storage order, lattice access, the border policy, world <->
// lattice coordinates.
#include "runtime/lattice_volume.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <limits>
#include <stdexcept>
#include <string>

namespace boxgen::runtime {
namespace {

// Every sample gets a code that names its own (c, i, j, k).
template <class T>
LatticeVolume<T> coded_volume(Sizes sizes) {
  LatticeVolume<T> v(CosetLattice::bcc(), sizes, 0.5, {1, 2, 3});
  for (int k = 0; k < sizes[2]; ++k)
    for (int j = 0; j < sizes[1]; ++j)
      for (int i = 0; i < sizes[0]; ++i)
        for (int c = 0; c < 2; ++c) v(c, i, j, k) = static_cast<T>(1000 * c + 100 * i + 10 * j + k);
  return v;
}

template <class F>
std::string message_of(F&& f) {
  try {
    f();
  } catch (const std::exception& e) {
    return e.what();
  }
  return {};
}

TEST(BccLatticeVolume, StorageOrderIsCosetFastestThenIJK) {
  const LatticeVolume<double> v(CosetLattice::bcc(), {3, 4, 5}, 0.5, {1, 2, 3});
  EXPECT_EQ(v.sample_count(), 2u * 3 * 4 * 5);
  EXPECT_EQ(v.index(0, 0, 0, 0), 0u);
  EXPECT_EQ(v.index(1, 0, 0, 0), 1u);
  EXPECT_EQ(v.index(0, 1, 0, 0), 2u);
  EXPECT_EQ(v.index(0, 0, 1, 0), 6u);   // 2 * N0
  EXPECT_EQ(v.index(0, 0, 0, 1), 24u);  // 2 * N0 * N1
  EXPECT_EQ(v.index(1, 2, 3, 4), v.sample_count() - 1);
  for (double x : v.samples()) EXPECT_EQ(x, 0.0);  // zero-filled
}

TEST(BccLatticeVolume, LatticeValueFindsTheRightSample) {
  const auto v = coded_volume<float>({3, 4, 5});
  EXPECT_EQ(v.value(0, 0, 0), 0.0f);
  EXPECT_EQ(v.value(3, 5, 7), 1123.0f);  // odd: coset 1, i = 1, j = 2, k = 3
  EXPECT_EQ(v.value(4, 2, 6), 213.0f);   // even: coset 0, i = 2, j = 1, k = 3
  EXPECT_EQ(v.value(LatticePoint{5, 7, 9}), 1234.0f);
  for (int k = 0; k < 5; ++k)
    for (int j = 0; j < 4; ++j)
      for (int i = 0; i < 3; ++i)
        for (int c = 0; c < 2; ++c)
          EXPECT_EQ(v.value(2 * i + c, 2 * j + c, 2 * k + c), v.at(c, i, j, k));
}

TEST(BccLatticeVolume, ContainsExactlyTheStoredLatticePoints) {
  const LatticeVolume<double> v(CosetLattice::bcc(), {3, 4, 5}, 0.5, {1, 2, 3});
  int inside = 0;
  for (int z = -3; z <= 12; ++z)
    for (int y = -3; y <= 10; ++y)
      for (int x = -3; x <= 8; ++x) {
        const bool lattice = ((x - y) % 2 == 0) && ((x - z) % 2 == 0);
        const int c = ((x % 2) + 2) % 2;
        const bool stored = lattice && x >= c && y >= c && z >= c && (x - c) / 2 < 3 &&
                            (y - c) / 2 < 4 && (z - c) / 2 < 5;
        EXPECT_EQ(v.contains(x, y, z), stored) << x << " " << y << " " << z;
        inside += stored;
      }
  EXPECT_EQ(inside, 2 * 3 * 4 * 5);
}

TEST(BccLatticeVolume, OutsidePointsThrowOrGiveTheOutsideValue) {
  const auto v = coded_volume<double>({3, 4, 5});
  const LatticePoint outside[] = {{-1, -1, -1},
                                  {-2, 0, 0},
                                  {6, 0, 0},
                                  {5, 7, 11},
                                  {0, 8, 0},
                                  {std::numeric_limits<std::int64_t>::min(), 0, 0},
                                  {std::numeric_limits<std::int64_t>::max(), 1, 1}};
  for (const auto& p : outside) {
    EXPECT_FALSE(v.contains(p));
    EXPECT_THROW((void)v.value(p), std::out_of_range);
    EXPECT_EQ(v.value_or(p, -7.5), -7.5);
  }
  const std::string message = message_of([&] { (void)v.value(6, 0, 0); });
  EXPECT_NE(message.find("outside the volume"), std::string::npos) << message;
  EXPECT_EQ(message.find('\n'), std::string::npos);
  EXPECT_EQ(v.value_or(5, 7, 9, -1.0), 1234.0);
}

TEST(BccLatticeVolume, MixedParityIsNotALatticePoint) {
  const auto v = coded_volume<double>({3, 4, 5});
  EXPECT_FALSE(CosetLattice::bcc().contains(0, 1, 0));
  EXPECT_FALSE(CosetLattice::bcc().contains(-1, 0, 0));
  EXPECT_TRUE(CosetLattice::bcc().contains(-1, 1, -3));
  EXPECT_FALSE(v.contains(1, 0, 0));
  const std::string message = message_of([&] { (void)v.value(1, 2, 2); });
  EXPECT_NE(message.find("not a BCC lattice point"), std::string::npos) << message;
  EXPECT_EQ(v.value_or(1, 2, 2, 42.0), 42.0);
}

TEST(BccLatticeVolume, CheckedAtRejectsBadIndices) {
  auto v = coded_volume<double>({3, 4, 5});
  EXPECT_EQ(v.at(1, 2, 3, 4), 1234.0);
  v.at(0, 1, 1, 1) = 5;
  EXPECT_EQ(v(0, 1, 1, 1), 5.0);
  EXPECT_THROW((void)v.at(2, 0, 0, 0), std::out_of_range);
  EXPECT_THROW((void)v.at(-1, 0, 0, 0), std::out_of_range);
  EXPECT_THROW((void)v.at(0, 3, 0, 0), std::out_of_range);
  EXPECT_THROW((void)v.at(0, 0, 4, 0), std::out_of_range);
  EXPECT_THROW((void)v.at(0, 0, 0, 5), std::out_of_range);
  EXPECT_THROW((void)v.at(0, 0, 0, -1), std::out_of_range);
}

TEST(BccLatticeVolume, ContainsBoxAgreesWithEveryPointOfTheBox) {
  const LatticeVolume<double> v(CosetLattice::bcc(), {2, 3, 2}, 1, {0, 0, 0});
  int checked = 0;
  for (int lo = -2; lo <= 3; ++lo)
    for (int hi = lo; hi <= 7; ++hi)
      for (int axis = 0; axis < 3; ++axis) {
        LatticePoint a{0, 0, 0}, b{1, 1, 1};  // a box that is inside on the other axes
        a[axis] = lo;
        b[axis] = hi;
        bool all = true;
        for (std::int64_t z = a[2]; z <= b[2]; ++z)
          for (std::int64_t y = a[1]; y <= b[1]; ++y)
            for (std::int64_t x = a[0]; x <= b[0]; ++x)
              if (CosetLattice::bcc().contains(x, y, z) && !v.contains(x, y, z)) all = false;
        EXPECT_EQ(v.contains_box(a, b), all) << "axis " << axis << " [" << lo << ", " << hi << "]";
        ++checked;
      }
  EXPECT_GT(checked, 50);
  EXPECT_TRUE(v.contains_box({3, 0, 0}, {2, 0, 0}));  // empty
}

TEST(BccLatticeVolume, WorldAndLatticeCoordinates) {
  const LatticeVolume<double> v(CosetLattice::bcc(), {3, 4, 5}, 0.5, {1, 2, 3});
  const Vec3 p = v.sample_position(1, 1, 2, 3);  // o + h (3, 5, 7)
  EXPECT_EQ(p, (Vec3{2.5, 4.5, 6.5}));
  EXPECT_EQ(v.to_lattice(p), (Vec3{3, 5, 7}));
  EXPECT_EQ(v.sample_position(0, 2, 0, 1), (Vec3{3, 2, 4}));
  const Vec3 q{-0.3, 7.25, 1e-3};
  const Vec3 back = v.to_world(v.to_lattice(q));
  for (int a = 0; a < 3; ++a) EXPECT_NEAR(back[a], q[a], 1e-15 * (1 + std::fabs(q[a])));
}

TEST(BccLatticeVolume, InvalidGeometryIsRejected) {
  EXPECT_THROW(LatticeVolume<double>(CosetLattice::bcc(), {0, 1, 1}, 1, {0, 0, 0}),
               std::invalid_argument);
  EXPECT_THROW(LatticeVolume<double>(CosetLattice::bcc(), {1, -1, 1}, 1, {0, 0, 0}),
               std::invalid_argument);
  EXPECT_THROW(LatticeVolume<double>(CosetLattice::bcc(),
                                     {1, 1, LatticeVolume<double>::kMaxSize + 1}, 1, {0, 0, 0}),
               std::invalid_argument);
  EXPECT_THROW(
      LatticeVolume<double>(CosetLattice::bcc(), {1 << 20, 1 << 20, 1 << 20}, 1, {0, 0, 0}),
      std::invalid_argument);  // 2^61 samples
  EXPECT_THROW(LatticeVolume<double>(CosetLattice::bcc(), {1, 1, 1}, 0, {0, 0, 0}),
               std::invalid_argument);
  EXPECT_THROW(LatticeVolume<double>(CosetLattice::bcc(), {1, 1, 1}, -1, {0, 0, 0}),
               std::invalid_argument);
  EXPECT_THROW(LatticeVolume<double>(CosetLattice::bcc(), {1, 1, 1}, std::nan(""), {0, 0, 0}),
               std::invalid_argument);
  EXPECT_THROW(LatticeVolume<float>(CosetLattice::bcc(), {1, 1, 1}, 1,
                                    {0, std::numeric_limits<double>::infinity(), 0}),
               std::invalid_argument);
  const std::string message = message_of([] {
    LatticeVolume<double>(CosetLattice::bcc(), {0, 1, 1}, 1, {0, 0, 0});
  });
  EXPECT_EQ(message.find('\n'), std::string::npos);
  EXPECT_FALSE(message.empty());
}

TEST(BccLatticeVolume, ToSampleOverflowsToInfinityForFloat) {
  EXPECT_EQ(to_sample<float>(1e300), std::numeric_limits<float>::infinity());
  EXPECT_EQ(to_sample<float>(-1e300), -std::numeric_limits<float>::infinity());
  EXPECT_EQ(to_sample<float>(1.5), 1.5f);
  EXPECT_EQ(to_sample<float>(0.1), 0.1f);
  EXPECT_EQ(to_sample<double>(1e300), 1e300);
}

}  // namespace
}  // namespace boxgen::runtime
