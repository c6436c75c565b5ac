#include "generator/spec.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <functional>
#include <string>

#include "generator/error.h"
#include "tests/generator/paper_directions.h"

namespace boxgen::generator {
namespace {

// Runs `parse`, requires an InputError whose message is one line and mentions `needle`.
void expect_input_error(const std::function<void()>& parse, const std::string& needle) {
  try {
    parse();
    ADD_FAILURE() << "expected an InputError mentioning '" << needle << "'";
  } catch (const InputError& e) {
    const std::string message = e.what();
    EXPECT_FALSE(message.empty());
    EXPECT_EQ(message.find('\n'), std::string::npos) << message;
    EXPECT_EQ(message.find('\r'), std::string::npos) << message;
    EXPECT_NE(message.find(needle), std::string::npos) << "message: " << message;
  }
}

void expect_spec_error(const std::string& spec, const std::string& needle,
                       const std::string& lattice = "") {
  SCOPED_TRACE("SPEC '" + spec + "' lattice '" + lattice + "'");
  expect_input_error([&] { parse_spec(spec, lattice); }, needle);
}

// Columns as the issue states them, written out independently of the preset table.
IntColumns repeat(const IntColumns& block, int times, int sign = 1) {
  IntColumns out;
  for (int t = 0; t < times; ++t)
    for (IntVec c : block) {
      for (auto& v : c) v *= sign;
      out.push_back(c);
    }
  return out;
}
using fixture::kXi1;
using fixture::kXi2;
const IntColumns kIdentity3 = {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}};

IntColumns concat(IntColumns a, const IntColumns& b) {
  a.insert(a.end(), b.begin(), b.end());
  return a;
}

struct ExpectedPreset {
  std::string name;
  int dimension;
  int count;
  std::int64_t det;  // |det G|: bcc 4, fcc 2, cartesian 1 (docs/design.md §1)
  IntColumns directions;
};

std::vector<ExpectedPreset> expected_presets() {
  return {
      {"m7", 3, 7, 4, concat(kXi1, kXi2)},
      {"m8", 3, 8, 4, repeat(kXi1, 2)},
      {"m12", 3, 12, 4, concat(repeat(kXi2, 2), repeat(kXi2, 2, -1))},
      {"cart7", 3, 7, 1, concat(kIdentity3, {{1, 1, 1}, {1, 1, -1}, {1, -1, 1}, {-1, 1, 1}})},
      {"fcc6", 3, 6, 2, {{1, 1, 0}, {1, -1, 0}, {1, 0, 1}, {1, 0, -1}, {0, 1, 1}, {0, 1, -1}}},
      {"tricubic", 3, 12, 1, repeat(kIdentity3, 4)},
      {"hex3", 2, 3, 1, {{1, 0}, {0, 1}, {1, 1}}},
      {"zp", 2, 4, 1, {{1, 0}, {0, 1}, {1, 1}, {-1, 1}}},
  };
}

TEST(Spec, EveryPresetParsesWithItsDimensionCountAndLattice) {
  const auto expected = expected_presets();
  ASSERT_EQ(presets().size(), expected.size());
  for (const auto& e : expected) {
    SCOPED_TRACE(e.name);
    const BoxSplineSpec spec = parse_spec(e.name);
    EXPECT_EQ(spec.name, e.name);
    EXPECT_EQ(spec.dimension(), e.dimension);
    EXPECT_EQ(spec.count(), e.count);
    EXPECT_EQ(spec.lattice.det_abs(), e.det);
    EXPECT_EQ(spec.directions, e.directions);
  }
}

TEST(Spec, PresetTableIsConsistent) {
  for (const auto& p : presets()) {
    SCOPED_TRACE(p.name);
    EXPECT_FALSE(p.description.empty());
    EXPECT_EQ(p.description.find('\n'), std::string::npos);
    // The listed direction text and lattice name reproduce the preset when given explicitly.
    const BoxSplineSpec by_name = parse_spec(p.name);
    const BoxSplineSpec by_text = parse_spec(p.directions, p.lattice);
    EXPECT_EQ(by_text.name, "custom");
    EXPECT_EQ(by_text.directions, by_name.directions);
    EXPECT_EQ(by_text.lattice.generator(), by_name.lattice.generator());
    EXPECT_EQ(by_name.directions_text(), p.directions);
  }
}

TEST(Spec, PresetNamesAreCaseInsensitiveAndKeepTheUsersText) {
  const BoxSplineSpec spec = parse_spec("  M7 ");
  EXPECT_EQ(spec.name, "m7");
  EXPECT_EQ(spec.text, "  M7 ");
  EXPECT_EQ(spec.lattice.name(), "bcc");
}

TEST(Spec, CustomListParsesWithCommasOrBlanks) {
  const BoxSplineSpec a =
      parse_spec("1,1,1; 1,-1,-1; -1,1,-1; -1,-1,1; 2,0,0; 0,2,0; 0,0,2", "bcc");
  EXPECT_EQ(a.name, "custom");
  EXPECT_EQ(a.directions, concat(kXi1, kXi2));
  EXPECT_EQ(a.lattice.det_abs(), 4);

  const BoxSplineSpec b = parse_spec("1 0; 0 1; 1 1");
  EXPECT_EQ(b.dimension(), 2);
  EXPECT_EQ(b.directions, (IntColumns{{1, 0}, {0, 1}, {1, 1}}));
  EXPECT_EQ(b.lattice.name(), "cartesian");  // default for a direction list
  EXPECT_EQ(b.lattice.det_abs(), 1);

  const BoxSplineSpec c = parse_spec("\t1 ,0 ;\n0, +1;  -1\t-1 ;; ");  // trailing ';' tolerated
  EXPECT_EQ(c.directions, (IntColumns{{1, 0}, {0, 1}, {-1, -1}}));
  EXPECT_EQ(c.directions_text(), "1,0; 0,1; -1,-1");
}

TEST(Spec, LatticeOverridesAndNames) {
  EXPECT_EQ(parse_spec("m7", "cartesian").lattice.det_abs(), 1);
  EXPECT_EQ(parse_spec("m7", "BCC").lattice.det_abs(), 4);
  EXPECT_EQ(parse_spec("fcc6", " Fcc ").lattice.det_abs(), 2);
  // Explicit rows equal to the BCC generator give the same lattice as the name.
  const BoxSplineSpec rows = parse_spec("m8", "-1 1 1; 1 -1 1; 1 1 -1");
  EXPECT_EQ(rows.lattice.det_abs(), 4);
  for (const IntVec& p : {IntVec{1, 1, 1}, IntVec{2, 0, 0}, IntVec{1, 0, 0}, IntVec{1, 1, 0}})
    EXPECT_EQ(rows.lattice.contains(p), Lattice::bcc().contains(p));
}

TEST(Spec, LatticeRowsAreRowsOfG) {
  // G = [[1,1],[0,2]] has columns (1,0) and (1,2): it contains (1,0) and (0,2) but not (0,1).
  // Reading the text as columns would give (1,1),(0,2), which does not contain (1,0).
  const Lattice l = parse_lattice("1 1; 0 2", 2);
  EXPECT_EQ(l.generator(), (IntColumns{{1, 0}, {1, 2}}));
  EXPECT_EQ(l.det_abs(), 2);
  EXPECT_TRUE(l.contains({1, 0}));
  EXPECT_TRUE(l.contains({0, 2}));
  EXPECT_FALSE(l.contains({0, 1}));
  EXPECT_EQ(parse_spec("1,0; 0,2; 1,2", "1 1; 0 2").lattice.det_abs(), 2);
}

TEST(Spec, LimitsAreInclusive) {
  // 32 directions are allowed.
  std::string thirty_two;
  for (int k = 0; k < 16; ++k) thirty_two += "1,0; 0,1; ";
  EXPECT_EQ(parse_spec(thirty_two).count(), 32);
  // Components of magnitude 64 are allowed; bounding box 128 x 128 x 64 = 1048576 cells is below
  // the limit.
  EXPECT_EQ(parse_spec("64,0,0; 64,0,0; 0,-64,0; 0,64,0; 0,0,64").count(), 5);
}

// --- bad input: one test per case, each a single-line InputError ---

TEST(SpecErrors, MalformedText) {
  expect_spec_error("", "empty SPEC");
  expect_spec_error("  ;  ", "empty SPEC");
  expect_spec_error("1,0;;0,1", "direction 2 is empty");
  expect_spec_error("1,,0; 0,1", "empty entry");
  expect_spec_error("1,0,; 0,1", "empty entry");
  expect_spec_error("1,0; 0,1,1", "same dimension");
  expect_spec_error("1,0,0,0; 0,1,0,0; 0,0,1,0; 0,0,0,1", "2 or 3 entries");
  expect_spec_error("1; 2", "2 or 3 entries");
}

TEST(SpecErrors, NonNumericComponent) {
  expect_spec_error("1,a,1; 0,1,0; 0,0,1", "'a', which is not an integer");
  expect_spec_error("1.5,0; 0,1", "'1.5', which is not an integer");
  expect_spec_error("1,-; 0,1", "'-', which is not an integer");
}

TEST(SpecErrors, ZeroMatrix) {
  expect_spec_error("0,0,0; 0,0,0; 0,0,0", "zero vector");
  expect_spec_error("1,0; 0,0; 0,1", "direction 2 (0,0) is the zero vector");
}

TEST(SpecErrors, RankDeficientMatrix) {
  expect_spec_error("1,0,0; 0,1,0; 1,1,0; 2,0,0", "rank-deficient");
  expect_spec_error("1,1; 2,2; -1,-1", "rank-deficient");
  expect_spec_error("1,0,0; 0,1,0", "rank-deficient");  // fewer directions than the dimension
}

TEST(SpecErrors, DirectionNotInLattice) {
  expect_spec_error("1,0,0; 0,1,0; 0,0,1", "direction 1 (1,0,0) is not a point of the bcc lattice",
                    "bcc");
  expect_spec_error("m7", "not a point of the fcc lattice", "fcc");
  expect_spec_error("1,0; 0,1", "not a point of the lattice with generator rows '1,1; 0,2'",
                    "1 1; 0 2");
}

TEST(SpecErrors, SingularLattice) {
  expect_spec_error("1,0; 0,1", "singular lattice", "1 2; 2 4");
  expect_input_error([] { parse_lattice("1,1,0; 0,1,1; 1,2,1", 3); }, "singular lattice");
}

TEST(SpecErrors, LatticeTextProblems) {
  expect_spec_error("1,0; 0,1", "3-dimensional but the directions are 2-dimensional", "bcc");
  expect_spec_error("1,0; 0,1", "3-dimensional but the directions are 2-dimensional",
                    "1 0 0; 0 1 0; 0 0 1");
  expect_spec_error("1,0,0; 0,1,0; 0,0,1", "must be square", "1 0 0; 0 1 0");
  expect_spec_error("1,0; 0,1", "unknown lattice 'hexagonal'", "hexagonal");
  expect_spec_error("1,0; 0,1", "not an integer", "1 x; 0 1");
  expect_spec_error("1,0; 0,1", "at most 1000", "1 0; 0 5000");
  expect_input_error([] { parse_lattice("", 3); }, "empty lattice");
}

TEST(SpecErrors, MoreThan32Directions) {
  std::string thirty_three;
  for (int k = 0; k < 33; ++k) thirty_three += (k % 2 ? "1,0;" : "0,1;");
  expect_spec_error(thirty_three, "33 directions given: at most 32");
}

TEST(SpecErrors, UnknownPresetListsTheValidNames) {
  expect_spec_error(
      "m9", "unknown preset 'm9': valid presets are m7, m8, m12, cart7, fcc6, tricubic, hex3, zp");
}

TEST(SpecErrors, HugeComponent) {
  expect_spec_error("65,0; 0,1", "'65', which is too large to derive");
  expect_spec_error("1,0; 0,-100", "'-100', which is too large to derive");
  // Absurdly long numbers are rejected without overflow, and echoed only in part.
  const std::string huge(5000, '9');
  expect_spec_error(huge + ",0; 0,1", "too large to derive");
  expect_spec_error("1,0; 0,1", "at most 1000", "1 0; 0 " + huge);
  expect_spec_error("-9223372036854775808,0; 0,1", "too large to derive");
  // Leading zeros do not make a small number large.
  EXPECT_EQ(parse_spec("00000000000000000000000000001,0; 0,1").directions[0], (IntVec{1, 0}));
}

TEST(SpecErrors, SupportTooLargeToDerive) {
  // Bounding box 128 x 128 x 128 = 2097152 unit cells > 2000000.
  expect_spec_error("64,0,0; 64,0,0; 0,64,0; 0,64,0; 0,0,64; 0,0,64",
                    "support too large to derive");
}

TEST(SpecErrors, MessagesStayOneLineForAnyInput) {
  expect_spec_error("1,0;\n0,x\ny", "not an integer");
  expect_spec_error("m\n7", "unknown preset 'm?7'");
  expect_spec_error(std::string("1,0; 0,\0", 8), "not an integer");
  expect_spec_error("1,0; 0,1", "unknown lattice", "bc\nc");
}

}  // namespace
}  // namespace boxgen::generator
