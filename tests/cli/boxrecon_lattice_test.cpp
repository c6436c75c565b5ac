// boxrecon with the registry's filters that live off BCC (fcc6 on FCC, tricubic and cart7 on the
// Cartesian lattice): every command runs with each on its own lattice, and a filter given a volume
// of another lattice is one line on stderr, exit code 1, nothing on stdout and no output file.
//
// Oracles: the `cubic` test function (x^3 - 2xyz + 3y^2 - z + 1, runtime/test_functions.h,
// written out again here) is reproduced by Q^I with the order-4 filters (tricubic, cart7); fcc6
// has approximation order 3, so its error falls by 2^3 when the spacing halves.
#include <teem/nrrd.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include "cli_support.h"
#include "tests/support/scratch_directory.h"

namespace boxgen::test {
namespace {

namespace fs = std::filesystem;
using Point = std::array<double, 3>;

// The filters of the registry off BCC, with their lattices and approximation orders.
struct OffBccFilter {
  const char* name;
  const char* lattice;
  int order;
};
constexpr OffBccFilter kFilters[] = {
    {"fcc6", "fcc", 3}, {"tricubic", "cartesian", 4}, {"cart7", "cartesian", 4}};

std::vector<std::vector<double>> numbers_per_line(const std::string& out) {
  std::vector<std::vector<double>> lines;
  std::istringstream in(out);
  std::string line;
  while (std::getline(in, line)) {
    std::istringstream fields(line);
    std::vector<double> values;
    double v = 0;
    while (fields >> v) values.push_back(v);
    lines.push_back(values);
  }
  return lines;
}

class BoxreconLattices : public test::ScratchDirectoryTest {
 protected:
  BoxreconLattices() : ScratchDirectoryTest("boxrecon-lattices") {}
  std::string file(const std::string& name) const { return (dir_ / name).string(); }
  std::vector<Point> write_points(const std::string& name, int count) const {
    std::mt19937_64 rng(23);
    std::uniform_real_distribution<double> u(-1, 1);
    std::vector<Point> points(count);
    std::string text;
    for (auto& p : points) {
      p = {u(rng), u(rng), u(rng)};
      char line[100];
      std::snprintf(line, sizeof line, "%.17g %.17g %.17g\n", p[0], p[1], p[2]);
      text += line;
    }
    std::ofstream(file(name)) << text;
    return points;
  }
  // A refused command: exit 1, exactly `message` as the one line on stderr, nothing on stdout.
  void refused(const std::vector<std::string>& args, const std::string& message) {
    const ProcessResult r = boxrecon(args);
    const std::string what = describe(args, r);
    ASSERT_TRUE(r.exited) << what;
    EXPECT_EQ(r.exit_code, 1) << what;
    EXPECT_EQ(r.out, "") << what;
    EXPECT_EQ(r.err, "boxrecon: error: " + message + "\n") << what;
  }
};

TEST_F(BoxreconLattices, SampleWithAFilterUsesItsLattice) {
  for (const auto& f : kFilters) {
    SCOPED_TRACE(f.name);
    boxrecon_ok(
        {"sample", "--function", "cubic", "--n", "5", "--filter", f.name, "-o", file("v.nrrd")});
    const std::string text = read_bytes(file("v.nrrd"));
    EXPECT_NE(text.find(std::string("lattice:=") + f.lattice + "\n"), std::string::npos);
    // The same file as with --lattice: a filter only chooses the lattice.
    boxrecon_ok({"sample", "--function", "cubic", "--n", "5", "--lattice", f.lattice, "-o",
                 file("w.nrrd")});
    EXPECT_EQ(read_bytes(file("w.nrrd")), text);
  }
}

TEST_F(BoxreconLattices, EvalErrorAndResampleWorkWithEachFilterOnItsLattice) {
  const auto points = write_points("points.txt", 30);
  for (const auto& f : kFilters) {
    SCOPED_TRACE(f.name);
    boxrecon_ok(
        {"sample", "--function", "cubic", "--n", "9", "--filter", f.name, "-o", file("v.nrrd")});
    const auto lines = numbers_per_line(
        boxrecon_ok({"eval", "--filter", f.name, "--prefilter", "q1", "--volume", file("v.nrrd"),
                     "--points", file("points.txt"), "--gradient", "--hessian"}));
    ASSERT_EQ(lines.size(), points.size());
    for (std::size_t i = 0; i < points.size(); ++i) {
      ASSERT_EQ(lines[i].size(), 10u) << "value, gradient, Hessian";
      if (f.order < 4) continue;  // exactness below; fcc6's convergence in the next test
      EXPECT_NEAR(lines[i][0], cubic(points[i]), 1e-10) << i;
      const Point g = cubic_gradient(points[i]);
      for (int d = 0; d < 3; ++d) EXPECT_NEAR(lines[i][1 + d], g[d], 1e-9) << i;
      EXPECT_NEAR(lines[i][4], 6 * points[i][0], 1e-7) << "h_xx";
      EXPECT_NEAR(lines[i][5], -2 * points[i][2], 1e-7) << "h_xy";
    }
    for (const char* q : {"q1", "q2"}) {
      const auto j = nlohmann::json::parse(
          boxrecon_ok({"error", "--function", "cubic", "--n", "9", "--filter", f.name,
                       "--prefilter", q, "--points", "300", "--json"}));
      EXPECT_EQ(j["filter"], f.name);
      EXPECT_EQ(j["prefilter"], q);
      if (f.order == 4) {
        EXPECT_LE(j["rms"].get<double>(), 1e-11) << q;
      }
    }
    boxrecon_ok({"resample", "--filter", f.name, "--prefilter", "q1", "--volume", file("v.nrrd"),
                 "-o", file("grid.nrrd"), "--n", "3", "--min", "-1", "-1", "-1", "--max", "1", "1",
                 "1"});
    Nrrd* nrrd = nrrdNew();
    ASSERT_EQ(nrrdLoad(nrrd, file("grid.nrrd").c_str(), nullptr), 0);
    ASSERT_EQ(nrrd->dim, 3u);
    ASSERT_EQ(nrrd->type, nrrdTypeDouble);
    const auto* values = static_cast<const double*>(nrrd->data);
    for (int k = 0; k < 3; ++k)
      for (int jj = 0; jj < 3; ++jj)
        for (int i = 0; i < 3; ++i) {
          const double want = cubic({-1.0 + i, -1.0 + jj, -1.0 + k});
          const double got = values[i + 3 * (jj + 3 * k)];
          EXPECT_NEAR(got, want, f.order == 4 ? 1e-10 : 1e-2) << i << " " << jj << " " << k;
        }
    nrrdNuke(nrrd);
  }
}

TEST_F(BoxreconLattices, Fcc6ConvergesAtItsApproximationOrder) {
  double rms[2] = {};
  int i = 0;
  for (const char* n : {"9", "17"}) {  // spacing halves
    const auto j = nlohmann::json::parse(
        boxrecon_ok({"error", "--function", "cubic", "--n", n, "--filter", "fcc6", "--prefilter",
                     "q1", "--points", "2000", "--json"}));
    rms[i++] = j["rms"].get<double>();
  }
  EXPECT_GT(rms[0] / rms[1], 6.0);  // 2^3 = 8 for order 3
  EXPECT_LT(rms[0] / rms[1], 11.0);
}

TEST_F(BoxreconLattices, RenderAndBenchRunWithEachFilter) {
  for (const auto& f : kFilters) {
    SCOPED_TRACE(f.name);
    boxrecon_ok({"render", "--function", "ml", "--n", "9", "--filter", f.name, "--width", "12",
                 "--height", "10", "--quiet", "-o", file("f.png")});
    boxrecon_ok(
        {"sample", "--function", "sphere", "--n", "7", "--filter", f.name, "-o", file("s.nrrd")});
    boxrecon_ok({"render", "--volume", file("s.nrrd"), "--filter", f.name, "--iso", "0.6",
                 "--shading", "curvature", "--width", "12", "--height", "10", "--quiet", "-o",
                 file("v.png")});
    for (const char* png : {"f.png", "v.png"}) EXPECT_EQ(read_bytes(file(png)).substr(1, 3), "PNG");
    const auto j = nlohmann::json::parse(
        boxrecon_ok({"bench", "--filter", f.name, "--points", "500", "--repeats", "1", "--json"}));
    EXPECT_EQ(j["filter"], f.name);
    EXPECT_EQ(j["lattice"], f.lattice);
    ASSERT_FALSE(j["timings"].empty());
    for (const auto& t : j["timings"]) {
      EXPECT_GT(t["value_ns_per_point"].get<double>(), 0);
      EXPECT_GT(t["gradient_ns_per_point"].get<double>(), 0);
    }
  }
}

TEST_F(BoxreconLattices, AFilterOnAVolumeOfAnotherLatticeIsOneLine) {
  write_points("p.txt", 2);
  boxrecon_ok({"sample", "--function", "cubic", "--n", "5", "-o", file("bcc.nrrd")});
  boxrecon_ok(
      {"sample", "--function", "cubic", "--n", "5", "--lattice", "fcc", "-o", file("fcc.nrrd")});
  boxrecon_ok({"sample", "--function", "cubic", "--n", "5", "--lattice", "cartesian", "-o",
               file("cart.nrrd")});
  const std::pair<const char*, const char*> volumes[] = {
      {"bcc", "bcc.nrrd"}, {"fcc", "fcc.nrrd"}, {"cartesian", "cart.nrrd"}};
  for (const auto& f : kFilters)
    for (const auto& [lattice, volume] : volumes) {
      if (std::string(lattice) == f.lattice) continue;
      SCOPED_TRACE(std::string(f.name) + " on " + lattice);
      const std::string message = std::string("filter ") + f.name + " is for the " + f.lattice +
                                  " lattice, but the volume is on the " + lattice + " lattice";
      refused({"eval", "--filter", f.name, "--volume", file(volume), "--points", file("p.txt")},
              message);
      refused({"resample", "--filter", f.name, "--volume", file(volume), "-o", file("out.nrrd")},
              message);
      refused({"render", "--filter", f.name, "--volume", file(volume), "--width", "8", "--height",
               "8", "--quiet", "-o", file("out.png")},
              message);
      EXPECT_FALSE(fs::exists(file("out.nrrd")));
      EXPECT_FALSE(fs::exists(file("out.png")));
    }
  refused({"sample", "--function", "cubic", "--n", "5", "--filter", "fcc6", "--lattice", "bcc",
           "-o", file("out.nrrd")},
          "filter fcc6 is for the fcc lattice, but --lattice is bcc");
  EXPECT_FALSE(fs::exists(file("out.nrrd")));
}

// error and render sample on the filter's own lattice: --lattice may name it, in any spelling
// of the same points, and anything else is one line.
TEST_F(BoxreconLattices, ErrorAndRenderTakeOnlyTheFiltersOwnLattice) {
  for (const auto& f : kFilters) {
    SCOPED_TRACE(f.name);
    const std::string same = std::string(f.lattice) == "fcc" ? "0,1,1; 1,0,1; 1,1,0" : "cartesian";
    const auto with = nlohmann::json::parse(
        boxrecon_ok({"error", "--function", "ml", "--n", "9", "--filter", f.name, "--lattice", same,
                     "--points", "200", "--json"}));
    const auto without =
        nlohmann::json::parse(boxrecon_ok({"error", "--function", "ml", "--n", "9", "--filter",
                                           f.name, "--points", "200", "--json"}));
    EXPECT_EQ(with["rms"], without["rms"]);
    const std::string message = std::string("filter ") + f.name + " is for the " + f.lattice +
                                " lattice, but --lattice is bcc";
    refused({"error", "--function", "ml", "--n", "9", "--filter", f.name, "--lattice", "bcc"},
            message);
    refused({"render", "--function", "ml", "--n", "9", "--filter", f.name, "--lattice", "bcc",
             "--width", "8", "--height", "8", "--quiet", "-o", file("out.png")},
            message);
    EXPECT_FALSE(fs::exists(file("out.png")));
  }
}

}  // namespace
}  // namespace boxgen::test
