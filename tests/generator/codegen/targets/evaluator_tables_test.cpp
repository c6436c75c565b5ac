// The evaluator's tables (generator/codegen/targets/evaluator_tables.h), as numbers: every cell is
// found by its cube and keys in the lookup table, and holds one stencil offset per value of its
// orbit.
#include "generator/codegen/targets/evaluator_tables.h"

#include <gtest/gtest.h>

#include "tests/generator/derivation_fixture.h"

namespace boxgen::generator {
namespace {

TEST(EvaluatorTables, EveryCellIsInTheLookupWithItsStencil) {
  for (const char* preset : {"m7", "fcc6", "zp"}) {
    const Derivation& a = fixture::derivation_of(preset);
    const KnotPlaneKeys keys = knot_plane_keys(a);
    const CellTables t = cell_tables(a, keys, hermite_basis(a));
    const std::size_t cells = a.structure.cells.size();
    ASSERT_EQ(t.cube.size(), cells) << preset;
    ASSERT_EQ(t.offset.size(), cells);
    for (std::size_t c = 0; c < cells; ++c) {
      long index = 0;
      ASSERT_EQ(t.keys[c].size(), keys.planes.size() + 1);
      EXPECT_EQ(t.keys[c].back(), 0);
      for (std::size_t p = 0; p < keys.planes.size(); ++p)
        index += static_cast<long>(t.keys[c][p] - keys.mins[p]) * keys.strides[p];
      EXPECT_EQ(t.lookup.at(t.cube[c]).at(index), static_cast<int>(c)) << preset << " cell " << c;
      EXPECT_EQ(t.offset[c].size(), a.structure.references[t.orbit[c]].stencil.size());
      EXPECT_EQ(t.perm[c].size(), static_cast<std::size_t>(a.spec.dimension()));
    }
  }
}

}  // namespace
}  // namespace boxgen::generator
