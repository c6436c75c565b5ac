// `boxgen pieces` through the real binary: every format for the spline and the filter, and one
// clear line with exit code 1 for each bad option. The exactness of the pieces themselves is
// tested on the library (tests/generator/pieces_test.cpp: GiNaC round trip, recurrence).
#include <algorithm>

#include "cli_support.h"

namespace boxgen::test {
namespace {

TEST(CliPieces, EveryFormatForSplineAndFilter) {
  for (const std::string of : {"spline", "filter"}) {
    // tricubic: a 3-D preset that derives in a fraction of a second (the sanitized suite runs this
    // too).
    const std::string text = boxgen_ok({"pieces", "tricubic", "--of", of});
    EXPECT_NE(text.find(of == "spline" ? "  s(x,y,z) = " : "  M(x,y,z) = "), std::string::npos)
        << text;
    const std::string latex = boxgen_ok({"pieces", "tricubic", "--of", of, "--format", "latex"});
    EXPECT_NE(latex.find("\\begin{dmath*}"), std::string::npos) << latex;
    const std::string c = boxgen_ok({"pieces", "tricubic", "--of", of, "--format", "c"});
    EXPECT_NE(c.find("double piece_0(double x, double y, double z"), std::string::npos) << c;
    const nlohmann::json j = boxgen_json({"pieces", "tricubic", "--of", of, "--format", "json"});
    ASSERT_TRUE(j.contains("pieces")) << j.dump();
    for (const auto& p : j["pieces"]) {
      EXPECT_TRUE(p["region"].contains("vertices") && p["region"].contains("inequalities"))
          << p.dump();
      EXPECT_EQ(p["polynomial"]["variables"], nlohmann::json({"x", "y", "z"}));
      EXPECT_EQ(p.contains("stencil"), of == "spline");
      for (const auto& q : p["region"]["inequalities"]) exact(q["bound"]);
    }
    EXPECT_EQ(boxgen_json({"pieces", "tricubic", "--of", of, "--json"}), j)
        << "--json is --format json";
  }
  // fcc6's spline has 10 regions per fundamental region in 2 orbits; `all` lists every region.
  EXPECT_EQ(boxgen_json({"pieces", "fcc6", "--region", "all", "--json"})["pieces"].size(), 10u);
  EXPECT_EQ(boxgen_json({"pieces", "fcc6", "--json"})["pieces"].size(), 2u);
  // A 2-D custom matrix: the variables are x and y.
  const nlohmann::json zp =
      boxgen_json({"pieces", "1,0; 0,1; 1,1; -1,1", "--of", "filter", "--json"});
  EXPECT_EQ(zp["pieces"][0]["polynomial"]["variables"], nlohmann::json({"x", "y"}));
}

TEST(CliPieces, BadOptionsGetOneLineAndExitOne) {
  const std::vector<std::pair<std::vector<std::string>, std::string>> cases{
      {{"pieces", "m7", "--region", "middle"}, "--region"},
      {{"pieces", "zp", "--region", "1"}, "orbit index from 0 to 0"},
      {{"pieces", "zp", "--of", "filter", "--region", "5"}, "orbit index from 0 to 4"},
      {{"pieces", "m7", "--format", "pdf"}, "--format"},
      {{"pieces", "m7", "--of", "kernel"}, "--of"},
      {{"pieces", "m99"}, "unknown preset"},
  };
  for (const auto& [args, mention] : cases) {
    const ProcessResult r = boxgen(args);
    const std::string what = describe(args, r);
    ASSERT_TRUE(r.exited) << what;
    EXPECT_EQ(r.exit_code, 1) << what;
    EXPECT_EQ(r.out, "") << what;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << what;
    EXPECT_EQ(r.err.rfind("boxgen: error: ", 0), 0u) << what;
    EXPECT_NE(r.err.find(mention), std::string::npos) << what;
  }
}

}  // namespace
}  // namespace boxgen::test
