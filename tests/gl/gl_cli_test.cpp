// boxrecon --device gl as a user runs it: eval prints the CPU's numbers (float, within rounding),
// names the renderer with --verbose, fails with the CPU's one line for a point outside the
// volume; resample and render write their files; a bad --device is one line.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include "cli_support.h"
#include "tests/support/scratch_directory.h"

namespace boxgen::test {
namespace {

class GlCliTest : public ScratchDirectoryTest {
 protected:
  GlCliTest() : ScratchDirectoryTest("boxgen-gl-cli") {}
  std::string file(const std::string& name) const { return (dir_ / name).string(); }
  void SetUp() override {
    ScratchDirectoryTest::SetUp();
    const ProcessResult r =
        boxrecon({"sample", "--function", "ml", "--n", "12", "-o", file("v.nrrd")});
    ASSERT_TRUE(r.exited && r.exit_code == 0) << r.err;
    std::ofstream(file("points.txt")) << "0.1 0.2 0.3\n-0.5 0.25 0.7\n0 0 0\n0.33 -0.61 0.05\n";
  }
  ProcessResult eval(std::vector<std::string> extra) {
    std::vector<std::string> args{
        "eval",     "--filter",         "m7",       "--volume", file("v.nrrd"),
        "--points", file("points.txt"), "--hessian"};
    args.insert(args.end(), extra.begin(), extra.end());
    return boxrecon(args, {}, std::chrono::seconds(300 * kSlowdown));
  }
};

std::vector<double> numbers(const std::string& text) {
  std::istringstream in(text);
  return {std::istream_iterator<double>(in), std::istream_iterator<double>()};
}

TEST_F(GlCliTest, EvalPrintsTheCpusFloatNumbers) {
  const ProcessResult cpu = eval({"--precision", "float"});
  const ProcessResult gl = eval({"--device", "gl"});  // float by default on the GL device
  ASSERT_EQ(gl.exit_code, 0) << gl.err;
  EXPECT_EQ(gl.err, "");
  const std::vector<double> a = numbers(cpu.out), b = numbers(gl.out);
  ASSERT_EQ(a.size(), 4u * 7u);
  ASSERT_EQ(b.size(), a.size());
  // Value, three first and six second derivatives (world units, spacing 2/11): float rounding.
  for (std::size_t i = 0; i < a.size(); ++i)
    EXPECT_NEAR(b[i], a[i], 1e-5 * std::max(1.0, std::abs(a[i]))) << i;
}

TEST_F(GlCliTest, VerboseNamesTheRenderer) {
  const ProcessResult r = eval({"--device", "gl", "--verbose", "--precision", "double"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(r.err.rfind("GL device: ", 0), 0u) << r.err;
  EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
}

TEST_F(GlCliTest, APointOutsideIsTheCpusError) {
  std::ofstream(file("points.txt")) << "0.1 0.2 0.3\n5 0 0\n";
  const ProcessResult cpu = eval({"--precision", "float"});
  const ProcessResult gl = eval({"--device", "gl"});
  EXPECT_EQ(cpu.exit_code, 1);
  EXPECT_EQ(gl.exit_code, 1);
  EXPECT_EQ(gl.err, cpu.err);
  EXPECT_EQ(gl.out, "");
}

TEST_F(GlCliTest, ResampleAndRenderWriteTheirFiles) {
  const ProcessResult resample = boxrecon({"resample", "--filter", "m7", "--volume", file("v.nrrd"),
                                           "--n", "6", "--device", "gl", "-o", file("grid.nrrd")},
                                          {}, std::chrono::seconds(300 * kSlowdown));
  EXPECT_EQ(resample.exit_code, 0) << resample.err;
  EXPECT_TRUE(std::filesystem::file_size(file("grid.nrrd")) > sizeof(float) * 216);
  const ProcessResult render =
      boxrecon({"render", "--volume", file("v.nrrd"), "--width", "16", "--height", "12", "--device",
                "gl", "--quiet", "-o", file("out.png")},
               {}, std::chrono::seconds(300 * kSlowdown));
  EXPECT_EQ(render.exit_code, 0) << render.err;
  EXPECT_EQ(render.err, "");
  std::ifstream png(file("out.png"), std::ios::binary);
  char signature[8] = {};
  png.read(signature, 8);
  EXPECT_EQ(std::string(signature + 1, 3), "PNG");
}

// The 3% BCC MRI volume of Fig. 10 rendered on defaults (M7, float, 512 x 512): float rays at the
// default box's faces reached samples outside the volume and the render failed with "choose a
// box inside it" while the CPU's succeeded. The MRI template comes with Debian's
// mricron-data (scripts/install-deps.sh).
TEST_F(GlCliTest, RenderOfTheBccMriVolumeWorksOnDefaults) {
  const std::string mri = "/usr/share/mricron/templates/ch2better.nii.gz";
  if (!std::filesystem::exists(mri)) GTEST_SKIP() << "no " << mri << " (mricron-data)";
  const ProcessResult subsample = boxrecon({"subsample", "--volume", mri, "--lattice", "bcc",
                                            "--fraction", "0.03", "-o", file("bcc3.nrrd")},
                                           {}, std::chrono::seconds(300 * kSlowdown));
  ASSERT_EQ(subsample.exit_code, 0) << subsample.err;
  const ProcessResult render = boxrecon({"render", "--volume", file("bcc3.nrrd"), "--filter", "m7",
                                         "--device", "gl", "--quiet", "-o", file("mri.png")},
                                        {}, std::chrono::seconds(600 * kSlowdown));
  EXPECT_EQ(render.exit_code, 0) << render.err;
  EXPECT_TRUE(std::filesystem::exists(file("mri.png")));
}

// A filter from a SPEC no preset has (label slow: its first use derives and compiles, about 15 s):
// its GLSL comes from the loader's cache, and eval on the GL device prints the CPU's numbers.
TEST_F(GlCliTest, SlowSpecFilterEvaluatesOnTheGlDevice) {
  const std::string spec = "1,1,1; 1,-1,-1; -1,1,-1; -1,-1,1; 2,0,0; 0,2,0";
  const std::string cache = file("cache");
  ::setenv("BOXGEN_CACHE_DIR", cache.c_str(), 1);  // the child processes inherit it
  const auto run = [&](std::vector<std::string> extra) {
    std::vector<std::string> args{"eval",         "--filter", spec,
                                  "--lattice",    "bcc",      "--volume",
                                  file("v.nrrd"), "--points", file("points.txt"),
                                  "--gradient",   "--quiet"};
    args.insert(args.end(), extra.begin(), extra.end());
    return boxrecon(args, {}, std::chrono::seconds(600 * kSlowdown));
  };
  const ProcessResult cpu = run({"--precision", "float"});
  const ProcessResult gl = run({"--device", "gl"});
  ::unsetenv("BOXGEN_CACHE_DIR");
  ASSERT_EQ(cpu.exit_code, 0) << cpu.err;
  ASSERT_EQ(gl.exit_code, 0) << gl.err;
  const std::vector<double> a = numbers(cpu.out), b = numbers(gl.out);
  ASSERT_EQ(a.size(), 4u * 4u);
  ASSERT_EQ(b.size(), a.size());
  for (std::size_t i = 0; i < a.size(); ++i)
    EXPECT_NEAR(b[i], a[i], 1e-5 * std::max(1.0, std::abs(a[i]))) << i;
  // Float and double, each with its tables as constants and in a storage block (the device
  // uses the latter), written with the shared object.
  int glsl_files = 0;
  for (const auto& entry : std::filesystem::directory_iterator(cache))
    glsl_files += entry.path().extension() == ".glsl";
  EXPECT_EQ(glsl_files, 4);
}

// BOXGEN_GL_DUMP=DIR: each compiled kernel's source, link log and program binary land in DIR
// (docs/gpu.md, "A kernel's compile"); a DIR that is a file is one line and exit 1.
TEST_F(GlCliTest, DumpWritesEachKernelsSourceLogAndBinary) {
  const std::string dump = file("dump");
  std::filesystem::create_directory(dump);  // an existing folder (a missing one is refused)
  ::setenv("BOXGEN_GL_DUMP", dump.c_str(), 1);
  const ProcessResult r = eval({"--device", "gl"});
  std::ofstream(file("not_a_folder")) << "x";
  ::setenv("BOXGEN_GL_DUMP", file("not_a_folder").c_str(), 1);
  const ProcessResult bad = eval({"--device", "gl"});
  ::unsetenv("BOXGEN_GL_DUMP");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const std::string base = dump + "/the_glsl_evaluator_m7_float_hessian_kernel";
  std::ifstream source(base + ".comp");
  const std::string text{std::istreambuf_iterator<char>(source), std::istreambuf_iterator<char>()};
  EXPECT_EQ(text.rfind("#version 430", 0), 0u);
  EXPECT_NE(text.find("m7_value_gradient_hessian(x, g, h)"), std::string::npos);
  EXPECT_TRUE(std::filesystem::exists(base + ".log"));
  EXPECT_TRUE(std::filesystem::exists(base + ".bin"));
  EXPECT_EQ(bad.exit_code, 1);
  EXPECT_EQ(bad.out, "");
  EXPECT_NE(bad.err.find("BOXGEN_GL_DUMP"), std::string::npos) << bad.err;
  EXPECT_EQ(std::count(bad.err.begin(), bad.err.end(), '\n'), 1) << bad.err;
}

// BOXGEN_GL_DUMP naming a folder that does not exist created it with its
// parents, and BOXGEN_GL_PLATFORM=bogus was ignored. Each is one line, exit 1, nothing made.
TEST_F(GlCliTest, AMissingDumpFolderAndAnUnknownPlatformAreRefused) {
  const std::string missing = file("no/such/folder");
  ::setenv("BOXGEN_GL_DUMP", missing.c_str(), 1);
  const ProcessResult dump = eval({"--device", "gl"});
  ::unsetenv("BOXGEN_GL_DUMP");
  ::setenv("BOXGEN_GL_PLATFORM", "bogus", 1);
  const ProcessResult platform = eval({"--device", "gl"});
  ::unsetenv("BOXGEN_GL_PLATFORM");
  for (const auto& [r, mention] :
       {std::pair{dump, std::string("is not an existing folder")},
        std::pair{platform, std::string("BOXGEN_GL_PLATFORM must be 'surfaceless' or unset, got "
                                        "'bogus'")}}) {
    EXPECT_EQ(r.exit_code, 1) << r.err;
    EXPECT_EQ(r.out, "");
    EXPECT_NE(r.err.find(mention), std::string::npos) << r.err;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
  }
  EXPECT_FALSE(std::filesystem::exists(file("no")));
}

TEST_F(GlCliTest, ABadDeviceIsOneLine) {
  const ProcessResult r = eval({"--device", "vulkan"});
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_EQ(r.err, "boxrecon: error: --device must be cpu or gl, got 'vulkan'\n");
  const ProcessResult f = boxrecon(
      {"render", "--function", "ml", "--n", "8", "--precision", "float", "-o", file("x.png")});
  EXPECT_EQ(f.exit_code, 1);
  EXPECT_EQ(f.err,
            "boxrecon: error: the CPU renderer works in double: --precision float needs --device "
            "gl\n");
}

}  // namespace
}  // namespace boxgen::test
