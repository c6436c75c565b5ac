// boxgen metrics / kernel / spectrum as a user's script sees them: the JSON contract, the figures
// (a real PNG appears, nothing else), and bad input giving one line on stderr, exit code 1 or 2
// and no file left behind. Expected values: the paper's printed smoothing digits (an independent
// computation), the exact a(0) of M7 from docs/design.md §9, and hand-derived facts (E(0) = 0,
// |psi_hat(0)| = 1, the Nyquist interval of BCC along (1,0,0) is [-pi, pi]).
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <numbers>
#include <sstream>

#include "cli_support.h"
#include "png_file.h"
#include "tests/support/scratch_directory.h"

namespace boxgen::test {
namespace {

namespace fs = std::filesystem;

class AnalysisCli : public ScratchDirectoryTest {
 protected:
  AnalysisCli() : ScratchDirectoryTest("boxgen-analysis-cli") {}
  std::string file(const std::string& name) const { return (dir_ / name).string(); }
  std::vector<std::string> listing() const {
    std::vector<std::string> names;
    for (const auto& e : fs::directory_iterator(dir_))
      names.push_back(e.path().filename().string());
    std::sort(names.begin(), names.end());
    return names;
  }
  static bool is_png(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    char sig[8] = {};
    in.read(sig, 8);
    return in && std::string(sig + 1, 3) == "PNG" && static_cast<unsigned char>(sig[0]) == 0x89;
  }
};

TEST_F(AnalysisCli, MetricsJsonHasTheDocumentedKeysAndThePapersSmoothing) {
  const auto j = boxgen_json({"metrics", "m7", "m8", "m12", "--json"});
  EXPECT_EQ(exact(j["m7"]["integral_squared"]), Q("39559/1064448"));  // docs/design.md §9
  const std::map<std::string, double> paper_s = {
      {"m7", 0.85488}, {"m8", 0.85287}, {"m12", 0.94495}};
  for (const auto& [key, s] : paper_s) {
    ASSERT_TRUE(j.contains(key)) << key;
    EXPECT_NEAR(j[key]["smoothing"].get<double>(), s, 0.5e-5) << key;
    const double p = j[key]["postaliasing"].get<double>();
    EXPECT_GT(p, 0) << key;
    EXPECT_LT(p, 0.01) << key;
    EXPECT_LT(j[key]["estimated_error"].get<double>(), 1e-9) << key;
  }
  // Measured: M7's postaliasing is below M8's (the paper's claim).
  EXPECT_LT(j["m7"]["postaliasing"].get<double>(), j["m8"]["postaliasing"].get<double>());
}

TEST_F(AnalysisCli, MetricsAreKeyedBySpecAsGiven) {
  const auto j = boxgen_json({"metrics", "1,0; 0,1; 1,1", "tricubic", "--json"});
  EXPECT_TRUE(j.contains("1,0; 0,1; 1,1"));
  EXPECT_TRUE(j.contains("tricubic"));
  EXPECT_EQ(j["tricubic"]["lattice"], "cartesian");
}

TEST_F(AnalysisCli, KernelJsonVanishesAtZeroAndGrows) {
  const auto j = boxgen_json({"kernel", "m7", "--prefilter", "q2", "--w", "0,0.1,0.5,1", "--json"});
  ASSERT_EQ(j["w"].size(), 4u);
  ASSERT_EQ(j["E"].size(), 4u);
  EXPECT_NEAR(j["E"][0].get<double>(), 0, 1e-14);
  for (int i = 1; i < 4; ++i) EXPECT_GT(j["E"][i].get<double>(), j["E"][i - 1].get<double>());
  const auto r = boxgen_json({"kernel", "m8", "--prefilter", "min", "--from", "0.1", "--to", "1",
                              "--steps", "10", "--json"});
  EXPECT_EQ(r["w"].size(), 10u);
  EXPECT_DOUBLE_EQ(r["w"][9].get<double>(), 1.0);
}

// The new prefilters: interp and qfir:K lie above E_min and vanish at 0; on M8 qfir:3 and interp
// are below no prefilter at w = 1 along (1,1,1) (as measured: 1.2e-2 and 1.1e-2 vs 0.43).
TEST_F(AnalysisCli, KernelTakesInterpAndQfir) {
  const std::vector<std::string> w{"--w", "0,0.5,1", "--json"};
  auto run = [&](const char* filter, const char* prefilter) {
    std::vector<std::string> args{"kernel", filter, "--prefilter", prefilter};
    args.insert(args.end(), w.begin(), w.end());
    return boxgen_json(args);
  };
  const auto lo = run("m8", "min"), interp = run("m8", "interp"), fir = run("m8", "qfir:3"),
             none = run("m8", "none");
  for (int i = 0; i < 3; ++i) {
    EXPECT_GE(interp["E"][i].get<double>(), lo["E"][i].get<double>() - 1e-15);
    EXPECT_GE(fir["E"][i].get<double>(), lo["E"][i].get<double>() - 1e-15);
  }
  EXPECT_NEAR(interp["E"][0].get<double>(), 0, 1e-14);
  EXPECT_NEAR(fir["E"][0].get<double>(), 0, 1e-14);
  EXPECT_LT(fir["E"][2].get<double>(), none["E"][2].get<double>());
  EXPECT_LT(interp["E"][2].get<double>(), none["E"][2].get<double>());
}

// Where the symbol vanishes (M7, M12) interp is the runtime's regularised interpolation, by default
// with lambda 1e-3 (tests/analysis checks its Q against the runtime's coefficients): its kernel
// keeps the order (E(0) = 0), lies above E_min, and changes with lambda. On M8 interp is exact:
// interp:0 is the same kernel.
TEST_F(AnalysisCli, KernelTakesTheRegularisedInterpolation) {
  auto run = [](const char* filter, const char* prefilter) {
    return boxgen_json({"kernel", filter, "--prefilter", prefilter, "--w", "0,0.5,1,2", "--json"});
  };
  for (const char* filter : {"m7", "m12"}) {
    const auto lo = run(filter, "min"), interp = run(filter, "interp"),
               same = run(filter, "interp:0.001"), other = run(filter, "interp:0.1");
    EXPECT_NEAR(interp["E"][0].get<double>(), 0, 1e-14) << filter;
    for (int i = 0; i < 4; ++i) {
      EXPECT_GE(interp["E"][i].get<double>(), lo["E"][i].get<double>() - 1e-15) << filter;
      EXPECT_EQ(interp["E"][i].get<double>(), same["E"][i].get<double>()) << filter;
    }
    EXPECT_NE(interp["E"][3].get<double>(), other["E"][3].get<double>()) << filter;
  }
  EXPECT_EQ(run("m8", "interp")["E"], run("m8", "interp:0")["E"]);
}

// q2opt: the free parameter printed to 17 digits (it reads back as the double of --json), the
// weights not exact, the integrated error kernel lowered; kernel takes it and keeps the order
// (E(0) = 0); q1opt of M8 has no free parameter and is Q^I, exactly.
TEST_F(AnalysisCli, PrefilterAndKernelTakeTheOptimisedPrefilters) {
  const auto q = boxgen_json({"prefilter", "m8", "--prefilter", "q2opt", "--json"});
  EXPECT_FALSE(q["exact"].get<bool>());
  const auto& o = q["optimisation"];
  ASSERT_EQ(o["parameters"].size(), 1U);
  EXPECT_LT(o["integrated_error_kernel"].get<double>(),
            o["integrated_error_kernel_at_zero"].get<double>());
  const double t = o["parameters"][0]["value"].get<double>();
  const std::string text = boxgen_ok({"prefilter", "m8", "--prefilter", "q2opt"});
  std::array<char, 64> printed{};
  std::snprintf(printed.data(), printed.size(), "= %.17g\n", t);
  EXPECT_NE(text.find(printed.data()), std::string::npos) << text;
  const auto q1 = boxgen_json({"prefilter", "m8", "--prefilter", "q1", "--json"});
  const auto q1opt = boxgen_json({"prefilter", "m8", "--prefilter", "q1opt", "--json"});
  EXPECT_TRUE(q1opt["exact"].get<bool>());
  EXPECT_EQ(q1opt["weights"], q1["weights"]);

  const auto kernel = boxgen_json({"kernel", "m8", "--prefilter", "q2opt", "--w", "0,1", "--json"});
  EXPECT_NEAR(kernel["E"][0].get<double>(), 0, 1e-14);
}

// --equal-density: the tricubic B-spline on Z^3 and the same spline scaled by 2 (directions 2 e_i
// on the lattice 2 Z^3, 1/8 the density) are one filter at unit density, so their kernels,
// spectra and metrics agree; without the flag they differ (the scaled one at w is the first at
// 2 w).
TEST_F(AnalysisCli, EqualDensityComparesAFilterWithItselfOnAScaledLattice) {
  const std::string one =
      "1,0,0; 0,1,0; 0,0,1; 1,0,0; 0,1,0; 0,0,1; 1,0,0; 0,1,0; 0,0,1; 1,0,0; "
      "0,1,0; 0,0,1@cartesian";
  const std::string two =
      "2,0,0; 0,2,0; 0,0,2; 2,0,0; 0,2,0; 0,0,2; 2,0,0; 0,2,0; 0,0,2; 2,0,0; "
      "0,2,0; 0,0,2@2,0,0; 0,2,0; 0,0,2";
  const std::vector<std::string> labels{"--label", "a", "--label", "b"};
  auto run = [&](std::vector<std::string> args, bool equal) {
    args.insert(args.begin() + 1, {one, two});
    args.insert(args.end(), labels.begin(), labels.end());
    args.push_back("--json");
    if (equal) args.push_back("--equal-density");
    return boxgen_json(args);
  };
  for (const char* prefilter : {"q1", "min"}) {
    const auto k = run({"kernel", "--prefilter", prefilter, "--w", "0.25,0.5,1,2"}, true);
    const auto plain = run({"kernel", "--prefilter", prefilter, "--w", "0.5,1,2"}, false);
    for (int i = 0; i < 4; ++i)
      EXPECT_NEAR(k["a"]["E"][i].get<double>(), k["b"]["E"][i].get<double>(),
                  1e-12 * (1 + k["a"]["E"][i].get<double>()))
          << prefilter << " " << i;
    // Without the flag the scaled spline at w is the first at 2 w.
    for (int i = 0; i < 2; ++i)
      EXPECT_NEAR(plain["b"]["E"][i].get<double>(), plain["a"]["E"][i + 1].get<double>(),
                  1e-12 * (1 + plain["a"]["E"][i + 1].get<double>()))
          << prefilter;
    EXPECT_GT(plain["b"]["E"][1].get<double>(), 10 * plain["a"]["E"][1].get<double>());
  }
  const auto s = run({"spectrum", "--line", "1,1,0", "--w", "0.5,1,2"}, true);
  for (int i = 0; i < 3; ++i)
    EXPECT_NEAR(s["a"]["magnitude"][i].get<double>(), s["b"]["magnitude"][i].get<double>(), 1e-14);
  EXPECT_NEAR(s["b"]["nyquist_interval"][1].get<double>(), std::numbers::pi, 1e-12);
  const auto m = run({"metrics"}, true);
  for (const char* key : {"smoothing", "postaliasing", "nyquist_volume", "integral_total"})
    EXPECT_NEAR(m["a"][key].get<double>(), m["b"][key].get<double>(),
                1e-12 * m["a"][key].get<double>())
        << key;
  EXPECT_NEAR(m["b"]["nyquist_volume"].get<double>(), std::pow(2 * std::numbers::pi, 3), 1e-9);
}

TEST_F(AnalysisCli, SpectrumLineJsonAndTheNyquistInterval) {
  const auto j = boxgen_json(
      {"spectrum", "m7", "--line", "1,0,0", "--from", "0", "--to", "6", "--steps", "7", "--json"});
  EXPECT_NEAR(j["magnitude"][0].get<double>(), 1.0, 1e-15);
  EXPECT_NEAR(j["nyquist_interval"][1].get<double>(), std::numbers::pi, 1e-12);
  // psi_hat of M7 vanishes at w = 2 pi e_1, a dual lattice point (partition of unity).
  const auto z =
      boxgen_json({"spectrum", "m7", "--line", "1,0,0", "--w", "6.283185307179586", "--json"});
  EXPECT_NEAR(z["magnitude"][0].get<double>(), 0, 1e-12);
}

TEST_F(AnalysisCli, FiguresAreWrittenAsPngAndNothingElse) {
  boxgen_ok({"kernel", "m7", "m8", "--plot", file("k.png")});
  boxgen_ok({"spectrum", "m7", "--line", "1,1,0", "-o", file("l.png")});
  boxgen_ok({"spectrum", "m12", "m7", "--plane", "1,1,1", "--size", "64", "-o", file("p.png")});
  EXPECT_TRUE(is_png(file("k.png")));
  EXPECT_TRUE(is_png(file("l.png")));
  EXPECT_TRUE(is_png(file("p.png")));
  EXPECT_EQ(listing(), (std::vector<std::string>{"k.png", "l.png", "p.png"}));
}

// FCC's directions as a list (no preset), so its lattice comes from '@' or --lattice only.
constexpr const char* kFccDirections = "1,1,0; 1,-1,0; 1,0,1; 1,0,-1; 0,1,1; 0,1,-1";

TEST_F(AnalysisCli, EachSpecMayNameItsLattice) {
  const std::string on_fcc = std::string(kFccDirections) + "@fcc";
  const auto mixed = boxgen_json({"metrics", "m7", on_fcc, "--json"});
  const auto fcc = boxgen_json({"metrics", kFccDirections, "--lattice", "fcc", "--json"});
  const auto cartesian = boxgen_json({"metrics", kFccDirections, "--json"});
  ASSERT_TRUE(mixed.contains(on_fcc)) << mixed.dump();
  EXPECT_EQ(mixed[on_fcc]["lattice"], "fcc");
  EXPECT_EQ(mixed["m7"]["lattice"], "bcc");
  // SPEC@fcc is the SPEC with --lattice fcc, and not the SPEC on its default (Cartesian) lattice.
  for (const char* key : {"smoothing", "postaliasing", "integral_squared"})
    EXPECT_EQ(mixed[on_fcc][key], fcc[kFccDirections][key]) << key;
  EXPECT_EQ(cartesian[kFccDirections]["lattice"], "cartesian");
  EXPECT_NE(cartesian[kFccDirections]["smoothing"], fcc[kFccDirections]["smoothing"]);
  // '@' wins over --lattice, which is the default of the SPECs without one.
  const auto both = boxgen_json({"metrics", on_fcc, "m7", "--lattice", "bcc", "--json"});
  EXPECT_EQ(both[on_fcc]["lattice"], "fcc");
  EXPECT_EQ(both["m7"]["lattice"], "bcc");
}

// The Nyquist extent along w (1,1,1) by hand: Z^3's dual is 2 pi Z^3, whose Voronoi cell
// [-pi, pi]^3 gives t = pi; FCC's dual is 2 pi times the BCC lattice Z^3 u (Z^3 + 1/2), whose
// neighbour k = 2 pi (1/2, 1/2, 1/2) bounds the cell by w . k <= |k|^2 / 2, i.e. 3 pi t <= 3 pi^2 /
// 2, t = pi / 2.
TEST_F(AnalysisCli, SpectrumLinesOnTwoLatticesHaveTheirOwnNyquistIntervals) {
  const auto j = boxgen_json({"spectrum", "fcc6", "fcc6@cartesian", "--line", "1,1,1", "--w", "0,1",
                              "--label", "FCC", "--label", "Z3", "--json"});
  ASSERT_TRUE(j.contains("FCC") && j.contains("Z3")) << j.dump();
  EXPECT_NEAR(j["FCC"]["nyquist_interval"][1].get<double>(), std::numbers::pi / 2, 1e-12);
  EXPECT_NEAR(j["Z3"]["nyquist_interval"][1].get<double>(), std::numbers::pi, 1e-12);
  EXPECT_NEAR(j["FCC"]["magnitude"][0].get<double>(), 1.0, 1e-15);  // psi_hat(0) = 1
}

TEST_F(AnalysisCli, LabelsNameTheRowsAndKeys) {
  const auto j =
      boxgen_json({"metrics", "m7", "m8", "--label", "quartic M7", "--label", "M8", "--json"});
  EXPECT_TRUE(j.contains("quartic M7") && j.contains("M8")) << j.dump();
  EXPECT_FALSE(j.contains("m7"));
  const auto k =
      boxgen_json({"kernel", "m7", "m8", "--w", "0.5", "--label", "a", "--label", "b", "--json"});
  EXPECT_TRUE(k.contains("a") && k.contains("b")) << k.dump();
  const ProcessResult r = boxgen({"metrics", "m7", "--label", "quartic"});
  ASSERT_TRUE(r.exited && r.exit_code == 0) << describe({"metrics"}, r);
  EXPECT_NE(r.out.find("\nquartic "), std::string::npos) << r.out;  // the table's row
}

// Two panels of --size 64 are 2 (64 + 200) x (64 + 100) pixels (docs/cli.md). Each panel's
// colour bar is a column right of its image running from the colour map's top, viridis yellow
// (0.993, 0.906, 0.144) * 255, down to its bottom, (0.267, 0.005, 0.329) * 255, without white
// (within 20 of each: gnuplot draws the bar in steps whose colours are sampled inside them);
// the image itself (64 pixels square, its centre yellow) sits in the left half of the panel.
TEST_F(AnalysisCli, PlaneImagesHaveAPanelPerSpecWithAColourBar) {
  boxgen_ok({"spectrum", "m7", "fcc6@fcc", "--plane", "1,1,1", "--size", "64", "--label", "M7",
             "--label", "FCC6", "-o", file("p.png")});
  const Png p = read_png(file("p.png"));
  ASSERT_EQ(p.width, 2 * (64 + 200));
  ASSERT_EQ(p.height, 64 + 100);
  const auto near = [](std::array<int, 3> c, std::array<int, 3> want) {
    return std::abs(c[0] - want[0]) <= 20 && std::abs(c[1] - want[1]) <= 20 &&
           std::abs(c[2] - want[2]) <= 20;
  };
  const std::array<int, 3> top{253, 231, 37}, bottom{68, 1, 84};
  for (int panel = 0; panel < 2; ++panel) {
    const int x0 = panel * (64 + 200), x1 = x0 + 64 + 200;
    int bar = -1;  // the rightmost column of the panel holding the top colour
    for (int x = x0; x < x1; ++x)
      for (int y = 0; y < p.height; ++y)
        if (near(p.at(x, y), top)) bar = x;
    ASSERT_GE(bar, x0 + (x1 - x0) / 2) << "panel " << panel;
    int y = 0;
    while (!near(p.at(bar, y), top)) ++y;
    int run = 0;
    for (; y < p.height && !near(p.at(bar, y), bottom); ++y, ++run)
      ASSERT_NE(p.at(bar, y), (std::array<int, 3>{255, 255, 255}))
          << "panel " << panel << " y " << y;
    EXPECT_LT(y, p.height) << "no bottom colour below the top in panel " << panel;
    EXPECT_GE(run, 32) << "panel " << panel;  // a bar, not a speck
  }
}

TEST_F(AnalysisCli, RenderWritesAPngOfTheRequestedSize) {
  const ProcessResult r =
      boxrecon({"render", "--function", "ml", "--n", "17", "--filter", "m7", "--prefilter", "q1",
                "--cutaway", "--width", "40", "--height", "30", "--quiet", "-o", file("r.png")});
  ASSERT_TRUE(r.exited && r.exit_code == 0) << describe({"render"}, r);
  EXPECT_EQ(r.err, "");
  ASSERT_TRUE(is_png(file("r.png")));
  std::ifstream in(file("r.png"), std::ios::binary);
  unsigned char header[24] = {};
  in.read(reinterpret_cast<char*>(header), 24);
  const auto be32 = [&](int at) {
    return (header[at] << 24) | (header[at + 1] << 16) | (header[at + 2] << 8) | header[at + 3];
  };
  EXPECT_EQ(be32(16), 40);  // IHDR width
  EXPECT_EQ(be32(20), 30);  // IHDR height
  EXPECT_EQ(listing(), (std::vector<std::string>{"r.png"}));
}

// render --min/--max (or --box): the default box given explicitly ([-1,1]^3 for --function) is the
// same picture byte for byte; a smaller box another one; a box beyond the region the filter
// reconstructs one line and no file.
TEST_F(AnalysisCli, RenderTakesABox) {
  const std::vector<std::string> base{"render",  "--function", "ml",       "--n", "13",
                                      "--width", "24",         "--height", "20",  "--quiet"};
  const auto render = [&](std::vector<std::string> extra, const std::string& name) {
    std::vector<std::string> args = base;
    args.insert(args.end(), extra.begin(), extra.end());
    args.insert(args.end(), {"-o", file(name)});
    const ProcessResult r = boxrecon(args);
    EXPECT_TRUE(r.exited && r.exit_code == 0) << describe(args, r);
    std::ifstream in(file(name), std::ios::binary);
    return std::string(std::istreambuf_iterator<char>(in), {});
  };
  const std::string plain = render({}, "plain.png");
  ASSERT_FALSE(plain.empty());
  EXPECT_EQ(render({"--min", "-1", "-1", "-1", "--max", "1", "1", "1"}, "same.png"), plain);
  const std::string small =
      render({"--min", "-0.5", "-1", "-1", "--max", "1", "0.6", "1"}, "small.png");
  EXPECT_NE(small, plain);
  // --box LO HI, the same boxes: one number per corner (the cube), or x,y,z.
  EXPECT_EQ(render({"--box", "-1", "1"}, "box.png"), plain);
  EXPECT_EQ(render({"--box", "-0.5,-1,-1", "1,0.6,1"}, "small_box.png"), small);
  std::vector<std::string> outside = base;
  outside.insert(outside.end(),
                 {"--min", "-3", "-1", "-1", "--max", "1", "1", "1", "-o", file("out.png")});
  const ProcessResult r = boxrecon(outside);
  EXPECT_TRUE(r.exited && r.exit_code == 1) << describe(outside, r);
  EXPECT_NE(r.err.find("leaves the region the m7 filter reconstructs"), std::string::npos) << r.err;
  EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
  EXPECT_FALSE(fs::exists(file("out.png")));
}

TEST_F(AnalysisCli, ErrorTableJsonHasEveryRowAndKey) {
  const ProcessResult r = boxrecon({"error", "--table", "--points", "200", "--json"});
  ASSERT_TRUE(r.exited && r.exit_code == 0) << describe({"error", "--table"}, r);
  const auto j = nlohmann::json::parse(r.out);
  // 5 densities x (3 filters x 6 prefilters (none q1 q2 q2opt qfir:3 interp) + 3 tricubic rows).
  ASSERT_EQ(j["rows"].size(), 105u);
  int interp_rows = 0, qfir_rows = 0, optimised_rows = 0;
  for (const auto& row : j["rows"]) {
    for (const char* key : {"n", "filter", "prefilter", "rms", "max", "gradient_rms", "samples"})
      EXPECT_TRUE(row.contains(key)) << key << " in " << row.dump();
    const int n = row["n"].get<int>();
    EXPECT_LE(row["rms"].get<double>(), row["max"].get<double>());
    interp_rows += row["prefilter"] == "interp";
    qfir_rows += row["prefilter"] == "qfir:3";
    optimised_rows += row["prefilter"] == "q2opt";
    if (row["filter"] == "tricubic") {
      const int m = static_cast<int>(std::lround(std::cbrt(2.0) * n));
      EXPECT_EQ(row["cartesian_n"].get<int>(), m);
      EXPECT_EQ(row["samples"].get<std::uint64_t>(), static_cast<std::uint64_t>(m) * m * m);
    } else {
      EXPECT_FALSE(row.contains("cartesian_n"));
      EXPECT_EQ(row["samples"].get<std::uint64_t>(), 2ull * n * n * n);
    }
  }
  EXPECT_EQ(interp_rows, 5 * 4);
  EXPECT_EQ(qfir_rows, 5 * 3);
  EXPECT_EQ(optimised_rows, 5 * 3);
}

// eval --hessian: the cubic x^3 - 2xyz + 3y^2 - z + 1 (runtime/test_functions.h) is reproduced by
// every filter with Q^I, so its second derivatives, written out here by hand, come back exactly
// (up to rounding): h_xx = 6x, h_xy = -2z, h_xz = -2y, h_yy = 6, h_yz = -2x, h_zz = 0.
TEST_F(AnalysisCli, EvalHessianReproducesTheCubicsSecondDerivatives) {
  ProcessResult r = boxrecon({"sample", "--function", "cubic", "--n", "9", "-o", file("c.nrrd")});
  ASSERT_TRUE(r.exited && r.exit_code == 0) << describe({"sample"}, r);
  {
    std::ofstream out(file("p.txt"));
    out << "0.1 -0.2 0.3\n-0.55 0.4 0.05\n0.7 0.7 -0.6\n";
  }
  const double pts[3][3] = {{0.1, -0.2, 0.3}, {-0.55, 0.4, 0.05}, {0.7, 0.7, -0.6}};
  for (const char* filter : {"m7", "m8", "m12"}) {
    r = boxrecon({"eval", "--filter", filter, "--prefilter", "q1", "--volume", file("c.nrrd"),
                  "--points", file("p.txt"), "--gradient", "--hessian"});
    ASSERT_TRUE(r.exited && r.exit_code == 0) << describe({"eval", filter}, r);
    std::istringstream lines(r.out);
    for (const auto& p : pts) {
      double v[10];
      for (double& x : v) ASSERT_TRUE(lines >> x) << r.out;
      const double x = p[0], y = p[1], z = p[2];
      const double expected[6] = {6 * x, -2 * z, -2 * y, 6, -2 * x, 0};
      for (int k = 0; k < 6; ++k)
        EXPECT_NEAR(v[4 + k], expected[k], 1e-8)
            << filter << " h" << k << " at " << x << "," << y << "," << z;
    }
  }
}

TEST_F(AnalysisCli, RenderWithCurvatureShading) {
  const ProcessResult r =
      boxrecon({"render", "--function", "ml", "--n", "17", "--shading", "curvature", "--width",
                "32", "--height", "32", "--quiet", "-o", file("c.png")});
  ASSERT_TRUE(r.exited && r.exit_code == 0) << describe({"render", "--shading", "curvature"}, r);
  EXPECT_TRUE(is_png(file("c.png")));
}

// A BCC volume of 2 x 2^3 samples written by hand (the NRRD layout of runtime/nrrd_io.h): far too
// small for any stencil.
TEST_F(AnalysisCli, RenderRefusesAVolumeWithoutTheStencilMargin) {
  std::string text =
      "NRRD0004\ntype: double\ndimension: 4\nspace dimension: 3\nsizes: 2 2 2 2\n"
      "space directions: none (1,0,0) (0,1,0) (0,0,1)\nspace origin: (0,0,0)\nendian: little\n"
      "encoding: raw\nlattice:=bcc\n\n";
  const std::vector<double> ones(16, 1.0);
  text.append(reinterpret_cast<const char*>(ones.data()), ones.size() * sizeof(double));
  {
    std::ofstream out(file("tiny.nrrd"), std::ios::binary);
    out << text;
  }
  const ProcessResult r = boxrecon({"render", "--volume", file("tiny.nrrd"), "--prefilter", "none",
                                    "--boundary", "strict", "-o", file("r.png")});
  EXPECT_TRUE(r.exited) << describe({"render"}, r);
  EXPECT_EQ(r.exit_code, 1) << describe({"render"}, r);
  EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
  EXPECT_EQ(listing(), (std::vector<std::string>{"tiny.nrrd"}));
}

struct BadAnalysisInput {
  const char* name;
  std::vector<std::string> args;  // "@/" stands for the scratch directory
  int exit_code;
  const char* mentions;
};
void PrintTo(const BadAnalysisInput& c, std::ostream* os) { *os << c.name; }

class AnalysisBadInput : public AnalysisCli,
                         public ::testing::WithParamInterface<BadAnalysisInput> {};

TEST_P(AnalysisBadInput, OneLineOnStderrNonZeroExitNoFile) {
  const auto& c = GetParam();
  std::vector<std::string> args = c.args;
  for (auto& a : args)
    if (a.starts_with("@/")) a = file(a.substr(2));
  const bool recon = args.front() == "boxrecon";
  if (recon) args.erase(args.begin());
  const ProcessResult r = recon ? boxrecon(args) : boxgen(args);
  const std::string what = describe(args, r);
  ASSERT_TRUE(r.exited) << what;
  EXPECT_EQ(r.exit_code, c.exit_code) << what;
  EXPECT_EQ(r.out, "") << what;
  EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << what;
  std::string lower = r.err;
  std::transform(lower.begin(), lower.end(), lower.begin(),
                 [](unsigned char ch) { return static_cast<char>(std::tolower(ch)); });
  EXPECT_NE(lower.find(c.mentions), std::string::npos) << what;
  EXPECT_TRUE(listing().empty()) << "a file was left behind\n" << what;
}

INSTANTIATE_TEST_SUITE_P(
    Boxgen, AnalysisBadInput,
    ::testing::Values(
        BadAnalysisInput{
            "UnknownPrefilter", {"kernel", "m7", "--prefilter", "q3", "--w", "1"}, 1, "prefilter"},
        BadAnalysisInput{"ExactInterpWhereTheSymbolVanishes",
                         {"kernel", "m7", "--prefilter", "interp:0", "--w", "1"},
                         1,
                         "vanishes"},
        BadAnalysisInput{"InterpLambdaNotANumber",
                         {"kernel", "m8", "--prefilter", "interp:1e-3x", "--w", "1"},
                         1,
                         "interp:"},
        BadAnalysisInput{"InterpLambdaNotFinite",
                         {"kernel", "m7", "--prefilter", "interp:inf", "--w", "1"},
                         1,
                         "finite"},
        BadAnalysisInput{"InterpLambdaAboveOne",
                         {"kernel", "m7", "--prefilter", "interp:2", "--w", "1"},
                         1,
                         "[0, 1]"},
        BadAnalysisInput{
            "QfirOutOfRange", {"kernel", "m7", "--prefilter", "qfir:9", "--w", "1"}, 1, "qfir"},
        BadAnalysisInput{
            "UnknownOptimisedPrefilter", {"prefilter", "m7", "--prefilter", "q3opt"}, 1, "q1opt"},
        BadAnalysisInput{
            "ZeroDirection", {"kernel", "m7", "--direction", "0,0,0", "--w", "1"}, 1, "zero"},
        BadAnalysisInput{
            "ShortDirection", {"kernel", "m7", "--direction", "1,1", "--w", "1"}, 1, "direction"},
        BadAnalysisInput{"InvertedRange",
                         {"kernel", "m7", "--from", "2", "--to", "1", "--steps", "5"},
                         1,
                         "range"},
        BadAnalysisInput{
            "EmptyRange",
            {"spectrum", "m7", "--line", "1,0,0", "--from", "1", "--to", "1", "--steps", "5"},
            1,
            "range"},
        BadAnalysisInput{"NoAbscissae", {"kernel", "m7"}, 1, "--w"},
        BadAnalysisInput{
            "ZeroPlaneNormal", {"spectrum", "m7", "--plane", "0,0,0", "-o", "@/p.png"}, 1, "zero"},
        BadAnalysisInput{"PlaneAndLine",
                         {"spectrum", "m7", "--plane", "1,0,0", "--line", "1,0,0", "-o", "@/p.png"},
                         1,
                         "exactly one"},
        BadAnalysisInput{
            "UnwritablePlot", {"kernel", "m7", "--plot", "@/missing/k.png"}, 1, "cannot write"},
        BadAnalysisInput{"UnwritablePlane",
                         {"spectrum", "m7", "--plane", "1,1,1", "-o", "@/missing/p.png"},
                         1,
                         "cannot write"},
        BadAnalysisInput{"BadSpec", {"metrics", "m7", "m99"}, 1, "m99"},
        BadAnalysisInput{"BadLatticeOfOneSpec", {"metrics", "m7", "m8@hex"}, 1, "'m8@hex'"},
        BadAnalysisInput{
            "NoLatticeAfterAt", {"kernel", "m7", "m8@", "--w", "1"}, 1, "'m8@': no lattice"},
        BadAnalysisInput{"DirectionNotOnItsLattice",
                         {"spectrum", "m7@fcc", "--line", "1,0,0", "--json"},
                         1,
                         "'m7@fcc'"},
        BadAnalysisInput{"LabelCount", {"metrics", "m7", "m8", "--label", "a"}, 1, "--label"},
        BadAnalysisInput{"SameKeyTwice", {"metrics", "m7", "m7"}, 1, "--label"},
        BadAnalysisInput{"RenderUnknownShading",
                         {"boxrecon", "render", "--function", "ml", "--n", "9", "--shading",
                          "phong", "-o", "@/r.png"},
                         1,
                         "shading"},
        BadAnalysisInput{
            "RenderUnwritable",
            {"boxrecon", "render", "--function", "ml", "--n", "9", "-o", "@/missing/r.png"},
            1,
            "cannot write"},
        BadAnalysisInput{"RenderUnknownPrefilter",
                         {"boxrecon", "render", "--function", "ml", "--n", "9", "--prefilter", "q7",
                          "-o", "@/r.png"},
                         1,
                         "prefilter"},
        BadAnalysisInput{
            "RenderNoSource", {"boxrecon", "render", "-o", "@/r.png"}, 1, "--function"},
        BadAnalysisInput{
            "RenderBadSize",
            {"boxrecon", "render", "--function", "ml", "--n", "9", "--width", "0", "-o", "@/r.png"},
            1,
            "width"},
        BadAnalysisInput{
            "ErrorWithoutTableOrN", {"boxrecon", "error", "--filter", "m7"}, 2, "--table"},
        BadAnalysisInput{
            "LogPlotFromZero",
            {"kernel", "m7", "--plot", "@/k.png", "--from", "0", "--to", "1", "--steps", "5"},
            1,
            "positive"}),
    [](const ::testing::TestParamInfo<BadAnalysisInput>& p) { return std::string(p.param.name); });

}  // namespace
}  // namespace boxgen::test
