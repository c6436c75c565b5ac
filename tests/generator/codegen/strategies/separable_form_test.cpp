// The separable form (generator/separable_form) exists exactly for tensor products (M12,
// tricubic: full grids per coset) and not for M7.
#include "generator/codegen/strategies/separable_form.h"

#include <gtest/gtest.h>

#include "generator/derivation.h"
#include "generator/spec.h"

namespace boxgen::generator {
namespace {

TEST(SeparableForm, SeparableFormExactlyForTensorProducts) {
  for (const char* preset : {"m12", "tricubic"}) {
    const Derivation a = derive(parse_spec(preset));
    const auto grids = separable_form(a.structure.references.at(0), 3);
    ASSERT_TRUE(grids.has_value()) << preset;
    std::size_t points = 0;
    for (const auto& g : *grids) {
      EXPECT_EQ(g.sizes, (std::vector<int>{4, 4, 4})) << preset;
      points += g.stencil.size();
    }
    EXPECT_EQ(points, a.structure.references[0].stencil.size()) << preset;
    EXPECT_EQ(grids->size(), std::string(preset) == "m12" ? 2u : 1u)
        << preset;  // BCC: one grid per coset
  }
  const Derivation m7 = derive(parse_spec("m7"));
  EXPECT_FALSE(separable_form(m7.structure.references.at(0), 3).has_value());
}

}  // namespace
}  // namespace boxgen::generator
