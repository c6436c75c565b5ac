// runtime/gl/glsl_tables.h: the generator's data beside a registry filter's GLSL (its evaluator
// with the run-time-indexed tables in a storage block, and the block's contents) holds what the
// C++ header of the same filter holds (generated/, the generator's other output), in the block's
// order, and the `const` text holds none of it twice. The GL device's evaluation with either
// storage is checked against the CPU in gl_device_test.cpp.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "generated/fcc6.hpp"
#include "generated/m7.hpp"
#include "runtime/gl/gl_context.h"
#include "runtime/gl/gl_spline.h"
#include "runtime/gl/glsl_tables.h"

namespace boxgen::runtime::gl {
namespace {

// What the block must hold, from the C++ header's tables (glsl_tables.cpp's order: the order of
// the GLSL template, lookup then the cells' cube, orbit, keys, perm, sign, a; with several orbits
// the orbits' stencil sizes and reference stencils follow, checked by their sizes).
template <class Traits>
std::vector<int> cell_tables() {
  std::vector<int> out;
  for (const auto& row : Traits::kLookup) out.insert(out.end(), std::begin(row), std::end(row));
  const auto field = [&](auto member) {
    for (const auto& c : Traits::kCells) {
      const auto& v = c.*member;
      if constexpr (std::is_array_v<std::remove_reference_t<decltype(v)>>)
        out.insert(out.end(), std::begin(v), std::end(v));
      else
        out.push_back(v);
    }
  };
  using Cell = std::remove_cv_t<std::remove_extent_t<decltype(Traits::kCells)>>;
  field(&Cell::cube);
  field(&Cell::orbit);
  field(&Cell::keys);
  field(&Cell::perm);
  field(&Cell::sign);
  field(&Cell::a);
  return out;
}

TEST(GlslTables, OneOrbitFilterMovesTheCellTables) {
  for (const bool dbl : {false, true}) {
    const GlslEvaluator glsl = registry_glsl("m7", dbl);
    EXPECT_EQ(glsl.block, cell_tables<generated::m7::Traits>());
    EXPECT_NE(glsl.text.find("const int m7_kLookup["), std::string::npos);
    EXPECT_EQ(glsl.buffered.find("const int m7_kLookup["), std::string::npos);
    EXPECT_EQ(glsl.buffered.find("const int m7_kCellA["), std::string::npos);
    EXPECT_NE(glsl.buffered.find("layout(std430, binding = BOXGEN_TABLES_BINDING) readonly buffer "
                                 "m7_Tables {\n  int m7_kLookup[256];"),
              std::string::npos);
    // One orbit: its reference stencil is indexed by constants and stays a `const` array.
    EXPECT_NE(glsl.buffered.find("const int m7_kReferenceStencil["), std::string::npos);
    EXPECT_NE(glsl.buffered.find("m7_kLookup[cube * m7_kLookupSize + index]"), std::string::npos);
  }
}

TEST(GlslTables, SeveralOrbitsMoveTheOrbitTablesToo) {
  using Traits = generated::fcc6::Traits;
  const GlslEvaluator glsl = registry_glsl("fcc6", true);
  const std::vector<int> cells = cell_tables<Traits>();
  ASSERT_EQ(glsl.block.size(), cells.size() + Traits::kOrbitCount +
                                   Traits::kOrbitCount * Traits::kStencilSize * Traits::kDimension);
  EXPECT_EQ(std::vector<int>(glsl.block.begin(), glsl.block.begin() + cells.size()), cells);
  for (int o = 0; o < Traits::kOrbitCount; ++o)
    EXPECT_EQ(glsl.block[cells.size() + o], Traits::kOrbitStencilSize[o]);
  EXPECT_EQ(glsl.buffered.find("const int fcc6_kReferenceStencil["), std::string::npos);
  EXPECT_NE(glsl.buffered.find("  int fcc6_kReferenceStencil["), std::string::npos);
}

}  // namespace
}  // namespace boxgen::runtime::gl
