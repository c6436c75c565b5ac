// boxrecon as a user's script sees it: `sample` then `eval` / `error` / `resample` round trips
// checked against the analytic test function, and every kind of bad input giving one line on
// stderr, the documented exit code (1 bad input, 2 usage), nothing on stdout and no output file.
//
// Expected values come from the documented formula of the `cubic` test function
// (runtime/test_functions.h: x^3 - 2xyz + 3y^2 - z + 1), written out again here. Quasi-
// interpolation with Q^I reproduces cubics, so eval must return it up to rounding.
#include <teem/biff.h>
#include <teem/nrrd.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <random>
#include <set>
#include <sstream>
#include <string>
#include <tuple>

#include "cli_support.h"
#include "tests/support/scratch_directory.h"

namespace boxgen::test {
namespace {

namespace fs = std::filesystem;
using Point = std::array<double, 3>;

// The header of a BCC volume written by hand (not by boxrecon): 2 x n^3 doubles, h = 0.5, origin 0.
std::string hand_written_header(int n, bool with_lattice_key, const std::string& encoding = "raw") {
  std::string text = "NRRD0004\ntype: double\ndimension: 4\nspace dimension: 3\n";
  const std::string size = std::to_string(n);
  text += "sizes: 2 " + size + " " + size + " " + size + "\n";
  text +=
      "space directions: none (1,0,0) (0,1,0) (0,0,1)\nspace origin: (0,0,0)\nendian: "
      "little\nencoding: " +
      encoding + "\n";
  if (with_lattice_key) text += "lattice:=bcc\n";
  return text + '\n';
}

// A whole hand-written volume with raw data, all samples 1.
std::string hand_written_bcc(int n, bool with_lattice_key) {
  std::string text = hand_written_header(n, with_lattice_key);
  const std::vector<double> ones(static_cast<std::size_t>(2 * n * n * n), 1.0);
  text.append(reinterpret_cast<const char*>(ones.data()), ones.size() * sizeof(double));
  return text;
}

// Every token of every line is a number printed as %.17g (17 significant digits, C's shortest
// exponent form): formatting the parsed value again gives the same text.
std::vector<std::vector<double>> parse_lines(const std::string& out, std::size_t values_per_line) {
  std::vector<std::vector<double>> lines;
  std::istringstream in(out);
  std::string line;
  while (std::getline(in, line)) {
    std::istringstream fields(line);
    std::vector<double> values;
    std::string token;
    while (fields >> token) {
      char* end = nullptr;
      const double v = std::strtod(token.c_str(), &end);
      EXPECT_EQ(*end, '\0') << "not a number: " << token;
      char again[64];
      std::snprintf(again, sizeof again, "%.17g", v);
      EXPECT_EQ(token, again) << "not printed with 17 significant digits";
      values.push_back(v);
    }
    EXPECT_EQ(values.size(), values_per_line) << line;
    lines.push_back(values);
  }
  EXPECT_TRUE(out.empty() || out.back() == '\n');
  return lines;
}

class BoxreconCli : public test::ScratchDirectoryTest {
 protected:
  BoxreconCli() : ScratchDirectoryTest("boxrecon-cli") {}
  std::string file(const std::string& name) const { return (dir_ / name).string(); }
  std::set<std::string> listing() const {
    std::set<std::string> names;
    for (const auto& entry : fs::directory_iterator(dir_))
      names.insert(entry.path().filename().string());
    return names;
  }
  // Random points of [-1,1]^3, one "x y z" line each, and the points themselves.
  std::vector<Point> write_points(const std::string& name, int count) const {
    std::mt19937_64 rng(17);
    std::uniform_real_distribution<double> u(-1, 1);
    std::vector<Point> points(count);
    std::string text;
    for (auto& p : points) {
      p = {u(rng), u(rng), u(rng)};
      char line[100];
      std::snprintf(line, sizeof line, "%.17g %.17g %.17g\n", p[0], p[1], p[2]);
      text += line;
    }
    write_bytes(file(name), text);
    return points;
  }
};

// `boxrecon filters` lists the registry's filters and the cache's (none in a fresh cache). A SPEC
// filter without a compiler is one line saying what to install, before any work (compiled SPEC
// filters are tested in tests/loader).
TEST_F(BoxreconCli, FiltersListsTheRegistryAndTheCache) {
  const std::string cache = file("cache");
  ::setenv("BOXGEN_CACHE_DIR", cache.c_str(), 1);
  const std::string out = boxrecon_ok({"filters"});
  for (const char* line :
       {"  m7         bcc\n", "  m8         bcc\n", "  m12        bcc\n", "  fcc6       fcc\n",
        "  tricubic   cartesian\n", "  cart7      cartesian\n"})
    EXPECT_NE(out.find(line), std::string::npos) << out;
  EXPECT_NE(out.find("compiled filters (cached in " + cache + "): none\n"), std::string::npos)
      << out;
  ::setenv("BOXGEN_CXX", file("no-compiler").c_str(), 1);
  const std::vector<std::string> args{"eval",
                                      "--filter",
                                      "1,1,1; 1,-1,-1; -1,1,-1; -1,-1,1; 2,0,0",
                                      "--lattice",
                                      "bcc",
                                      "--volume",
                                      file("none.nrrd"),
                                      "--points",
                                      "-"};
  const ProcessResult r = boxrecon(args);
  ::unsetenv("BOXGEN_CXX");
  ::unsetenv("BOXGEN_CACHE_DIR");
  EXPECT_TRUE(r.exited && r.exit_code == 1) << describe(args, r);
  EXPECT_NE(r.err.find("install g++"), std::string::npos) << describe(args, r);
  EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << describe(args, r);
  EXPECT_FALSE(fs::exists(cache) && !fs::is_empty(cache));
}

TEST_F(BoxreconCli, SampleThenEvalReproducesTheCubic) {
  EXPECT_EQ(boxrecon_ok({"sample", "--function", "cubic", "--n", "9", "-o", file("vol.nrrd")}), "");
  const auto points = write_points("points.txt", 40);
  for (const char* filter : {"m7", "m8", "m12"}) {
    SCOPED_TRACE(filter);
    const auto values =
        parse_lines(boxrecon_ok({"eval", "--filter", filter, "--prefilter", "q1", "--volume",
                                 file("vol.nrrd"), "--points", file("points.txt")}),
                    1);
    ASSERT_EQ(values.size(), points.size());
    for (std::size_t i = 0; i < points.size(); ++i)
      EXPECT_NEAR(values[i][0], cubic(points[i]), 1e-10) << i;
    // The gradient of a reproduced cubic is reproduced too; the 1/h = 8 of the chain rule scales
    // the rounding, hence 1e-9.
    const auto with_gradient =
        parse_lines(boxrecon_ok({"eval", "--filter", filter, "--prefilter", "q1", "--volume",
                                 file("vol.nrrd"), "--points", file("points.txt"), "--gradient"}),
                    4);
    ASSERT_EQ(with_gradient.size(), points.size());
    for (std::size_t i = 0; i < points.size(); ++i) {
      EXPECT_EQ(with_gradient[i][0], values[i][0]) << i;
      const Point g = cubic_gradient(points[i]);
      for (int d = 0; d < 3; ++d) EXPECT_NEAR(with_gradient[i][1 + d], g[d], 1e-9) << i << " " << d;
    }
  }
}

TEST_F(BoxreconCli, FloatPrecisionEvaluatesInFloat) {
  // float samples and float arithmetic: |cubic| <= 8 on [-1,1]^3, float epsilon 6e-8, a few dozen
  // weighted terms: 1e-4 is ample, and still far below the error of a wrong reconstruction.
  EXPECT_EQ(boxrecon_ok({"sample", "--function", "cubic", "--n", "9", "--precision", "float", "-o",
                         file("vol.nrrd")}),
            "");
  const auto points = write_points("points.txt", 20);
  const auto values = parse_lines(
      boxrecon_ok({"eval", "--filter", "m8", "--prefilter", "q1", "--volume", file("vol.nrrd"),
                   "--points", file("points.txt"), "--precision", "float"}),
      1);
  ASSERT_EQ(values.size(), points.size());
  for (std::size_t i = 0; i < points.size(); ++i) {
    EXPECT_NEAR(values[i][0], cubic(points[i]), 1e-4) << i;
    EXPECT_EQ(values[i][0], static_cast<double>(static_cast<float>(values[i][0])))
        << "a float result printed as double";
  }
}

TEST_F(BoxreconCli, ErrorJsonHasTheDocumentedKeys) {
  auto j =
      nlohmann::json::parse(boxrecon_ok({"error", "--function", "cubic", "--n", "9", "--filter",
                                         "m7", "--prefilter", "q1", "--points", "200", "--json"}));
  ASSERT_TRUE(j.contains("rms") && j.contains("max")) << j.dump();
  EXPECT_FALSE(j.contains("gradient_rms")) << j.dump();
  EXPECT_EQ(j["filter"], "m7");
  EXPECT_EQ(j["lattice"], "bcc");
  EXPECT_LE(j["rms"].get<double>(), 1e-11);  // the cubic is reproduced
  EXPECT_LE(j["rms"].get<double>(), j["max"].get<double>());
  j = nlohmann::json::parse(
      boxrecon_ok({"error", "--function", "ml", "--n", "9", "--filter", "m8", "--prefilter", "none",
                   "--points", "200", "--gradient", "--json"}));
  ASSERT_TRUE(j.contains("rms") && j.contains("max") && j.contains("gradient_rms")) << j.dump();
  EXPECT_GT(j["rms"].get<double>(), 1e-3);  // Marschner-Lobb at N = 9 is badly under-sampled
  EXPECT_GT(j["gradient_rms"].get<double>(), 0);
  j = nlohmann::json::parse(boxrecon_ok({"error", "--function", "cubic", "--n", "9", "--filter",
                                         "fcc6", "--points", "50", "--json"}));
  EXPECT_EQ(j["lattice"], "fcc");
}

// Teem's view of a resampled grid; the values are returned as doubles.
std::vector<double> load_grid(const std::string& path, int type, std::array<std::size_t, 3> sizes,
                              Point spacing, Point origin) {
  Nrrd* nrrd = nrrdNew();
  std::vector<double> values;
  if (nrrdLoad(nrrd, path.c_str(), nullptr) != 0) {
    char* e = biffGetDone(NRRD);
    ADD_FAILURE() << "Teem cannot load " << path << ": " << e;
    std::free(e);
    nrrdNuke(nrrd);
    return values;
  }
  EXPECT_EQ(nrrd->dim, 3u);
  EXPECT_EQ(nrrd->type, type);
  EXPECT_EQ(nrrd->spaceDim, 3u);
  for (int a = 0; a < 3; ++a) {
    EXPECT_EQ(nrrd->axis[a].size, sizes[a]);
    for (int b = 0; b < 3; ++b)
      EXPECT_DOUBLE_EQ(nrrd->axis[a].spaceDirection[b], a == b ? spacing[a] : 0.0);
    EXPECT_DOUBLE_EQ(nrrd->spaceOrigin[a], origin[a]);
  }
  if (nrrd->dim == 3 && nrrd->data) {
    const std::size_t count = nrrd->axis[0].size * nrrd->axis[1].size * nrrd->axis[2].size;
    for (std::size_t i = 0; i < count; ++i)
      values.push_back(nrrd->type == nrrdTypeFloat ? static_cast<const float*>(nrrd->data)[i]
                                                   : static_cast<const double*>(nrrd->data)[i]);
  }
  nrrdNuke(nrrd);
  return values;
}

TEST_F(BoxreconCli, ResampleWritesAPlain3dNrrdOfTheReconstruction) {
  EXPECT_EQ(boxrecon_ok({"sample", "--function", "cubic", "--n", "9", "-o", file("vol.nrrd")}), "");
  EXPECT_EQ(boxrecon_ok({"resample", "--filter", "m7", "--prefilter", "q1", "--volume",
                         file("vol.nrrd"), "-o", file("grid.nrrd"), "--n", "5", "--min", "-1", "-1",
                         "-1", "--max", "1", "1", "1"}),
            "");
  const auto values =
      load_grid(file("grid.nrrd"), nrrdTypeDouble, {5, 5, 5}, {0.5, 0.5, 0.5}, {-1, -1, -1});
  ASSERT_EQ(values.size(), 125u);
  for (int k = 0; k < 5; ++k)
    for (int j = 0; j < 5; ++j)
      for (int i = 0; i < 5; ++i)
        EXPECT_NEAR(values[static_cast<std::size_t>(i + 5 * (j + 5 * k))],
                    cubic({-1 + 0.5 * i, -1 + 0.5 * j, -1 + 0.5 * k}), 1e-10)
            << i << " " << j << " " << k;

  // The same box spelt --box LO HI: one number per corner, or x,y,z; the same file byte for byte.
  const auto bytes = [&](const std::string& name) {
    std::ifstream in(file(name), std::ios::binary);
    return std::string(std::istreambuf_iterator<char>(in), {});
  };
  for (const auto& [name, lo, hi] :
       {std::tuple<std::string, std::string, std::string>{"cube.nrrd", "-1", "1"},
        {"corners.nrrd", "-1,-1,-1", "1,1,1"}}) {
    EXPECT_EQ(boxrecon_ok({"resample", "--filter", "m7", "--prefilter", "q1", "--volume",
                           file("vol.nrrd"), "-o", file(name), "--n", "5", "--box", lo, hi}),
              "");
    EXPECT_EQ(bytes(name), bytes("grid.nrrd")) << name;
  }
  // A box that is not a cube: 5 points over [-1, 1] x [-0.5, 0.5] x [0, 1].
  EXPECT_EQ(
      boxrecon_ok({"resample", "--filter", "m7", "--prefilter", "q1", "--volume", file("vol.nrrd"),
                   "-o", file("slab.nrrd"), "--n", "5", "--box", "-1,-0.5,0", "1,0.5,1"}),
      "");
  const auto slab =
      load_grid(file("slab.nrrd"), nrrdTypeDouble, {5, 5, 5}, {0.5, 0.25, 0.25}, {-1, -0.5, 0});
  ASSERT_EQ(slab.size(), 125u);
  EXPECT_NEAR(slab[124], cubic({1, 0.5, 1}), 1e-10);
  EXPECT_NEAR(slab[0], cubic({-1, -0.5, 0}), 1e-10);

  // Defaults: the largest box where the stencil fits, which holds the sampled cube [-1,1]^3.
  EXPECT_EQ(boxrecon_ok({"resample", "--filter", "m12", "--volume", file("vol.nrrd"), "-o",
                         file("default.nrrd"), "--n", "4", "--precision", "float"}),
            "");
  Nrrd* nrrd = nrrdNew();
  ASSERT_EQ(nrrdLoad(nrrd, file("default.nrrd").c_str(), nullptr), 0);
  EXPECT_EQ(nrrd->type, nrrdTypeFloat);
  for (int a = 0; a < 3; ++a) {
    EXPECT_EQ(nrrd->axis[a].size, 4u);
    EXPECT_LE(nrrd->spaceOrigin[a], -1);
    EXPECT_GE(nrrd->spaceOrigin[a] + 3 * nrrd->axis[a].spaceDirection[a], 1);
  }
  nrrdNuke(nrrd);
  EXPECT_EQ(listing(), (std::set<std::string>{"vol.nrrd", "grid.nrrd", "cube.nrrd", "corners.nrrd",
                                              "slab.nrrd", "default.nrrd"}));
}

TEST_F(BoxreconCli, AFailedWriteToStdoutIsAnError) {
  EXPECT_EQ(boxrecon_ok({"sample", "--function", "cubic", "--n", "5", "-o", file("vol.nrrd")}), "");
  write_points("points.txt", 3);
  for (const std::vector<std::string>& args :
       {std::vector<std::string>{"eval", "--filter", "m7", "--volume", file("vol.nrrd"), "--points",
                                 file("points.txt")},
        std::vector<std::string>{"error", "--function", "ml", "--n", "5", "--filter", "m7",
                                 "--points", "10", "--json"}}) {
    const ProcessResult r = boxrecon(args, {.stdout_file = "/dev/full", .stdin_file = ""});
    ASSERT_TRUE(r.exited) << describe(args, r);
    EXPECT_EQ(r.exit_code, 1) << describe(args, r);
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << describe(args, r);
    EXPECT_EQ(r.err.rfind("boxrecon: ", 0), 0u) << describe(args, r);
  }
}

// One bad input: "@/" in an argument stands for the test's scratch directory.
struct BadInput {
  const char* name;
  std::vector<std::string> args;
  int exit_code;                      // 1 bad input, 2 usage
  std::vector<std::string> mentions;  // the message names the problem: one of these (any case)
};

void PrintTo(const BadInput& c, std::ostream* os) { *os << c.name; }

std::vector<std::string> eval_with(const std::string& volume, const std::string& points) {
  return {"eval", "--filter", "m7", "--volume", "@/" + volume, "--points", "@/" + points};
}
std::vector<std::string> resample_with(const std::string& volume,
                                       std::vector<std::string> more = {}) {
  std::vector<std::string> args{"resample", "--filter",   "m7",  "--volume", "@/" + volume,
                                "-o",       "@/out.nrrd", "--n", "3"};
  args.insert(args.end(), more.begin(), more.end());
  return args;
}

std::vector<BadInput> bad_inputs() {
  return {
      // volume files
      {"MissingVolumeFile", eval_with("missing.nrrd", "good.txt"), 1, {"no such file"}},
      {"EmptyVolumeFile", eval_with("empty.nrrd", "good.txt"), 1, {"not a nrrd"}},
      {"TruncatedVolume", eval_with("truncated.nrrd", "good.txt"), 1, {"truncated"}},
      {"ThreeDimensionalNrrd", eval_with("grid3d.nrrd", "good.txt"), 1, {"dimension 3"}},
      {"NrrdWithoutLatticeKey", eval_with("nolattice.nrrd", "good.txt"), 1, {"lattice"}},
      {"GarbageText", eval_with("garbage.txt", "good.txt"), 1, {"not a nrrd"}},
      {"VolumeIsADirectory", eval_with("", "good.txt"), 1, {"directory"}},
      {"CorruptGzipVolume", eval_with("corruptgz.nrrd", "good.txt"), 1, {"corruptgz.nrrd"}},
      {"MissingVolumeFileResample", resample_with("missing.nrrd"), 1, {"no such file"}},
      {"TruncatedVolumeResample", resample_with("truncated.nrrd"), 1, {"truncated"}},
      // points files
      {"MissingPointsFile", eval_with("vol.nrrd", "missing.txt"), 1, {"missing.txt"}},
      {"NonNumericPoint", eval_with("vol.nrrd", "nonnumeric.txt"), 1, {"nonnumeric.txt:2"}},
      {"PointWithTwoNumbers", eval_with("vol.nrrd", "two.txt"), 1, {"two.txt:2"}},
      {"PointWithFourNumbers", eval_with("vol.nrrd", "four.txt"), 1, {"four.txt:2"}},
      {"NaNPoint", eval_with("vol.nrrd", "nan.txt"), 1, {"nan.txt:2"}},
      {"InfinitePoint", eval_with("vol.nrrd", "inf.txt"), 1, {"inf.txt:2"}},
      {"PointOutsideTheVolume", eval_with("vol.nrrd", "outside.txt"), 1, {"outside"}},
      // volumes too small for the stencil (a valid hand-written file: see
      // SmallHandWrittenVolumeWorks)
      // under the strict boundary, samples beyond the volume are refused, never invented
      {"VolumeTooSmallForEval",
       [] {
         auto args = eval_with("tiny.nrrd", "tinypoint.txt");
         args.insert(args.end(), {"--boundary", "strict"});
         return args;
       }(),
       1,
       {"outside"}},
      {"VolumeTooSmallForResample",
       resample_with("tiny.nrrd", {"--boundary", "strict"}),
       1,
       {"too small"}},
      {"VolumeTooSmallForThePrefilter",
       resample_with("tiny.nrrd", {"--prefilter", "q2", "--boundary", "strict"}),
       1,
       {"too small", "no sample", "remain"}},
      // interpolation: a volume of one sample per coset along an axis, lambda not in [0, 1] or
      // not a number, lambda 0 where the symbol vanishes (m7), an unknown boundary
      {"VolumeTooSmallForInterp",
       resample_with("flat.nrrd", {"--prefilter", "interp"}),
       1,
       {"too small"}},
      {"InterpLambdaNotFinite",
       resample_with("vol.nrrd", {"--prefilter", "interp:inf"}),
       1,
       {"interp"}},
      {"InterpLambdaNaN", resample_with("vol.nrrd", {"--prefilter", "interp:nan"}), 1, {"interp"}},
      {"InterpLambdaNegative",
       resample_with("vol.nrrd", {"--prefilter", "interp:-1"}),
       1,
       {"interp"}},
      {"InterpLambdaNotANumber",
       resample_with("vol.nrrd", {"--prefilter", "interp:1e-3x"}),
       1,
       {"interp"}},
      {"ExactInterpWhereTheSymbolVanishes",
       resample_with("vol.nrrd", {"--prefilter", "interp:0"}),
       1,
       {"vanishes"}},
      {"UnknownBoundary", resample_with("vol.nrrd", {"--boundary", "wrap"}), 1, {"wrap"}},
      // qfir:K: K not a shell index 0..8, or too few shells for the order
      {"FirShellOutOfRange", resample_with("vol.nrrd", {"--prefilter", "qfir:9"}), 1, {"qfir"}},
      {"FirTooFewShells", resample_with("vol.nrrd", {"--prefilter", "qfir:0"}), 1, {"qfir:0"}},
      // resampling boxes
      {"BoxLeavesTheVolume",
       resample_with("vol.nrrd", {"--min", "-1", "-1", "-1", "--max", "1", "1", "9"}),
       1,
       {"leaves"}},
      {"BoxDegenerate",
       resample_with("vol.nrrd", {"--min", "-1", "0.5", "-1", "--max", "1", "0.5", "1"}),
       1,
       {"degenerate"}},
      {"BoxInverted",
       resample_with("vol.nrrd", {"--min", "1", "1", "1", "--max", "-1", "-1", "-1"}),
       1,
       {"degenerate"}},
      {"BoxNotANumber",
       resample_with("vol.nrrd", {"--min", "-1", "x", "-1", "--max", "1", "1", "1"}),
       2,
       {"--min", "x"}},
      {"BoxMinWithoutMax", resample_with("vol.nrrd", {"--min", "-1", "-1", "-1"}), 2, {"--max"}},
      {"BoxWithTwoCoordinates",
       resample_with("vol.nrrd", {"--min", "-1", "-1", "--max", "1", "1", "1"}),
       2,
       {"--min", "3"}},
      // --box LO HI: each corner one number or x,y,z; not beside --min/--max
      {"BoxCornerWithTwoCoordinates",
       resample_with("vol.nrrd", {"--box", "-1,-1", "1"}),
       2,
       {"--box", "-1,-1"}},
      {"BoxCornerWithATrailingComma",
       resample_with("vol.nrrd", {"--box", "-1,-1,-1,", "1"}),
       2,
       {"--box"}},
      {"BoxCornerNotANumber", resample_with("vol.nrrd", {"--box", "-1", "x"}), 2, {"--box", "x"}},
      {"BoxCornerNotFinite", resample_with("vol.nrrd", {"--box", "-1", "inf"}), 2, {"--box"}},
      {"BoxWithOneCorner", resample_with("vol.nrrd", {"--box", "-1"}), 2, {"--box"}},
      {"BoxBesideMinMax",
       resample_with("vol.nrrd",
                     {"--box", "-1", "1", "--min", "-1", "-1", "-1", "--max", "1", "1", "1"}),
       2,
       {"--box"}},
      {"BoxSpeltLeavesTheVolume", resample_with("vol.nrrd", {"--box", "-1", "9"}), 1, {"leaves"}},
      {"BoxSpeltInverted", resample_with("vol.nrrd", {"--box", "1", "-1"}), 1, {"degenerate"}},
      // names
      {"UnknownFilter",
       {"eval", "--filter", "m9", "--volume", "@/vol.nrrd", "--points", "@/good.txt"},
       1,
       {"m9"}},
      {"UnknownPrefilter",
       {"eval", "--filter", "m7", "--prefilter", "q3", "--volume", "@/vol.nrrd", "--points",
        "@/good.txt"},
       1,
       {"q3"}},
      {"UnknownFilterResample",
       {"resample", "--filter", "m9", "--volume", "@/vol.nrrd", "-o", "@/out.nrrd"},
       1,
       {"m9"}},
      {"UnknownFunction",
       {"sample", "--function", "foo", "--n", "5", "-o", "@/out.nrrd"},
       1,
       {"foo"}},
      {"UnknownFunctionError",
       {"error", "--function", "foo", "--n", "5", "--filter", "m7"},
       1,
       {"foo"}},
      {"UnknownPrecision", resample_with("vol.nrrd", {"--precision", "half"}), 1, {"half"}},
      // --n
      {"SampleNTooSmall", {"sample", "--n", "1", "-o", "@/out.nrrd"}, 1, {"--n"}},
      {"SampleNTooLarge", {"sample", "--n", "5000", "-o", "@/out.nrrd"}, 1, {"--n"}},
      {"ErrorNZero", {"error", "--n", "0", "--filter", "m7"}, 1, {"--n"}},
      {"ResampleNTooSmall",
       {"resample", "--filter", "m7", "--volume", "@/vol.nrrd", "-o", "@/out.nrrd", "--n", "1"},
       1,
       {"--n"}},
      {"ResampleNTooLarge",
       {"resample", "--filter", "m7", "--volume", "@/vol.nrrd", "-o", "@/out.nrrd", "--n", "70000"},
       1,
       {"--n"}},
      // 2500^3 points of 8 + 8 bytes: 233 GiB, beyond half of any machine this runs on.
      {"ResampleGridBeyondMemory",
       {"resample", "--filter", "m7", "--volume", "@/vol.nrrd", "-o", "@/out.nrrd", "--n", "2500"},
       1,
       {"2500 x 2500 x 2500", "232.8 GiB"}},
      {"ResampleLikeALatticeVolumeOntoCartesian",
       {"resample", "--filter", "m7", "--volume", "@/vol.nrrd", "-o", "@/out.nrrd", "--like",
        "@/vol.nrrd", "--lattice", "cartesian"},
       1,
       {"--like", "differs from the lattice"}},
      {"ResampleSpacingWiderThanTheBox",
       {"resample", "--filter", "m7", "--volume", "@/vol.nrrd", "-o", "@/out.nrrd", "--spacing",
        "50"},
       1,
       {"--spacing 50", "no two points fit"}},
      {"ResampleNWithSize", resample_with("vol.nrrd", {"--size", "3", "3", "3"}), 2, {"--size"}},
      {"NNotANumber", {"sample", "--n", "many", "-o", "@/out.nrrd"}, 2, {"--n", "many"}},
      // output files
      {"SampleIntoMissingDirectory",
       {"sample", "--n", "5", "-o", "@/nodir/out.nrrd"},
       1,
       {"nodir", "does not exist"}},
      {"ResampleIntoMissingDirectory",
       {"resample", "--filter", "m7", "--volume", "@/vol.nrrd", "-o", "@/nodir/out.nrrd"},
       1,
       {"nodir", "does not exist"}},
      // usage
      {"NoSubcommand", {}, 2, {"subcommand"}},
      {"UnknownSubcommand", {"frobnicate"}, 2, {"frobnicate", "subcommand"}},
      {"EvalWithoutVolume", {"eval", "--filter", "m7", "--points", "@/good.txt"}, 2, {"--volume"}},
      {"ResampleWithoutOutput",
       {"resample", "--filter", "m7", "--volume", "@/vol.nrrd"},
       2,
       {"--output", "-o"}},
      {"UnknownOption",
       {"eval", "--filter", "m7", "--volume", "@/vol.nrrd", "--points", "@/good.txt", "--frob"},
       2,
       {"--frob"}},
  };
}

class BoxreconBadInput : public BoxreconCli, public ::testing::WithParamInterface<BadInput> {
 protected:
  // The inputs of all cases: a good volume and points, and the bad files.
  void make_inputs() {
    ASSERT_EQ(boxrecon_ok({"sample", "--function", "cubic", "--n", "5", "-o", file("vol.nrrd")}),
              "");
    const std::string volume = read_bytes(file("vol.nrrd"));
    const std::size_t data = volume.find("\n\n");
    ASSERT_NE(data, std::string::npos);
    write_bytes(file("truncated.nrrd"),
                volume.substr(0, data + 2 + (volume.size() - data - 2) / 2));
    write_bytes(file("empty.nrrd"), "");
    write_bytes(file("garbage.txt"), "this is not a volume\n\x01\x02\x03 at all\n");
    std::string grid3d =
        "NRRD0004\ntype: double\ndimension: 3\nsizes: 2 2 2\nendian: little\nencoding: raw\n\n";
    grid3d.append(64, '\0');
    write_bytes(file("grid3d.nrrd"), grid3d);
    write_bytes(file("nolattice.nrrd"), hand_written_bcc(3, false));
    // A gzip member header, then bytes that are no deflate stream.
    write_bytes(file("corruptgz.nrrd"), hand_written_header(3, true, "gzip") +
                                            std::string("\x1f\x8b\x08\0\0\0\0\0\0\x03", 10) +
                                            std::string(64, '\xff'));
    write_bytes(file("tiny.nrrd"), hand_written_bcc(2, true));
    write_bytes(file("flat.nrrd"), hand_written_bcc(1, true));
    write_bytes(file("good.txt"), "0 0 0\n0.5 -0.25 0.125\n");
    write_bytes(file("tinypoint.txt"), "1 1 1\n");
    write_bytes(file("nonnumeric.txt"), "0 0 0\n0 x 0\n");
    write_bytes(file("two.txt"), "0 0 0\n0.5 0.5\n");
    write_bytes(file("four.txt"), "0 0 0\n0.5 0.5 0.5 0.5\n");
    write_bytes(file("nan.txt"), "0 0 0\nnan 0 0\n");
    write_bytes(file("inf.txt"), "0 0 0\n0 inf 0\n");
    write_bytes(file("outside.txt"), "0 0 0\n5 0 0\n");
  }
};

TEST_P(BoxreconBadInput, OneLineOnStderrExitCodeNothingOnStdoutNoFile) {
  make_inputs();
  const BadInput& c = GetParam();
  std::vector<std::string> args = c.args;
  for (auto& a : args)
    if (a.starts_with("@/")) a = file(a.substr(2));
  const auto before = listing();
  const ProcessResult r = boxrecon(args);
  const std::string what = describe(args, r);
  ASSERT_TRUE(r.started) << what;
  ASSERT_FALSE(r.timed_out) << "a bad input must not hang\n" << what;
  ASSERT_TRUE(r.exited) << "a bad input must not crash\n" << what;
  EXPECT_EQ(r.exit_code, c.exit_code) << what;
  EXPECT_EQ(r.out, "") << "nothing may be written to stdout on an error\n" << what;
  ASSERT_FALSE(r.err.empty()) << what;
  EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << what;
  EXPECT_EQ(r.err.back(), '\n') << what;
  EXPECT_EQ(r.err.rfind("boxrecon: ", 0), 0u) << what;
  const std::string message = lower(r.err);
  EXPECT_TRUE(std::any_of(
      c.mentions.begin(), c.mentions.end(),
      [&](const std::string& m) { return message.find(lower(m)) != std::string::npos; }))
      << "the message does not name the problem (expected one of "
      << ::testing::PrintToString(c.mentions) << ")\n"
      << what;
  EXPECT_EQ(listing(), before) << "an output file (or a temporary) was left behind\n" << what;
}

INSTANTIATE_TEST_SUITE_P(Boxrecon, BoxreconBadInput, ::testing::ValuesIn(bad_inputs()),
                         [](const ::testing::TestParamInfo<BadInput>& param_info) {
                           return std::string(param_info.param.name);
                         });

// The hand-written volume format of the "too small" cases is valid: a larger volume in the same
// form evaluates (all samples 1: a partition of unity reconstructs 1).
TEST_F(BoxreconCli, SmallHandWrittenVolumeWorks) {
  write_bytes(file("small.nrrd"), hand_written_bcc(8, true));
  write_bytes(file("centre.txt"), "4 4 4\n");
  const auto values = parse_lines(boxrecon_ok({"eval", "--filter", "m7", "--volume",
                                               file("small.nrrd"), "--points", file("centre.txt")}),
                                  1);
  ASSERT_EQ(values.size(), 1u);
  EXPECT_NEAR(values[0][0], 1.0, 1e-14);
}

// boxrecon bench --quick --json: one JSON object with every ratio it names (each a measured,
// positive, finite number) and the machine; --threads takes a positive count.
TEST(BoxreconBench, QuickJsonHasEveryRatioAndTheMachine) {
  const std::string out = boxrecon_ok(
      {"--threads", "2", "bench", "--quick", "--json", "--points", "20000", "--repeats", "1"});
  const auto j = nlohmann::json::parse(out);
  for (const char* key : {"t7_over_t8", "t12_over_t8", "m7_over_floor", "m8_over_floor",
                          "m12_over_floor", "speedup_2_threads", "m7_over_tricubic"}) {
    ASSERT_TRUE(j.contains(key) && j[key].is_number()) << key;
    EXPECT_TRUE(std::isfinite(j[key].get<double>()) && j[key].get<double>() > 0) << key;
  }
  EXPECT_FALSE(j["machine"]["cpu"].get<std::string>().empty());
  EXPECT_GE(j["machine"]["cores"].get<int>(), 1);
  EXPECT_TRUE(j["machine"].contains("simd_target"));
  const ProcessResult bad = boxrecon({"--threads", "0", "bench", "--quick"});
  EXPECT_EQ(bad.exit_code, 2) << describe({"--threads", "0"}, bad);
}

}  // namespace
}  // namespace boxgen::test
