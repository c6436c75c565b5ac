// The GL device's kernels index no private or `const` array, and no vector, at a run-time index
// (docs/gpu.md, "Kernels"): a GPU compiler may keep such an array in each invocation's local
// memory, and NVIDIA's keeps only single precision where a double array or vector is indexed at
// run time. glslang's syntax tree (glslangValidator -i) marks every index by a non-constant
// expression "indirect index"; in the device's kernels of every registry filter, float and
// double, the only operands of such an index must be storage-buffer members.
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include <unistd.h>

#include "run_process.h"
#include "runtime/gl/gl_spline.h"
#include "runtime/sampling.h"

namespace boxgen::runtime::gl {
namespace {

// The operands of the indirect indexes in the syntax tree of a compute shader (the line after
// each "indirect index" node: its first child, the array or vector indexed).
std::vector<std::string> indirect_operands(const std::string& source, const std::string& label) {
  const std::filesystem::path file =
      std::filesystem::temp_directory_path() /
      ("boxgen_kernel_" + std::to_string(::getpid()) + "_" + label + ".comp");
  std::ofstream(file) << source;
  const test::ProcessResult r =
      test::run_process(GLSLANG_VALIDATOR, {"-i", file.string()}, std::chrono::seconds(120));
  std::filesystem::remove(file);
  EXPECT_TRUE(r.exited && r.exit_code == 0) << label << ": glslang does not accept the kernel\n"
                                            << test::describe({"-i"}, r);
  std::vector<std::string> operands;
  std::istringstream lines(r.out);
  std::string line, next;
  while (std::getline(lines, line))
    if (line.find("indirect index") != std::string::npos && std::getline(lines, next))
      operands.push_back(next);
  return operands;
}

bool is_buffer_member(const std::string& operand) {
  return operand.find("direct index for structure") != std::string::npos &&
         operand.find(" buffer ") != std::string::npos;
}

template <class T>
void expect_only_buffers_indexed_at_run_time(const std::string& name) {
  try {
    (void)device();
  } catch (const GlError& e) {
    FAIL() << e.what();
  }
  const SplineFilter f = SplineFilter::parse(name);
  const LatticeVolume<T> volume(f.lattice(), {6, 6, 6}, 1.0, {0, 0, 0});
  const GlSpline<T> spline(volume, f, registry_glsl(name, sizeof(T) == 8));
  using Spline = GlSpline<T>;
  for (int kind : {0, 1, 2, Spline::kFetchFloor, Spline::kFrame}) {
    const std::string label = name + (sizeof(T) == 8 ? "_double_" : "_float_") +
                              (kind == Spline::kFrame ? "frame" : std::to_string(kind));
    const std::vector<std::string> operands = indirect_operands(spline.kernel_source(kind), label);
    EXPECT_FALSE(operands.empty()) << label << ": no storage buffer read at all?";
    for (const std::string& operand : operands)
      EXPECT_TRUE(is_buffer_member(operand)) << label << ": indexed at run time:" << operand;
  }
}

class KernelIndexing : public ::testing::TestWithParam<const char*> {};

TEST_P(KernelIndexing, FloatKernelsIndexOnlyBuffersAtRunTime) {
  expect_only_buffers_indexed_at_run_time<float>(GetParam());
}

TEST_P(KernelIndexing, DoubleKernelsIndexOnlyBuffersAtRunTime) {
  expect_only_buffers_indexed_at_run_time<double>(GetParam());
}

INSTANTIATE_TEST_SUITE_P(Registry, KernelIndexing,
                         ::testing::Values("m7", "m8", "m12", "fcc6", "tricubic", "cart7"),
                         [](const auto& p) { return std::string(p.param); });

// The emitted text as it stands alone (TableStorage::constant): the cell's tables are `const`
// arrays indexed at run time, and they are the only other operands.
TEST(KernelIndexingCheck, ConstTablesAreTheOnlyOtherOperands) {
  const SplineFilter f = SplineFilter::parse("m7");
  const LatticeVolume<float> volume(f.lattice(), {6, 6, 6}, 1.0, {0, 0, 0});
  const GlSpline<float> spline(volume, f, registry_glsl("m7", false), TableStorage::constant);
  int tables = 0;
  for (const std::string& operand : indirect_operands(spline.kernel_source(2), "m7_const")) {
    if (is_buffer_member(operand)) continue;
    EXPECT_NE(operand.find("Constant:"), std::string::npos) << operand;
    ++tables;
  }
  EXPECT_GT(tables, 0);
}

// The check itself: an array indexed by a loop variable is found.
TEST(KernelIndexingCheck, FindsAPrivateArrayIndexedAtRunTime) {
  const std::string source = R"(#version 430
layout(local_size_x = 1) in;
layout(std430, binding = 0) buffer Out { float out_values[]; };
void main() {
  float a[4] = float[4](1.0, 2.0, 3.0, 4.0);
  int i = int(gl_GlobalInvocationID.x);
  out_values[i] = a[i % 4];
}
)";
  const std::vector<std::string> operands = indirect_operands(source, "check");
  ASSERT_EQ(operands.size(), 2u);
  int private_arrays = 0;
  for (const std::string& operand : operands) private_arrays += is_buffer_member(operand) ? 0 : 1;
  EXPECT_EQ(private_arrays, 1);
}

}  // namespace
}  // namespace boxgen::runtime::gl
