// boxrecon's commands for real volumes (subsample, compare, slice) as a user meets them: a
// polynomial subsampled onto BCC is reproduced where the filter's order allows, compare's numbers
// match a case checked by hand, slices have the asked size and values, and every bad input is one
// line, a non-zero exit and no file. The volumes are small (seconds in all).
#include <nifti2_io.h>
#include <teem/nrrd.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <functional>
#include <regex>
#include <sstream>
#include <string>
#include <vector>

#include "boxrecon_scratch_test.h"
#include "cli_support.h"
#include "png_file.h"

namespace boxgen::test {
namespace {

namespace fs = std::filesystem;

// A NRRD read with Teem, as users' tools read it: float samples, sizes, and for each of the last
// three axes its space direction's diagonal entry; the origin.
struct TeemVolume {
  std::vector<float> samples;
  std::vector<std::size_t> sizes;
  std::array<double, 3> step{}, origin{};
};

TeemVolume load(const std::string& path) {
  TeemVolume v;
  Nrrd* nrrd = nrrdNew();
  if (nrrdLoad(nrrd, path.c_str(), nullptr) != 0) {
    ADD_FAILURE() << "Teem cannot read " << path;
    nrrdNuke(nrrd);
    return v;
  }
  Nrrd* floats = nrrdNew();
  EXPECT_EQ(nrrdConvert(floats, nrrd, nrrdTypeFloat), 0);
  std::size_t count = 1;
  for (unsigned a = 0; a < nrrd->dim; ++a) {
    v.sizes.push_back(nrrd->axis[a].size);
    count *= nrrd->axis[a].size;
  }
  const unsigned first = nrrd->dim - 3;
  for (int a = 0; a < 3; ++a) {
    v.step[a] = nrrd->axis[first + a].spaceDirection[a];
    v.origin[a] = nrrd->spaceOrigin[a];
  }
  const float* data = static_cast<const float*>(floats->data);
  v.samples.assign(data, data + count);
  nrrdNuke(floats);
  nrrdNuke(nrrd);
  return v;
}

// A Cartesian NRRD of n^3 float samples f(i, j, k), spacing 1, origin 0, written with Teem.
void save_cartesian(const std::string& path, std::size_t n,
                    const std::function<float(int, int, int)>& f) {
  std::vector<float> values;
  for (std::size_t k = 0; k < n; ++k)
    for (std::size_t j = 0; j < n; ++j)
      for (std::size_t i = 0; i < n; ++i)
        values.push_back(f(static_cast<int>(i), static_cast<int>(j), static_cast<int>(k)));
  Nrrd* nrrd = nrrdNew();
  const std::size_t sizes[3] = {n, n, n};
  ASSERT_EQ(nrrdWrap_nva(nrrd, values.data(), nrrdTypeFloat, 3, sizes), 0);
  ASSERT_EQ(nrrdSpaceSet(nrrd, nrrdSpace3DRightHanded), 0);
  for (int a = 0; a < 3; ++a)
    for (int b = 0; b < 3; ++b) nrrd->axis[a].spaceDirection[b] = a == b ? 1.0 : 0.0;
  double origin[3] = {0, 0, 0};
  ASSERT_EQ(nrrdSpaceOriginSet(nrrd, origin), 0);
  ASSERT_EQ(nrrdSave(path.c_str(), nrrd, nullptr), 0);
  nrrdNix(nrrd);
}

class BoxreconVolumes : public BoxreconScratchTest {
 protected:
  BoxreconVolumes() : BoxreconScratchTest("boxrecon-volumes") {}
  // Refused: a non-zero exit, one line on stderr mentioning `mention`, and `output` not written.
  void refused(const std::vector<std::string>& args, const std::string& mention,
               const std::string& output) {
    const ProcessResult r = boxrecon(args);
    const std::string what = describe(args, r);
    ASSERT_TRUE(r.exited) << what;
    EXPECT_NE(r.exit_code, 0) << what;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << what;
    EXPECT_NE(lower(r.err).find(lower(mention)), std::string::npos) << what;
    if (!output.empty()) {
      EXPECT_FALSE(fs::exists(output)) << what;
    }
  }
};

// boxrecon's `cubic` (degree 3) sampled on a Cartesian grid and subsampled onto BCC with the
// tricubic after Q^II, which reproduces every polynomial of degree < 4: each BCC sample must be
// the cubic at its own position (to float rounding: the volumes are float, values near 1).
TEST_F(BoxreconVolumes, SubsampleReproducesACubicOnBcc) {
  ok({"sample", "--function", "cubic", "--lattice", "cartesian", "--n", "17", "-o",
      file("c.nrrd")});
  // strict: the region where q2 reproduces cubics (a mirror image is no cubic near the faces)
  const std::string out = ok({"subsample", "--volume", file("c.nrrd"), "--lattice", "bcc",
                              "--fraction", "0.1", "--boundary", "strict", "-o", file("b.nrrd")});
  const TeemVolume in = load(file("c.nrrd")), b = load(file("b.nrrd"));
  ASSERT_EQ(b.sizes.size(), 4u);
  ASSERT_EQ(b.sizes[0], 2u);
  const std::size_t kept = 2 * b.sizes[1] * b.sizes[2] * b.sizes[3];
  const std::size_t total = in.samples.size();
  // "kept K of N samples: fraction K/N = ..."
  EXPECT_NE(out.find("kept " + std::to_string(kept) + " of " + std::to_string(total)),
            std::string::npos)
      << out;
  EXPECT_NEAR(static_cast<double>(kept) / static_cast<double>(total), 0.1, 0.05) << out;
  const double h = b.step[0] / 2;  // space direction 2h
  double worst = 0;
  std::size_t s = 0;
  for (std::size_t k = 0; k < b.sizes[3]; ++k)
    for (std::size_t j = 0; j < b.sizes[2]; ++j)
      for (std::size_t i = 0; i < b.sizes[1]; ++i)
        for (std::size_t c = 0; c < 2; ++c, ++s) {
          const std::array<double, 3> p{b.origin[0] + h * static_cast<double>(2 * i + c),
                                        b.origin[1] + h * static_cast<double>(2 * j + c),
                                        b.origin[2] + h * static_cast<double>(2 * k + c)};
          worst = std::max(worst, std::fabs(b.samples[s] - cubic(p)));
        }
  EXPECT_LT(worst, 2e-5);
}

// Reference v(i, j, k) = 10 + (i - 4.5) on a 10^3 grid of spacing 1 (range 9); the volume is
// the constant 10 (the tricubic's B-splines sum to 1: it reconstructs 10 exactly). In the box
// [3, 6]^3: 64 points, errors 4.5 - i for i = 3..6, i.e. 1.5, 0.5, -0.5, -1.5 on 16 points
// each: RMS sqrt(5/4), max 1.5, mean |e| 1, PSNR 20 log10(9 / sqrt(5/4)). Mask v > 10.8: i = 6
// only (v = 11.5): 16 points, all errors -1.5.
TEST_F(BoxreconVolumes, CompareMatchesAHandCheckedCase) {
  save_cartesian(file("ref.nrrd"), 10,
                 [](int i, int, int) { return 10 + (static_cast<float>(i) - 4.5f); });
  save_cartesian(file("ten.nrrd"), 10, [](int, int, int) { return 10.0f; });
  const nlohmann::json j = nlohmann::json::parse(ok({"compare",
                                                     "--reference",
                                                     file("ref.nrrd"),
                                                     "--volume",
                                                     file("ten.nrrd"),
                                                     "--filter",
                                                     "tricubic",
                                                     "--min",
                                                     "3",
                                                     "3",
                                                     "3",
                                                     "--max",
                                                     "6",
                                                     "6",
                                                     "6",
                                                     "--mask-above",
                                                     "10.8",
                                                     "--json",
                                                     "--error-volume",
                                                     file("err.nrrd")}));
  EXPECT_EQ(j["region"]["points"], 64);
  EXPECT_NEAR(j["region"]["rms"].get<double>(), std::sqrt(1.25), 1e-6);
  EXPECT_NEAR(j["region"]["max"].get<double>(), 1.5, 1e-6);
  EXPECT_NEAR(j["region"]["mean_abs"].get<double>(), 1.0, 1e-6);
  EXPECT_NEAR(j["region"]["psnr_db"].get<double>(), 20 * std::log10(9 / std::sqrt(1.25)), 1e-5);
  EXPECT_EQ(j["peak"], 9.0);
  EXPECT_EQ(j["mask"]["points"], 16);
  EXPECT_NEAR(j["mask"]["rms"].get<double>(), 1.5, 1e-6);
  // The error volume: reconstruction minus reference inside the box, 0 outside.
  const TeemVolume e = load(file("err.nrrd"));
  ASSERT_EQ(e.samples.size(), 1000u);
  const auto at = [&](int i, int j2, int k) {
    return e.samples[static_cast<std::size_t>(i) +
                     10 * (static_cast<std::size_t>(j2) + 10 * static_cast<std::size_t>(k))];
  };
  EXPECT_NEAR(at(3, 4, 5), 1.5, 1e-6);
  EXPECT_NEAR(at(6, 3, 6), -1.5, 1e-6);
  EXPECT_EQ(at(2, 4, 4), 0.0f);
  EXPECT_EQ(at(7, 4, 4), 0.0f);
}

// compare's box spelt --box LO HI: one number per corner is the cube (the same 4^3 points as
// --min 3 3 3 --max 6 6 6 above), three comma-separated numbers a box of any shape (z in [3, 4]:
// two of the grid's z layers, 4 x 4 x 2 points).
TEST_F(BoxreconVolumes, CompareTakesTheBoxInEitherSpelling) {
  save_cartesian(file("ref.nrrd"), 10,
                 [](int i, int, int) { return 10 + (static_cast<float>(i) - 4.5f); });
  save_cartesian(file("ten.nrrd"), 10, [](int, int, int) { return 10.0f; });
  const auto region = [&](const std::string& lo, const std::string& hi) {
    return nlohmann::json::parse(
        ok({"compare", "--reference", file("ref.nrrd"), "--volume", file("ten.nrrd"), "--filter",
            "tricubic", "--box", lo, hi, "--json"}))["region"];
  };
  const nlohmann::json cube = region("3", "6");
  EXPECT_EQ(cube["points"], 64);
  EXPECT_NEAR(cube["rms"].get<double>(), std::sqrt(1.25), 1e-6);
  EXPECT_EQ(region("3,3,3", "6,6,6"), cube);
  const nlohmann::json flat = region("3,3,3", "6,6,4");
  EXPECT_EQ(flat["points"], 32);
  EXPECT_NEAR(flat["rms"].get<double>(), std::sqrt(1.25), 1e-6);
  refused({"compare", "--reference", file("ref.nrrd"), "--volume", file("ten.nrrd"), "--filter",
           "tricubic", "--box", "3,3", "6", "--error-volume", file("e.nrrd")},
          "--box", file("e.nrrd"));
  refused({"compare", "--reference", file("ref.nrrd"), "--volume", file("ten.nrrd"), "--filter",
           "tricubic", "--box", "-30", "6", "--error-volume", file("e.nrrd")},
          "leaves the region", file("e.nrrd"));
}

// Where image_png (analysis/gnuplot.cpp) draws panel p of a slice of W x H pixels, each drawn as
// Z x Z (Z = 256 / the longer side, at least 1): columns from p (Z W + 200) + 70, rows from 40;
// the PNG is panels (Z W + 200) by Z H + 100 pixels. The checks look at the centre of each
// pixel's square.
constexpr int kLeft = 70, kTop = 40, kMarginX = 200, kMarginY = 100;
std::array<int, 3> drawn(const Png& png, int panel, int w, int zoom, int x, int y) {
  return png.at(panel * (zoom * w + kMarginX) + kLeft + zoom * x + zoom / 2,
                kTop + zoom * y + zoom / 2);
}
bool near_rgb(std::array<int, 3> got, std::array<int, 3> want) {
  for (int c = 0; c < 3; ++c)
    if (std::abs(got[c] - want[c]) > 2) return false;
  return true;
}

// Reference v(i, j, k) = 10 i on a 10^3 grid: its z slice is 10 x 10 pixels (drawn 25 x 25), x
// along i, the top row the largest j, grey 255 v / 90 over the default window, the 1st and 99th
// percentiles of the 1000 samples (each of 0, 10, ..., 90 a hundred times: 0 and 90). A constant
// 10 reconstructed by the tricubic (partition of unity) over --range 0 20 is grey 128 everywhere,
// in each of three panels side by side.
TEST_F(BoxreconVolumes, SlicePngsHaveTheirSizeAndValues) {
  save_cartesian(file("ramp.nrrd"), 10,
                 [](int i, int, int) { return 10.0f * static_cast<float>(i); });
  const std::string said = ok(
      {"slice", "--reference", file("ramp.nrrd"), "--axis", "z", "--at", "4", "-o", file("r.png")});
  EXPECT_NE(said.find("10 x 10 pixels per panel (drawn 25 x 25 each), 1 panel(s)"),
            std::string::npos)
      << said;
  EXPECT_NE(said.find("values [0, 90] mapped to the colour map (percentiles 1 and 99 of the "
                      "reference's samples)"),
            std::string::npos)
      << said;
  const Png r = read_png(file("r.png"));
  ASSERT_EQ(r.width, 250 + kMarginX);
  ASSERT_EQ(r.height, 250 + kMarginY);
  for (int x : {0, 3, 9})
    for (int y : {0, 3, 9}) {
      const int grey = static_cast<int>(std::lround(255.0 * 10 * x / 90));
      EXPECT_TRUE(near_rgb(drawn(r, 0, 10, 25, x, y), {grey, grey, grey}))
          << x << " " << y << ": " << drawn(r, 0, 10, 25, x, y)[0];
    }
  save_cartesian(file("ten.nrrd"), 12, [](int, int, int) { return 10.0f; });
  ok({"slice",    "--volume", file("ten.nrrd"), "--filter", "tricubic", "--filter", "cart7",
      "--filter", "tricubic", "--axis",         "y",        "--at",     "5.5",      "--size",
      "8",        "6",        "--range",        "0",        "20",       "-o",       file("t.png")});
  const Png t = read_png(file("t.png"));  // drawn 32 x 32
  ASSERT_EQ(t.width, 3 * (8 * 32 + kMarginX));
  ASSERT_EQ(t.height, 6 * 32 + kMarginY);
  for (int panel = 0; panel < 3; ++panel)
    for (int x : {0, 2, 7})
      EXPECT_TRUE(near_rgb(drawn(t, panel, 8, 32, x, 2), {128, 128, 128})) << panel << " " << x;
  // The difference to the ramp at its voxels, 10 - 10 i, over [-20, 20]: white at i = 1, half
  // way to blue at i = 2 (-10: 255 (1 - 1/2)), blue at i = 3 (-20) and beyond.
  ok({"slice", "--volume", file("ten.nrrd"), "--filter", "tricubic", "--axis", "z", "--at", "5",
      "--difference-to", file("ramp.nrrd"), "--range", "-20", "20", "-o", file("d.png")});
  const Png d = read_png(file("d.png"));
  ASSERT_EQ(d.width, 250 + kMarginX);
  EXPECT_TRUE(near_rgb(drawn(d, 0, 10, 25, 1, 2), {255, 255, 255}));
  EXPECT_TRUE(near_rgb(drawn(d, 0, 10, 25, 2, 2), {128, 128, 255}));
  EXPECT_TRUE(near_rgb(drawn(d, 0, 10, 25, 3, 2), {0, 0, 255}));
  EXPECT_TRUE(near_rgb(drawn(d, 0, 10, 25, 8, 2), {0, 0, 255}));
  refused({"slice", "--reference", file("ramp.nrrd"), "--filter", "m7", "--at", "4", "-o",
           file("x.png")},
          "need --volume", file("x.png"));
  refused({"slice", "--reference", file("ramp.nrrd"), "--at", "40", "-o", file("x.png")}, "outside",
          file("x.png"));
}

// render --volume without --iso: v = i + 10 j + 100 k on 10^3 voxels takes each value 0..999
// once, so (NumPy's linear percentiles) p1 = 0.01 * 999 = 9.99, p99 = 0.99 * 999 = 989.01 and
// the iso is their midpoint 499.5, printed on stdout.
TEST_F(BoxreconVolumes, RenderTakesItsDefaultIsoFromTheData) {
  save_cartesian(file("ramp.nrrd"), 10,
                 [](int i, int j, int k) { return static_cast<float>(i + 10 * j + 100 * k); });
  const std::string out = ok({"render", "--volume", file("ramp.nrrd"), "--filter", "tricubic",
                              "--width", "8", "--height", "8", "--quiet", "-o", file("r.png")});
  EXPECT_EQ(out,
            "iso = 499.5 (midpoint of the 1st and 99th percentiles of the samples, 9.99 and "
            "989.01)\n");
  EXPECT_EQ(ok({"render", "--volume", file("ramp.nrrd"), "--filter", "tricubic", "--iso", "300",
                "--width", "8", "--height", "8", "--quiet", "-o", file("r.png")}),
            "");  // a given iso is not printed
}

// A Gaussian blob exp(-r^2 / 8) (iso 1/2 at r = 2.35) centred at (11, 7.5, 7.5) on 16^3 voxels
// of spacing 1, right (+x) of the render box's centre (7.5, 7.5, 7.5). Seen level (elevation 0)
// from +y (azimuth 90) the camera's right is -x, so the blob is left of the image's centre; from
// -y (azimuth 270) it is right of it. By hand: at distance D = 3.2 half-diagonals (about 36
// voxels for the box inside the tricubic's margin) and tan(18 deg) = 0.325, its centre is
// 3.5 / 36 / 0.325 = 0.3 half-widths off centre, pixel 22 of 64 (or 41), its radius 6 pixels, and
// row 30 (the view looks 0.08 half-diagonals below the centre). The mirrored pixel is
// background: render.cpp's vertical gradient (0.93 - 0.12 t, 0.94 - 0.1 t, 0.96) * 255 with
// t = row / height.
TEST_F(BoxreconVolumes, AzimuthTurnsTheCameraAboutTheZAxis) {
  save_cartesian(file("blob.nrrd"), 16, [](int i, int j, int k) {
    const double r2 = (i - 11.0) * (i - 11.0) + (j - 7.5) * (j - 7.5) + (k - 7.5) * (k - 7.5);
    return static_cast<float>(std::exp(-r2 / 8));
  });
  const auto render = [&](const char* azimuth) {
    ok({"render", "--volume", file("blob.nrrd"), "--filter", "tricubic", "--iso", "0.5",
        "--azimuth", azimuth, "--elevation", "0", "--width", "64", "--height", "64", "--quiet",
        "-o", file("a.png")});
    return read_png(file("a.png"));
  };
  const double t = 30.0 / 64;
  const std::array<int, 3> background{static_cast<int>(std::lround(255 * (0.93 - 0.12 * t))),
                                      static_cast<int>(std::lround(255 * (0.94 - 0.1 * t))),
                                      static_cast<int>(std::lround(255 * 0.96))};
  const Png from_y = render("90");
  EXPECT_NE(from_y.at(22, 30), background);
  EXPECT_EQ(from_y.at(41, 30), background);
  const Png from_minus_y = render("270");
  EXPECT_EQ(from_minus_y.at(22, 30), background);
  EXPECT_NE(from_minus_y.at(41, 30), background);
}

TEST_F(BoxreconVolumes, RenderOptionsWithoutEffectOrOutOfRangeAreRefused) {
  save_cartesian(file("v.nrrd"), 10, [](int i, int, int) { return static_cast<float>(i); });
  const std::string out = file("r.png");
  const auto render = [&](std::vector<std::string> more) {
    std::vector<std::string> a{"render",  "--volume", file("v.nrrd"), "--filter", "tricubic",
                               "--width", "8",        "--height",     "8",        "-o",
                               out};
    a.insert(a.end(), more.begin(), more.end());
    return a;
  };
  refused(render({"--n", "9"}), "--n has no effect", out);
  refused(render({"--closeup", "--azimuth", "10"}), "--closeup", out);
  refused(render({"--closeup", "--distance", "2"}), "--closeup", out);
  refused(render({"--elevation", "90"}), "--elevation", out);
  refused(render({"--distance", "0"}), "--distance", out);
  refused(render({"--azimuth", "inf"}), "--azimuth", out);
  refused({"render", "--function", "ml", "--volume", file("v.nrrd"), "-o", out}, "--function", out);
}

// A NIfTI-1 file written through nifticlib: 12^3 int16 voxels (all 0), spacing 1, the given sform.
void save_nifti(const std::string& path, double shear) {
  const std::int64_t dims[8] = {3, 12, 12, 12, 1, 1, 1, 1};
  nifti_image* nim = nifti_make_new_nim(dims, DT_INT16, 1);
  ASSERT_NE(nim, nullptr);
  nim->sform_code = 1;
  for (int r = 0; r < 4; ++r)
    for (int c = 0; c < 4; ++c) nim->sto_xyz.m[r][c] = r == c ? 1 : 0;
  nim->sto_xyz.m[0][1] = shear;
  nim->nifti_type = NIFTI_FTYPE_NIFTI1_1;
  ASSERT_EQ(nifti_set_filenames(nim, path.c_str(), 0, 1), 0);
  nifti_image_write(nim);
  nifti_image_free(nim);
}

TEST_F(BoxreconVolumes, BadInputIsOneLineAndWritesNothing) {
  ok({"sample", "--function", "cubic", "--lattice", "cartesian", "--n", "9", "-o", file("c.nrrd")});
  const std::string out = file("out.nrrd");
  const auto subsample = [&](const std::string& volume, std::vector<std::string> more) {
    std::vector<std::string> a{"subsample", "--volume", volume, "-o", out};
    a.insert(a.end(), more.begin(), more.end());
    return a;
  };
  refused(subsample(file("c.nrrd"), {"--lattice", "hexagonal", "--fraction", "0.1"}), "lattice",
          out);
  refused(subsample(file("c.nrrd"), {"--lattice", "bcc", "--fraction", "0"}), "--fraction", out);
  refused(subsample(file("c.nrrd"), {"--lattice", "bcc", "--fraction", "-0.5"}), "--fraction", out);
  refused(subsample(file("c.nrrd"), {"--lattice", "bcc", "--fraction", "1.5"}), "--fraction", out);
  refused(subsample(file("c.nrrd"), {"--lattice", "bcc"}), "--fraction", out);
  save_nifti(file("oblique.nii.gz"), 0.4);  // render does not map through an affine
  refused(
      {"render", "--volume", file("oblique.nii.gz"), "--filter", "tricubic", "-o", file("r.png")},
      "oblique", file("r.png"));
  save_nifti(file("good.nii.gz"), 0);
  std::ifstream in(file("good.nii.gz"), std::ios::binary);
  const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  std::ofstream(file("cut.nii.gz"), std::ios::binary)
      .write(bytes.data(), static_cast<std::streamsize>(bytes.size() - 20));
  refused(subsample(file("cut.nii.gz"), {"--lattice", "bcc", "--fraction", "0.1"}), "cut short",
          out);
  // The good file works (so the refusals above are about the files, not the command).
  ok(subsample(file("good.nii.gz"), {"--lattice", "bcc", "--spacing", "1"}));
  EXPECT_TRUE(fs::exists(out));
  fs::remove(out);
  // compare: a mask nothing passes, and the error volume is then not written.
  refused({"compare", "--reference", file("c.nrrd"), "--volume", file("c.nrrd"), "--filter",
           "tricubic", "--mask-above", "1e6", "--error-volume", out},
          "mask is empty", out);
  refused({"compare", "--reference", file("c.nrrd"), "--volume", file("c.nrrd"), "--filter", "m7"},
          "bcc", "");
}

// A NIfTI file read with nifticlib directly, as FSL, AFNI and ITK read it.
struct NiftiFile {
  int datatype = 0, sform_code = 0, qform_code = 0;
  std::array<std::int64_t, 4> dim{};  // dim[0..3]
  double sform[3][4]{}, qform[3][4]{};
  std::vector<double> values;  // as stored (no scaling)
};

NiftiFile load_nifti(const std::string& path) {
  NiftiFile f;
  nifti_image* nim = nifti_image_read(path.c_str(), 1);
  if (!nim) {
    ADD_FAILURE() << "nifticlib cannot read " << path;
    return f;
  }
  f.datatype = nim->datatype;
  f.sform_code = nim->sform_code;
  f.qform_code = nim->qform_code;
  for (int a = 0; a < 4; ++a) f.dim[a] = nim->dim[a];
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 4; ++c) {
      f.sform[r][c] = nim->sto_xyz.m[r][c];
      f.qform[r][c] = nim->qto_xyz.m[r][c];
    }
  const auto n = static_cast<std::size_t>(nim->nvox);
  const auto copy = [&](auto tag) {
    using S = decltype(tag);
    const S* p = static_cast<const S*>(nim->data);
    for (std::size_t i = 0; i < n; ++i) f.values.push_back(static_cast<double>(p[i]));
  };
  if (nim->datatype == DT_FLOAT32) copy(float{});
  if (nim->datatype == DT_FLOAT64) copy(double{});
  if (nim->datatype == DT_INT16) copy(std::int16_t{});
  if (nim->datatype == DT_UINT8) copy(std::uint8_t{});
  nifti_image_free(nim);
  return f;
}

// resample -o x.nii writes NIfTI-1 (float32 by default): nifticlib reads the same grid as the NRRD
// of the same command, the same values (both float), and the affine diag(spacing) + origin as
// the sform (code 2); sample's volume is tied to no patient, so the qform's code is 0 (as
// nibabel writes a new image). .nii.gz is the same file compressed.
TEST_F(BoxreconVolumes, ResampleWritesNiftiThatNifticlibReadsBack) {
  ok({"sample", "--function", "ml", "--lattice", "bcc", "--n", "9", "-o", file("ml.nrrd")});
  const std::vector<std::string> common{"resample", "--filter",      "m7",
                                        "--volume", file("ml.nrrd"), "--n",
                                        "7",        "--precision",   "float"};
  const auto run = [&](const std::string& out, std::vector<std::string> more = {}) {
    std::vector<std::string> a = common;
    a.insert(a.end(), {"-o", out});
    a.insert(a.end(), more.begin(), more.end());
    ok(a);
  };
  run(file("g.nrrd"));
  run(file("g.nii"));
  run(file("g.nii.gz"));
  const TeemVolume grid = load(file("g.nrrd"));
  for (const char* name : {"g.nii", "g.nii.gz"}) {
    SCOPED_TRACE(name);
    const NiftiFile nii = load_nifti(file(name));
    EXPECT_EQ(nii.datatype, DT_FLOAT32);
    EXPECT_EQ(nii.dim[0], 3);
    for (int a = 0; a < 3; ++a) EXPECT_EQ(nii.dim[a + 1], 7);
    EXPECT_EQ(nii.sform_code, NIFTI_XFORM_ALIGNED_ANAT);
    EXPECT_EQ(nii.qform_code, NIFTI_XFORM_UNKNOWN);
    for (int r = 0; r < 3; ++r) {
      for (int c = 0; c < 3; ++c) EXPECT_NEAR(nii.sform[r][c], r == c ? grid.step[r] : 0.0, 1e-6);
      EXPECT_NEAR(nii.sform[r][3], grid.origin[r], 1e-6);
    }
    ASSERT_EQ(nii.values.size(), grid.samples.size());
    for (std::size_t i = 0; i < grid.samples.size(); ++i)
      ASSERT_EQ(nii.values[i], static_cast<double>(grid.samples[i])) << i;
  }
  // boxrecon reads its own NIfTI back as the NRRD: compare's numbers are the same from either, to
  // the float32 rounding of NIfTI-1's affine (its srow entries are float: spacing and origin move
  // by ~1e-8 relative, and with them the points the reconstruction is evaluated at).
  const auto errors = [&](const std::string& volume) {
    const nlohmann::json j =
        nlohmann::json::parse(ok({"compare", "--reference", file("g.nrrd"), "--volume", volume,
                                  "--filter", "tricubic", "--json"}));
    return j["region"];
  };
  const nlohmann::json from_nrrd = errors(file("g.nrrd"));
  EXPECT_GT(from_nrrd["points"].get<int>(), 0);
  for (const char* name : {"g.nii.gz", "g.nii"}) {
    const nlohmann::json from_nifti = errors(file(name));
    EXPECT_EQ(from_nifti["points"], from_nrrd["points"]) << name;
    for (const char* key : {"rms", "max", "mean_abs"})
      EXPECT_NEAR(from_nifti[key].get<double>(), from_nrrd[key].get<double>(),
                  1e-5 * from_nrrd[key].get<double>())
          << name << " " << key;
  }
}

// The samples of a NRRD in double (Teem converts), in storage order.
std::vector<double> load_doubles(const std::string& path) {
  std::vector<double> v;
  Nrrd* nrrd = nrrdNew();
  Nrrd* doubles = nrrdNew();
  if (nrrdLoad(nrrd, path.c_str(), nullptr) == 0 &&
      nrrdConvert(doubles, nrrd, nrrdTypeDouble) == 0) {
    const auto* data = static_cast<const double*>(doubles->data);
    v.assign(data, data + nrrdElementNumber(doubles));
  } else {
    ADD_FAILURE() << "Teem cannot read " << path;
  }
  nrrdNuke(doubles);
  nrrdNuke(nrrd);
  return v;
}

// resample --lattice onto a BCC grid: with --like the input (its own grid) and an interpolating
// prefilter, the output is the input's samples (to the solve's rounding) in the input's layout;
// --lattice bcc names the same grid.
TEST_F(BoxreconVolumes, ResampleOntoItsOwnBccGridReproducesTheSamples) {
  ok({"sample", "--function", "ml", "--lattice", "bcc", "--n", "9", "-o", file("ml.nrrd")});
  ok({"resample", "--filter", "m8", "--prefilter", "interp", "--volume", file("ml.nrrd"), "--like",
      file("ml.nrrd"), "-o", file("same.nrrd")});
  ok({"resample", "--filter", "m8", "--prefilter", "interp", "--volume", file("ml.nrrd"), "--like",
      file("ml.nrrd"), "--lattice", "bcc", "-o", file("named.nrrd")});
  const TeemVolume in = load(file("ml.nrrd")), out = load(file("same.nrrd"));
  EXPECT_EQ(out.sizes, in.sizes);
  for (int a = 0; a < 3; ++a) {
    EXPECT_EQ(out.step[a], in.step[a]);
    EXPECT_EQ(out.origin[a], in.origin[a]);
  }
  const std::vector<double> samples = load_doubles(file("ml.nrrd"));
  const std::vector<double> values = load_doubles(file("same.nrrd"));
  ASSERT_EQ(values.size(), samples.size());
  EXPECT_EQ(load_doubles(file("named.nrrd")), values);
  const auto [lo, hi] = std::minmax_element(samples.begin(), samples.end());
  double worst = 0;
  for (std::size_t i = 0; i < samples.size(); ++i)
    worst = std::max(worst, std::fabs(values[i] - samples[i]));
  EXPECT_LT(worst, 1e-12 * (*hi - *lo));  // measured 7.8e-16 of the range
}

// resample --lattice fcc --spacing H: each FCC sample (c, i, j, k) at o + h (2 (i, j, k) + offset
// of coset c) is the value eval gives at that point (the same spline, evaluated by eval); --n N
// gives about N^3 samples.
TEST_F(BoxreconVolumes, ResampleOntoFccEqualsEvalAtItsSamples) {
  ok({"sample", "--function", "ml", "--lattice", "bcc", "--n", "9", "-o", file("ml.nrrd")});
  const std::vector<std::string> common{"resample", "--filter", "m7",           "--prefilter",
                                        "q1",       "--volume", file("ml.nrrd")};
  const auto with = [&](std::vector<std::string> more) {
    std::vector<std::string> a = common;
    a.insert(a.end(), more.begin(), more.end());
    return a;
  };
  ok(with({"--lattice", "fcc", "--spacing", "0.3", "-o", file("f.nrrd")}));
  const TeemVolume f = load(file("f.nrrd"));
  ASSERT_EQ(f.sizes.size(), 4u);
  ASSERT_EQ(f.sizes[0], 4u);
  const double h = f.step[0] / 2;  // space direction 2h
  EXPECT_DOUBLE_EQ(h, 0.3);
  const int offsets[4][3] = {{0, 0, 0}, {1, 1, 0}, {1, 0, 1}, {0, 1, 1}};
  std::string points;
  for (std::size_t k = 0; k < f.sizes[3]; ++k)
    for (std::size_t j = 0; j < f.sizes[2]; ++j)
      for (std::size_t i = 0; i < f.sizes[1]; ++i)
        for (const auto& o : offsets) {
          char line[96];
          std::snprintf(line, sizeof line, "%.17g %.17g %.17g\n",
                        f.origin[0] + h * static_cast<double>(2 * i + o[0]),
                        f.origin[1] + h * static_cast<double>(2 * j + o[1]),
                        f.origin[2] + h * static_cast<double>(2 * k + o[2]));
          points += line;
        }
  std::ofstream(file("p.txt")) << points;
  const std::string printed = ok({"eval", "--filter", "m7", "--prefilter", "q1", "--volume",
                                  file("ml.nrrd"), "--points", file("p.txt")});
  std::istringstream lines(printed);
  std::vector<double> expected;
  for (double v = 0; lines >> v;) expected.push_back(v);
  const std::vector<double> values = load_doubles(file("f.nrrd"));
  ASSERT_EQ(values.size(), expected.size());
  ASSERT_GT(values.size(), 100u);
  for (std::size_t s = 0; s < values.size(); ++s)
    EXPECT_NEAR(values[s], expected[s], 1e-13) << s;  // measured equal; the points may round
  ok(with({"--lattice", "bcc", "--n", "6", "-o", file("n.nrrd")}));
  const TeemVolume n = load(file("n.nrrd"));
  ASSERT_EQ(n.sizes.size(), 4u);
  const double count = static_cast<double>(n.samples.size());
  EXPECT_GT(count, 216 / 1.6) << count;
  EXPECT_LT(count, 216 * 1.6) << count;
  // Refused in one line, no file: NIfTI cannot hold it, --size and three spacings are for
  // Cartesian grids, a --lattice other than --like's, a box leaving the evaluable region.
  refused(with({"--lattice", "bcc", "-o", file("x.nii")}), "cannot be nifti", file("x.nii"));
  refused(with({"--lattice", "bcc", "--size", "4", "4", "4", "-o", file("x.nrrd")}), "--size",
          file("x.nrrd"));
  refused(with({"--lattice", "fcc", "--spacing", "0.3", "0.3", "0.4", "-o", file("x.nrrd")}),
          "one spacing", file("x.nrrd"));
  refused(with({"--lattice", "fcc", "--like", file("ml.nrrd"), "-o", file("x.nrrd")}),
          "differs from the lattice of --like", file("x.nrrd"));
  refused(with({"--lattice", "fcc", "--min", "-3", "-3", "-3", "--max", "3", "3", "3", "-o",
                file("x.nrrd")}),
          "leave the region", file("x.nrrd"));
}

// --type int16 rounds to the nearest integer and clamps beyond the range, saying how many on
// stderr (one line); uint8 in NRRD too. (Ties to even are encode_samples' unit test.)
TEST_F(BoxreconVolumes, TypeRoundsAndClampsAndSaysHowMany) {
  // A ramp 20000 i + 0.25: the tricubic reproduces it, and most of it is beyond int16's 32767.
  save_cartesian(file("big.nrrd"), 10,
                 [](int i, int, int) { return static_cast<float>(i) * 20000.0f + 0.25f; });
  const std::vector<std::string> resample{"resample", "--filter",       "tricubic",
                                          "--volume", file("big.nrrd"), "--n",
                                          "8",        "--precision",    "double"};
  std::vector<std::string> a = resample;
  a.insert(a.end(), {"-o", file("i.nii"), "--type", "int16"});
  const ProcessResult clamp = boxrecon(a);
  ASSERT_TRUE(clamp.exited && clamp.exit_code == 0) << clamp.err;
  a = resample;
  a.insert(a.end(), {"-o", file("d.nrrd")});
  ok(a);
  const TeemVolume d = load(file("d.nrrd"));  // the double grid, read as float
  const NiftiFile i16 = load_nifti(file("i.nii"));
  ASSERT_EQ(i16.datatype, DT_INT16);
  ASSERT_EQ(i16.values.size(), d.samples.size());
  std::size_t beyond = 0;
  for (std::size_t i = 0; i < d.samples.size(); ++i) {
    const double v = std::nearbyint(static_cast<double>(d.samples[i]));
    const double expected = std::clamp(v, -32768.0, 32767.0);
    beyond += v != expected ? 1 : 0;
    ASSERT_EQ(i16.values[i], expected) << i;
  }
  ASSERT_GT(beyond, 0u);
  EXPECT_NE(clamp.err.find(std::to_string(beyond) + " values were beyond the int16 range"),
            std::string::npos)
      << clamp.err;
  EXPECT_EQ(std::count(clamp.err.begin(), clamp.err.end(), '\n'), 1) << clamp.err;
  // NRRD with --type: Teem reads uint8 samples.
  a = resample;
  a.insert(a.end(), {"-o", file("u8.nrrd"), "--type", "uint8"});
  EXPECT_EQ(boxrecon(a).exit_code, 0);
  Nrrd* nrrd = nrrdNew();
  ASSERT_EQ(nrrdLoad(nrrd, file("u8.nrrd").c_str(), nullptr), 0);
  EXPECT_EQ(nrrd->type, nrrdTypeUChar);
  nrrdNuke(nrrd);
}

// Every output name says its format; the wrong one is refused before any work, in one line.
TEST_F(BoxreconVolumes, OutputNamesNoWriterKnowsAreRefused) {
  ok({"sample", "--function", "cubic", "--lattice", "cartesian", "--n", "9", "-o", file("c.nrrd")});
  ok({"sample", "--function", "cubic", "--lattice", "bcc", "--n", "9", "-o", file("b.nrrd")});
  const auto resample = [&](const std::string& out, std::vector<std::string> more = {}) {
    std::vector<std::string> a{"resample", "--filter", "tricubic", "--volume", file("c.nrrd"),
                               "--n",      "4",        "-o",       out};
    a.insert(a.end(), more.begin(), more.end());
    return a;
  };
  refused(resample(file("out.vol")), "no writer knows its extension", file("out.vol"));
  refused(resample(file("out")), ".nrrd, .nii or .nii.gz", file("out"));
  refused(resample(file("out.nhdr")), "detached", file("out.nhdr"));
  refused(resample(file("out.hdr")), ".hdr/.img", file("out.hdr"));
  refused(resample(file("out.nii"), {"--type", "int64"}), "--type", file("out.nii"));
  // A BCC volume cannot be NIfTI: subsample and sample refuse the name up front.
  refused({"subsample", "--volume", file("c.nrrd"), "--lattice", "bcc", "--fraction", "0.5", "-o",
           file("b.nii")},
          "NIfTI", file("b.nii"));
  refused({"sample", "--function", "cubic", "--lattice", "fcc", "--n", "5", "-o", file("f.nii.gz")},
          "cartesian grids only", file("f.nii.gz"));
  refused({"compare", "--reference", file("c.nrrd"), "--volume", file("b.nrrd"), "--filter", "m7",
           "--type", "int16"},
          "--error-volume", "");
  refused({"compare", "--reference", file("c.nrrd"), "--volume", file("b.nrrd"), "--filter", "m7",
           "--error-volume", file("e.img")},
          ".hdr/.img", file("e.img"));
  // A Cartesian subsample and sample are NIfTI where asked.
  ok({"subsample", "--volume", file("c.nrrd"), "--lattice", "cartesian", "--fraction", "0.5", "-o",
      file("s.nii.gz")});
  EXPECT_EQ(load_nifti(file("s.nii.gz")).datatype, DT_FLOAT32);
  ok({"sample", "--function", "cubic", "--lattice", "cartesian", "--n", "5", "-o", file("c.nii")});
  EXPECT_EQ(load_nifti(file("c.nii")).dim[0], 3);
}

// A NIfTI image of `dims` (dim[0] first) and `datatype`, all zeros, spacing 1, through nifticlib;
// `nifti_type` NIFTI_FTYPE_NIFTI1_2 writes a .hdr/.img pair, NIFTI_FTYPE_ANALYZE an Analyze one.
void save_nifti_image(const std::string& path, std::vector<std::int64_t> dims, int datatype,
                      int nifti_type, int intent = 0) {
  std::int64_t d[8] = {0, 1, 1, 1, 1, 1, 1, 1};
  for (std::size_t a = 0; a < dims.size(); ++a) d[a] = dims[a];
  nifti_image* nim = nifti_make_new_nim(d, datatype, 1);
  ASSERT_NE(nim, nullptr);
  nim->nifti_type = nifti_type;
  nim->intent_code = intent;
  nim->qform_code = nifti_type == NIFTI_FTYPE_ANALYZE ? 0 : 1;
  nim->qto_xyz = nifti_quatern_to_dmat44(0, 0, 0, 0, 0, 0, 1, 1, 1, 1);
  ASSERT_EQ(nifti_set_filenames(nim, path.c_str(), 0, 1), 0);
  nifti_image_write(nim);
  nifti_image_free(nim);
}

// NIfTI .hdr/.img pairs read (from either name); Analyze 7.5, DICOM, CIFTI, vector and RGB
// images are refused by name, in one line.
TEST_F(BoxreconVolumes, FormatsAreReadOrNamedWhenRefused) {
  ok({"sample", "--function", "cubic", "--lattice", "bcc", "--n", "9", "-o", file("b.nrrd")});
  const auto compare = [&](const std::string& reference) {
    return std::vector<std::string>{"compare",      "--reference", reference, "--volume",
                                    file("b.nrrd"), "--filter",    "m7"};
  };
  save_nifti_image(file("pair.hdr"), {3, 12, 12, 12}, DT_INT16, NIFTI_FTYPE_NIFTI1_2);
  ASSERT_TRUE(fs::exists(file("pair.img")));
  const ProcessResult pair = boxrecon(compare(file("pair.hdr")));
  // Both readable: the compare fails only for having no grid point in the filter's region or
  // succeeds; either way the file was read (no "cannot read").
  EXPECT_EQ(pair.err.find("cannot read"), std::string::npos) << pair.err;
  EXPECT_EQ(boxrecon(compare(file("pair.img"))).err.find("cannot read"), std::string::npos);
  save_nifti_image(file("analyze.hdr"), {3, 12, 12, 12}, DT_INT16, NIFTI_FTYPE_ANALYZE);
  refused(compare(file("analyze.hdr")), "Analyze 7.5", "");
  save_nifti_image(file("rgb.nii"), {3, 4, 4, 4}, DT_RGB24, NIFTI_FTYPE_NIFTI1_1);
  refused(compare(file("rgb.nii")), "RGB", "");
  save_nifti_image(file("vector.nii.gz"), {5, 4, 4, 4, 1, 3}, DT_FLOAT32, NIFTI_FTYPE_NIFTI1_1,
                   NIFTI_INTENT_VECTOR);
  refused(compare(file("vector.nii.gz")), "3 values per voxel", "");
  save_nifti_image(file("field.nii"), {5, 4, 4, 4, 1, 3}, DT_FLOAT32, NIFTI_FTYPE_NIFTI1_1);
  refused(compare(file("field.nii")), "3 values per voxel", "");
  // CIFTI-2: NIfTI-2 with a connectivity intent (3006: dense scalars), a 1 x 1 x 1 x 1 x 2 x 5
  // matrix.
  save_nifti_image(file("scalars.dscalar.nii"), {6, 1, 1, 1, 1, 2, 5}, DT_FLOAT32,
                   NIFTI_FTYPE_NIFTI2_1, 3006);
  refused(compare(file("scalars.dscalar.nii")), "CIFTI", "");
  std::string dicom(128, '\0');
  dicom += "DICM";
  dicom += std::string(64, 'x');
  std::ofstream(file("IM0001"), std::ios::binary) << dicom;
  refused(compare(file("IM0001")), "dcm2niix", "");
  std::ofstream(file("scan.dcm"), std::ios::binary) << "old ACR-NEMA bytes";
  refused(compare(file("scan.dcm")), "DICOM", "");
}

// The layout boxrecon once wrote for Cartesian volumes reads again: a 4-D NRRD with a coset axis
// of size 1 (sizes 1 n n n, space directions none (h,0,0) (0,h,0) (0,0,h), lattice:=cartesian),
// and its values are those of the same samples as a plain 3-D NRRD. A truly oblique NRRD is
// refused, with the directions it has, by a command that does not map through its affine.
TEST_F(BoxreconVolumes, FourDimensionalCartesianNrrdOfEarlierVersionsReads) {
  std::vector<float> values;
  for (int k = 0; k < 8; ++k)
    for (int j = 0; j < 8; ++j)
      for (int i = 0; i < 8; ++i) values.push_back(static_cast<float>(i + 2 * j + 3 * k));
  const auto save = [&](const std::string& path, bool four, double shear) {
    Nrrd* nrrd = nrrdNew();
    const std::size_t sizes4[4] = {1, 8, 8, 8}, sizes3[3] = {8, 8, 8};
    ASSERT_EQ(
        nrrdWrap_nva(nrrd, values.data(), nrrdTypeFloat, four ? 4 : 3, four ? sizes4 : sizes3), 0);
    ASSERT_EQ(nrrdSpaceSet(nrrd, nrrdSpace3DRightHanded), 0);
    const unsigned first = four ? 1 : 0;
    if (four)
      for (int b = 0; b < 3; ++b) nrrd->axis[0].spaceDirection[b] = AIR_NAN;
    for (unsigned a = 0; a < 3; ++a)
      for (unsigned b = 0; b < 3; ++b)
        nrrd->axis[first + a].spaceDirection[b] = a == b ? 0.5 : (a == 0 && b == 1 ? shear : 0.0);
    double origin[3] = {1, 2, 3};
    ASSERT_EQ(nrrdSpaceOriginSet(nrrd, origin), 0);
    ASSERT_EQ(nrrdKeyValueAdd(nrrd, "lattice", "cartesian"), 0);
    ASSERT_EQ(nrrdSave(path.c_str(), nrrd, nullptr), 0);
    nrrdNix(nrrd);
  };
  save(file("old.nrrd"), true, 0);
  save(file("new.nrrd"), false, 0);
  const nlohmann::json j = nlohmann::json::parse(
      ok({"compare", "--reference", file("new.nrrd"), "--volume", file("old.nrrd"), "--filter",
          "tricubic", "--prefilter", "q1", "--boundary", "strict", "--json"}));
  EXPECT_GT(j["region"]["points"].get<int>(), 0);
  EXPECT_LT(j["region"]["max"].get<double>(), 1e-4);  // a linear ramp: reproduced
  save(file("oblique.nrrd"), false, 0.25);
  refused({"render", "--volume", file("oblique.nrrd"), "--filter", "tricubic", "-o", file("r.png")},
          "(0.5,0.25,0)", file("r.png"));
}

}  // namespace
}  // namespace boxgen::test
