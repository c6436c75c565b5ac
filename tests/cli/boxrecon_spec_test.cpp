// SPEC filters in the commands that read volumes: eval, compare, subsample and
// slice take a direction list as --filter (never split at its commas), on the volume's lattice
// when --lattice is not given (read from the header before anything is compiled), and refuse a
// --lattice the volume is not on in one line. One SPEC (six of M7's seven directions, no preset)
// is compiled once into the test's own cache; every later command loads it from there.
//
// Expected values come from elsewhere: the exact rational value of `boxgen eval` (the generator's
// recurrence) for a delta volume, and polynomial reproduction for compare and subsample (the SPEC
// has approximation order 3 by `boxgen analyze`: with its prefilter q1 it reproduces quadratics
// exactly, and every centred box spline reproduces linear functions without one).
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <functional>
#include <sstream>
#include <string>
#include <vector>

#include "boxrecon_scratch_test.h"
#include "cli_support.h"
#include "png_file.h"

namespace boxgen::test {
namespace {

namespace fs = std::filesystem;

constexpr const char* kSpec = "1,1,1; 1,-1,-1; -1,1,-1; -1,-1,1; 2,0,0; 0,2,0";

using Function = std::function<double(double, double, double)>;

// A NRRD of doubles written here (not by boxrecon), origin 0: on BCC (`bcc`) the sample
// (c, i, j, k) lies at (2i + c, 2j + c, 2k + c), on the Cartesian lattice (i, j, k) at (i, j, k).
void write_volume(const fs::path& path, bool bcc, int n, const Function& f) {
  std::string text = "NRRD0004\ntype: double\n";
  const std::string s = std::to_string(n);
  if (bcc)
    text += "dimension: 4\nspace dimension: 3\nsizes: 2 " + s + " " + s + " " + s +
            "\nspace directions: none (2,0,0) (0,2,0) (0,0,2)\n";
  else
    text += "dimension: 3\nspace dimension: 3\nsizes: " + s + " " + s + " " + s +
            "\nspace directions: (1,0,0) (0,1,0) (0,0,1)\n";
  text += "space origin: (0,0,0)\nendian: little\nencoding: raw\n";
  text += bcc ? "lattice:=bcc\n\n" : "\n";
  std::vector<double> values;
  for (int k = 0; k < n; ++k)
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i)
        for (int c = 0; c < (bcc ? 2 : 1); ++c) {
          const int m = bcc ? 2 : 1;
          values.push_back(f(m * i + c, m * j + c, m * k + c));
        }
  text.append(reinterpret_cast<const char*>(values.data()), values.size() * sizeof(double));
  std::ofstream(path, std::ios::binary) << text;
}

std::vector<double> numbers(const std::string& text) {
  std::vector<double> out;
  std::istringstream in(text);
  for (double v = 0; in >> v;) out.push_back(v);
  return out;
}

class BoxreconSpec : public BoxreconScratchTest {
 protected:
  BoxreconSpec() : BoxreconScratchTest("boxrecon-spec") {}
  void SetUp() override {
    BoxreconScratchTest::SetUp();
    ::setenv("BOXGEN_CACHE_DIR", (dir_ / "cache").c_str(), 1);
  }
  void TearDown() override {
    ::unsetenv("BOXGEN_CACHE_DIR");
    BoxreconScratchTest::TearDown();
  }
  std::vector<fs::path> objects() const {
    std::vector<fs::path> found;
    for (const auto& e : fs::directory_iterator(dir_ / "cache"))
      if (e.path().extension() == ".so") found.push_back(e.path());
    return found;
  }
  // One line on stderr, exit 1, no file `output` (when given).
  void refused(const std::vector<std::string>& args, const std::string& says,
               const std::string& output = {}) {
    const ProcessResult r = boxrecon(args);
    EXPECT_TRUE(r.exited && r.exit_code == 1) << describe(args, r);
    EXPECT_NE(r.err.find(says), std::string::npos) << describe(args, r);
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << describe(args, r);
    if (!output.empty()) {
      EXPECT_FALSE(fs::exists(output)) << output;
    }
  }
  nlohmann::json compare(const std::string& reference, const std::string& volume,
                         const std::string& prefilter) {
    return nlohmann::json::parse(
        ok({"compare", "--reference", reference, "--volume", volume, "--filter", kSpec,
            "--prefilter", prefilter, "--boundary", "strict", "--json"}));
  }
};

TEST_F(BoxreconSpec, SpecFilterInEveryVolumeCommandOnTheVolumesLattice) {
  // A BCC volume that is 0 but for a 1 at the lattice point (8, 8, 8): its reconstruction is the
  // filter M(x - (8, 8, 8)), whose exact values `boxgen eval` gives.
  write_volume(file("delta.nrrd"), true, 9,
               [](double x, double y, double z) { return x == 8 && y == 8 && z == 8 ? 1.0 : 0.0; });
  const std::vector<std::string> offsets{"13/64 5/64 -21/64", "1/2 -3/4 3/8", "-5/4 1/8 1/16",
                                         "0 0 0", "9/8 7/8 -1/2"};
  std::string points;
  std::vector<double> exact;
  for (const std::string& d : offsets) {
    const nlohmann::json j = boxgen_json({"eval", kSpec, "--lattice", "bcc", "--at", d, "--json"});
    exact.push_back(j.at(0).at("value_float").get<double>());
    std::istringstream in(d);
    for (std::string t; in >> t;) {
      const auto slash = t.find('/');
      const double v = slash == std::string::npos
                           ? std::stod(t)
                           : std::stod(t.substr(0, slash)) / std::stod(t.substr(slash + 1));
      points += std::to_string(8 + v) + ' ';
    }
    points += '\n';
  }
  std::ofstream(file("points.txt")) << points;
  ASSERT_GT(exact[3], 0.1);  // the filter's value at its centre: the test cannot pass on zeros

  // First use, with --lattice: compiled (slowly: a longer limit than boxrecon()'s default).
  const std::vector<std::string> eval_bcc{
      "eval",     "--filter",         kSpec,      "--lattice",        "bcc",
      "--volume", file("delta.nrrd"), "--points", file("points.txt"), "--quiet"};
  const ProcessResult first = boxrecon(eval_bcc, {}, std::chrono::seconds(600 * kSlowdown));
  ASSERT_TRUE(first.exited && first.exit_code == 0) << describe(eval_bcc, first);
  const std::vector<double> values = numbers(first.out);
  ASSERT_EQ(values.size(), exact.size()) << first.out;
  for (std::size_t i = 0; i < exact.size(); ++i)
    EXPECT_NEAR(values[i], exact[i], 1e-13) << offsets[i];
  ASSERT_EQ(objects().size(), 1U);
  const fs::path object = objects()[0];
  const auto compiled_at = fs::last_write_time(object);

  // Without --lattice: BCC from the volume, the same cached object (a Cartesian SPEC would
  // compile a second one), the same values bit for bit.
  EXPECT_EQ(ok({"eval", "--filter", kSpec, "--volume", file("delta.nrrd"), "--points",
                file("points.txt")}),
            first.out);
  EXPECT_EQ(objects().size(), 1U);
  EXPECT_EQ(fs::last_write_time(object), compiled_at);

  // A --lattice the volume is not on: one line, before any derivation or compile.
  refused({"eval", "--filter", kSpec, "--lattice", "fcc", "--volume", file("delta.nrrd"),
           "--points", file("points.txt")},
          "--lattice is fcc, but the volume");
  EXPECT_EQ(objects().size(), 1U);

  // compare: a quadratic on BCC against the same quadratic on a Cartesian grid, the SPEC with its
  // own prefilter q1 (reproduces degree 2): float precision, not a reconstruction error.
  const Function quadratic = [](double x, double y, double z) {
    return 0.3 + 0.02 * x - 0.03 * y + 0.01 * z + 0.002 * x * y - 0.001 * z * z + 0.0015 * x * x;
  };
  write_volume(file("quad_bcc.nrrd"), true, 9, quadratic);
  write_volume(file("quad_cart.nrrd"), false, 17, quadratic);
  const nlohmann::json errors = compare(file("quad_cart.nrrd"), file("quad_bcc.nrrd"), "q1");
  EXPECT_EQ(errors.at("filter"), kSpec);
  EXPECT_GT(errors.at("region").at("points").get<double>(), 100);
  EXPECT_LT(errors.at("region").at("max").get<double>(), 1e-5) << errors.dump();
  // The same without the prefilter: a reconstruction error far larger (6.7e-4 when written), so
  // the bound above says something.
  EXPECT_GT(compare(file("quad_cart.nrrd"), file("quad_bcc.nrrd"), "none")
                .at("region")
                .at("max")
                .get<double>(),
            1e-4);

  // subsample: the BCC quadratic reconstructed with the SPEC (q1) onto a Cartesian grid is the
  // quadratic there, which compare reads as a reference.
  const std::string sub =
      ok({"subsample", "--volume", file("quad_bcc.nrrd"), "--filter", kSpec, "--prefilter", "q1",
          "--lattice", "cartesian", "--fraction", "0.5", "-o", file("sub.nrrd")});
  EXPECT_NE(sub.find("input reconstructed with " + std::string(kSpec) + " after q1"),
            std::string::npos)
      << sub;
  EXPECT_LT(
      compare(file("sub.nrrd"), file("quad_bcc.nrrd"), "q1").at("region").at("max").get<double>(),
      1e-5);

  // slice: the registry's m7 and the SPEC side by side (--filter repeated). Both reproduce a
  // linear function without a prefilter, so the two panels are the same ramp.
  write_volume(file("linear.nrrd"), true, 9,
               [](double x, double y, double z) { return 0.1 + 0.04 * x + 0.01 * y + 0 * z; });
  const std::string said =
      ok({"slice", "--volume", file("linear.nrrd"), "--filter", "m7", "--filter", kSpec,
          "--boundary", "strict", "--at", "8", "--size", "64", "64", "-o", file("slice.png")});
  EXPECT_NE(said.find("2 panel(s)"), std::string::npos) << said;
  const Png png = read_png(file("slice.png"));
  // Panel p's image, each pixel drawn 4 x 4: columns from p (4 * 64 + 200) + 70, rows from 40
  // (analysis/gnuplot.cpp); the centres of the pixels' squares are compared.
  EXPECT_NE(said.find("(drawn 4 x 4 each)"), std::string::npos) << said;
  ASSERT_EQ(png.width, 2 * (4 * 64 + 200));
  ASSERT_EQ(png.height, 4 * 64 + 100);
  const auto at = [&](int panel, int x, int y) {
    return png.at(panel * (4 * 64 + 200) + 70 + 4 * x + 2, 40 + 4 * y + 2);
  };
  int largest = 0;
  for (int y = 0; y < 64; ++y)
    for (int x = 0; x < 64; ++x)
      for (int c = 0; c < 3; ++c)
        largest = std::max(largest, std::abs(at(0, x, y)[c] - at(1, x, y)[c]));
  EXPECT_LE(largest, 1);
  EXPECT_GT(at(0, 63, 20)[0] - at(0, 0, 20)[0], 100);  // a ramp, not a blank panel
  EXPECT_EQ(objects().size(), 1U);  // every command loaded the one compiled object
}

// A comma list of names (the syntax of earlier versions) is one line saying to repeat --filter;
// a direction list with commas is one SPEC (the test above), never split.
TEST_F(BoxreconSpec, CommaListOfFiltersSaysRepeatFilter) {
  write_volume(file("v.nrrd"), true, 5, [](double x, double, double) { return x; });
  refused(
      {"slice", "--volume", file("v.nrrd"), "--filter", "m7,m8", "--at", "4", "-o", file("s.png")},
      "repeat --filter", file("s.png"));
}

}  // namespace
}  // namespace boxgen::test
