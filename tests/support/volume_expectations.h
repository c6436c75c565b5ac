// Two lattice volumes that must be the same volume: lattice, grid and every sample's bits
// (a round trip through a file, a copy, a conversion that must change nothing).
#pragma once
#include <gtest/gtest.h>

#include <cstring>

#include "runtime/lattice_volume.h"

namespace boxgen::test {

template <class T>
void expect_identical(const runtime::LatticeVolume<T>& a, const runtime::LatticeVolume<T>& b) {
  EXPECT_EQ(a.lattice(), b.lattice());
  EXPECT_EQ(a.lattice().name(), b.lattice().name());
  EXPECT_EQ(a.sizes(), b.sizes());
  EXPECT_EQ(a.spacing(), b.spacing());
  EXPECT_EQ(a.origin(), b.origin());
  ASSERT_EQ(a.sample_count(), b.sample_count());
  EXPECT_EQ(std::memcmp(a.samples().data(), b.samples().data(), a.samples().size_bytes()), 0);
}

}  // namespace boxgen::test
