// runtime/gl/glsl_tables.h: the run-time-indexed tables moved from the emitted GLSL's `const`
// arrays into a storage block hold what the C++ header of the same filter holds (generated/, the
// generator's other output), in the block's order; nothing else of the text changes; a text that
// is not an emitted evaluator is refused. The GL device's evaluation with either storage is
// checked against the CPU in gl_device_test.cpp.
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
  const GlslEvaluator glsl = registry_glsl("m7", false);
  const BufferedTables b = tables_in_buffer(glsl.text, "m7", 5);
  EXPECT_EQ(b.block, cell_tables<generated::m7::Traits>());
  EXPECT_EQ(b.text.find("const int m7_kLookup["), std::string::npos);
  EXPECT_EQ(b.text.find("const int m7_kCellA["), std::string::npos);
  EXPECT_NE(b.text.find("layout(std430, binding = 5) readonly buffer m7_Tables {\n  int "
                        "m7_kLookup[256];"),
            std::string::npos);
  // One orbit: its reference stencil is indexed by constants and stays a `const` array.
  EXPECT_NE(b.text.find("const int m7_kReferenceStencil["), std::string::npos);
  EXPECT_NE(b.text.find("m7_kLookup[cube * m7_kLookupSize + index]"), std::string::npos);
}

TEST(GlslTables, SeveralOrbitsMoveTheOrbitTablesToo) {
  using Traits = generated::fcc6::Traits;
  const BufferedTables b = tables_in_buffer(registry_glsl("fcc6", true).text, "fcc6", 7);
  const std::vector<int> cells = cell_tables<Traits>();
  ASSERT_EQ(b.block.size(), cells.size() + Traits::kOrbitCount +
                                Traits::kOrbitCount * Traits::kStencilSize * Traits::kDimension);
  EXPECT_EQ(std::vector<int>(b.block.begin(), b.block.begin() + cells.size()), cells);
  EXPECT_EQ(b.block[cells.size()], Traits::kOrbitStencilSize[0]);
  EXPECT_EQ(b.text.find("const int fcc6_kReferenceStencil["), std::string::npos);
  EXPECT_NE(b.text.find("binding = 7"), std::string::npos);
}

TEST(GlslTables, ATextWithoutTheTablesIsRefused) {
  const GlslEvaluator glsl = registry_glsl("m7", false);
  EXPECT_THROW((void)tables_in_buffer(glsl.text, "m8", 5), GlError);
  std::string broken = glsl.text;
  broken.replace(broken.find("const int m7_kCellSign"), 10, "// int");
  EXPECT_THROW((void)tables_in_buffer(broken, "m7", 5), GlError);
  broken = glsl.text;
  const std::size_t at = broken.find("int[](", broken.find("const int m7_kCellPerm"));
  broken.insert(at + 6, "x");
  EXPECT_THROW((void)tables_in_buffer(broken, "m7", 5), GlError);
}

}  // namespace
}  // namespace boxgen::runtime::gl
