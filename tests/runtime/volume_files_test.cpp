// Volume files as scanners write them: NRRDs of every scalar type read back exactly, anisotropic
// and flipped Cartesian grids, NIfTI-1/2 files the test writes through nifticlib (geometry from
// sform or qform, scale slope, the refusals), the shipped MRI template when mricron-data is
// installed, and the anisotropic reconstruction in world coordinates.
#include "runtime/nifti_io.h"
#include "runtime/prefilter.h"
#include "runtime/reconstruction.h"
#include "runtime/resample.h"
#include "runtime/sample_encoding.h"
#include "runtime/volume_output.h"
#include "tests/support/scratch_directory.h"

#include <gtest/gtest.h>
#include <nifti2_io.h>
#include <teem/nrrd.h>
#include <zlib.h>

#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>
#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace boxgen::runtime {
namespace {

namespace fs = std::filesystem;

class VolumeFiles : public test::ScratchDirectoryTest {
 protected:
  VolumeFiles() : ScratchDirectoryTest("boxgen-volume-files") {}
  fs::path file(const std::string& name) const { return dir_ / name; }
};

// A 3-D NRRD of `type` holding `values` (x fastest) with the given space directions, written by
// Teem itself (the library the files of users come from).
template <class S>
void write_teem_nrrd(const fs::path& path, int type, const std::vector<S>& values,
                     const std::size_t (&sizes)[3], const double (&steps)[3],
                     const double (&origin)[3]) {
  Nrrd* nrrd = nrrdNew();
  ASSERT_EQ(nrrdWrap_nva(nrrd, const_cast<S*>(values.data()), type, 3, sizes), 0);
  ASSERT_EQ(nrrdSpaceSet(nrrd, nrrdSpace3DRightHanded), 0);
  for (int a = 0; a < 3; ++a)
    for (int b = 0; b < 3; ++b) nrrd->axis[a].spaceDirection[b] = a == b ? steps[a] : 0.0;
  double o[3] = {origin[0], origin[1], origin[2]};
  ASSERT_EQ(nrrdSpaceOriginSet(nrrd, o), 0);
  ASSERT_EQ(nrrdSave(path.c_str(), nrrd, nullptr), 0);
  nrrdNix(nrrd);
}

// Every value of S's range ends, the middle, and a few in between: read back exactly in double
// (and in float for types of at most 16 bits, which float holds exactly).
template <class S>
void check_type_round_trip(const fs::path& path, int teem_type, const char* name) {
  const S lo = std::numeric_limits<S>::lowest(), hi = std::numeric_limits<S>::max();
  std::vector<S> values = {lo,
                           hi,
                           S{0},
                           S{1},
                           static_cast<S>(hi / 3),
                           static_cast<S>(lo / 7),
                           static_cast<S>(hi - 1),
                           static_cast<S>(lo + 1)};
  write_teem_nrrd(path, teem_type, values, {2, 2, 2}, {1, 1, 1}, {0, 0, 0});
  SourceSamples source;
  const LatticeVolume<double> v = read_lattice_nrrd<double>(path, {}, &source);
  EXPECT_EQ(source.type, name);
  EXPECT_EQ(source.min, static_cast<double>(lo)) << name;
  EXPECT_EQ(source.max, static_cast<double>(hi)) << name;
  ASSERT_EQ(v.sample_count(), values.size());
  for (std::size_t i = 0; i < values.size(); ++i)
    EXPECT_EQ(v.samples()[i], static_cast<double>(values[i])) << name << " sample " << i;
  if constexpr (sizeof(S) <= 2) {
    const LatticeVolume<float> f = read_lattice_nrrd<float>(path);
    for (std::size_t i = 0; i < values.size(); ++i)
      EXPECT_EQ(f.samples()[i], static_cast<float>(values[i])) << name << " sample " << i;
  }
}

TEST_F(VolumeFiles, EveryNrrdScalarTypeReadsBackExactly) {
  check_type_round_trip<std::int8_t>(file("i8.nrrd"), nrrdTypeChar, "int8");
  check_type_round_trip<std::uint8_t>(file("u8.nrrd"), nrrdTypeUChar, "uint8");
  check_type_round_trip<std::int16_t>(file("i16.nrrd"), nrrdTypeShort, "int16");
  check_type_round_trip<std::uint16_t>(file("u16.nrrd"), nrrdTypeUShort, "uint16");
  check_type_round_trip<std::int32_t>(file("i32.nrrd"), nrrdTypeInt, "int32");
  check_type_round_trip<std::uint32_t>(file("u32.nrrd"), nrrdTypeUInt, "uint32");
  check_type_round_trip<float>(file("f.nrrd"), nrrdTypeFloat, "float");
  check_type_round_trip<double>(file("d.nrrd"), nrrdTypeDouble, "double");
}

TEST_F(VolumeFiles, SixtyFourBitIntegersAreRefusedInOneLine) {
  const std::vector<std::int64_t> values(8, 5);
  write_teem_nrrd(file("l.nrrd"), nrrdTypeLLong, values, {2, 2, 2}, {1, 1, 1}, {0, 0, 0});
  try {
    (void)read_lattice_nrrd<double>(file("l.nrrd"));
    FAIL() << "a 64-bit integer NRRD was read";
  } catch (const NrrdError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("not supported"), std::string::npos) << what;
    EXPECT_EQ(what.find('\n'), std::string::npos);
  }
}

// Voxel (i, j, k) of a grid with steps s and origin o holds 100 i + 10 j + k: after reading, the
// sample at every world point must still be the file's value there.
TEST_F(VolumeFiles, AnisotropicAndFlippedNrrdAxesKeepEveryWorldPoint) {
  const std::size_t n[3] = {3, 4, 2};
  std::vector<std::int16_t> values;
  for (std::size_t k = 0; k < n[2]; ++k)
    for (std::size_t j = 0; j < n[1]; ++j)
      for (std::size_t i = 0; i < n[0]; ++i)
        values.push_back(static_cast<std::int16_t>(100 * i + 10 * j + k));
  const double steps[3] = {0.5, -0.75, 1.25}, origin[3] = {10, 20, 30};
  write_teem_nrrd(file("a.nrrd"), nrrdTypeShort, values, n, steps, origin);
  const LatticeVolume<double> v = read_lattice_nrrd<double>(file("a.nrrd"));
  EXPECT_EQ(v.axis_spacing(), (Vec3{0.5, 0.75, 1.25}));
  EXPECT_FALSE(v.is_isotropic());
  EXPECT_THROW((void)v.spacing(), std::logic_error);
  for (int k = 0; k < 2; ++k)
    for (int j = 0; j < 4; ++j)
      for (int i = 0; i < 3; ++i) {
        const Vec3 world{origin[0] + steps[0] * i, origin[1] + steps[1] * j,
                         origin[2] + steps[2] * k};
        const Vec3 lattice = v.to_lattice(world);
        const LatticePoint p{std::llround(lattice[0]), std::llround(lattice[1]),
                             std::llround(lattice[2])};
        EXPECT_EQ(v.value(p), 100 * i + 10 * j + k) << i << " " << j << " " << k;
      }
  // Written back, an anisotropic volume keeps its spacings.
  write_lattice_nrrd(file("b.nrrd"), v);
  const LatticeVolume<double> w = read_lattice_nrrd<double>(file("b.nrrd"));
  EXPECT_EQ(w.axis_spacing(), v.axis_spacing());
  EXPECT_EQ(w.origin(), v.origin());
}

TEST_F(VolumeFiles, OnlyCartesianVolumesMayBeAnisotropic) {
  EXPECT_THROW(LatticeVolume<double>(CosetLattice::bcc(), {2, 2, 2}, Vec3{1, 1, 2}, {0, 0, 0},
                                     std::vector<double>(16)),
               std::invalid_argument);
  EXPECT_NO_THROW(LatticeVolume<double>(CosetLattice::cartesian(), {2, 2, 2}, Vec3{1, 1, 2},
                                        {0, 0, 0}, std::vector<double>(8)));
}

// The tricubic after Q^II reproduces polynomials of degree < 4 (approximation order 4): on an
// anisotropic grid, in world coordinates, value and gradient of a cubic in x, y, z.
TEST_F(VolumeFiles, AnisotropicTricubicReproducesACubicInWorldCoordinates) {
  const auto f = [](const Vec3& p) {
    return 1 + 0.5 * p[0] - p[1] + 0.25 * p[2] + p[0] * p[1] - 0.3 * p[2] * p[2] +
           0.1 * p[0] * p[0] * p[0] + 0.2 * p[0] * p[1] * p[2];
  };
  const Sizes n{12, 10, 9};
  const Vec3 h{0.5, 0.75, 1.25}, o{-2, 1, 3};
  std::vector<double> samples;
  for (int k = 0; k < n[2]; ++k)
    for (int j = 0; j < n[1]; ++j)
      for (int i = 0; i < n[0]; ++i)
        samples.push_back(f({o[0] + h[0] * i, o[1] + h[1] * j, o[2] + h[2] * k}));
  const SplineFilter tricubic = SplineFilter::parse("tricubic");
  LatticeVolume<double> v(CosetLattice::cartesian(), n, h, o, std::move(samples));
  v = prefilter(v, tricubic.prefilter(PrefilterChoice::Q2));
  const Reconstructor<double> spline(v, tricubic);
  const Box box = default_box(v, tricubic);
  for (const Vec3& t : {Vec3{0.1, 0.2, 0.3}, Vec3{0.5, 0.5, 0.5}, Vec3{0.9, 0.05, 0.7}}) {
    Vec3 p;
    for (int a = 0; a < 3; ++a) p[a] = box.min[a] + t[a] * (box.max[a] - box.min[a]);
    Vec3 gradient;
    const double value = spline.value(p, &gradient);
    EXPECT_NEAR(value, f(p), 1e-11);
    const double e = 1e-6;  // the exact gradient, by the symmetric difference of a cubic
    for (int a = 0; a < 3; ++a) {
      Vec3 plus = p, minus = p;
      plus[a] += e;
      minus[a] -= e;
      EXPECT_NEAR(gradient[a], (f(plus) - f(minus)) / (2 * e), 1e-6) << "axis " << a;
    }
  }
}

// A symmetric, normalised kernel keeps a linear function: after the Gaussian low-pass (sigma 1,
// radius 3) each remaining sample of an anisotropic grid still holds the function at its point,
// and the volume lost 3 samples per side (origin moved by 3 spacings).
TEST_F(VolumeFiles, GaussianLowPassKeepsALinearFunctionAndShrinks) {
  const auto f = [](const Vec3& p) { return 2 * p[0] + 3 * p[1] - p[2] + 1; };
  const Vec3 h{1, 0.5, 2}, o{-1, 2, 3};
  std::vector<double> samples;
  for (int k = 0; k < 12; ++k)
    for (int j = 0; j < 12; ++j)
      for (int i = 0; i < 12; ++i)
        samples.push_back(f({o[0] + h[0] * i, o[1] + h[1] * j, o[2] + h[2] * k}));
  const LatticeVolume<double> v(CosetLattice::cartesian(), {12, 12, 12}, h, o, std::move(samples));
  const LatticeVolume<double> s = gaussian_smooth(v, 1.0);
  EXPECT_EQ(s.sizes(), (Sizes{6, 6, 6}));
  EXPECT_EQ(s.origin(), (Vec3{o[0] + 3 * h[0], o[1] + 3 * h[1], o[2] + 3 * h[2]}));
  for (int k = 0; k < 6; ++k)
    for (int j = 0; j < 6; ++j)
      for (int i = 0; i < 6; ++i)
        EXPECT_NEAR(s(0, i, j, k), f(s.sample_position(0, i, j, k)), 1e-12);
  EXPECT_THROW((void)gaussian_smooth(v, 2.0), std::invalid_argument);  // radius 6: nothing left
  EXPECT_THROW((void)gaussian_smooth(v, 0.0), std::invalid_argument);
}

// A NIfTI file written through nifticlib: `dims` voxels of `datatype` holding 0, 1, 2, ... (in the
// type), with the given sform (if sform_code > 0) and qform, in NIfTI-1 or NIfTI-2.
struct NiftiSpec {
  int datatype = DT_INT16;
  std::int64_t dims[3] = {3, 4, 2};
  std::int64_t frames = 1;
  int sform_code = 1;
  double sform[3][4] = {{0.5, 0, 0, -10}, {0, 0.75, 0, 20}, {0, 0, 1.25, 5}};
  int qform_code = 0;
  double quatern[3] = {0, 0, 0}, qoffset[3] = {0, 0, 0}, qfac = 1;
  double pixdim[3] = {1, 1, 1};
  double slope = 0, inter = 0;
  int nifti_type = NIFTI_FTYPE_NIFTI1_1;
};

void write_nifti(const fs::path& path, const NiftiSpec& s) {
  const std::int64_t dims[8] = {
      s.frames > 1 ? 4 : 3, s.dims[0], s.dims[1], s.dims[2], s.frames, 1, 1, 1};
  nifti_image* nim = nifti_make_new_nim(dims, s.datatype, 1);
  ASSERT_NE(nim, nullptr);
  for (std::int64_t i = 0; i < static_cast<std::int64_t>(nim->nvox); ++i) {
    if (s.datatype == DT_INT16)
      static_cast<std::int16_t*>(nim->data)[i] = static_cast<std::int16_t>(i);
    if (s.datatype == DT_UINT8)
      static_cast<std::uint8_t*>(nim->data)[i] = static_cast<std::uint8_t>(i);
    if (s.datatype == DT_FLOAT32) static_cast<float*>(nim->data)[i] = static_cast<float>(i);
  }
  nim->sform_code = s.sform_code;
  for (int r = 0; r < 4; ++r)
    for (int c = 0; c < 4; ++c) nim->sto_xyz.m[r][c] = r < 3 ? s.sform[r][c] : (c == 3 ? 1 : 0);
  nim->qform_code = s.qform_code;
  nim->quatern_b = s.quatern[0];
  nim->quatern_c = s.quatern[1];
  nim->quatern_d = s.quatern[2];
  nim->qoffset_x = s.qoffset[0];
  nim->qoffset_y = s.qoffset[1];
  nim->qoffset_z = s.qoffset[2];
  nim->qfac = s.qfac;
  nim->dx = nim->pixdim[1] = s.pixdim[0];
  nim->dy = nim->pixdim[2] = s.pixdim[1];
  nim->dz = nim->pixdim[3] = s.pixdim[2];
  nim->scl_slope = s.slope;
  nim->scl_inter = s.inter;
  nim->nifti_type = s.nifti_type;
  ASSERT_EQ(nifti_set_filenames(nim, path.c_str(), 0, 1), 0);
  nifti_image_write(nim);
  nifti_image_free(nim);
}

// Voxel (i, j, k) holds i + 3 j + 12 k (as write_nifti fills a 3 x 4 x 2 grid): check it at the
// world point the affine (steps, origin: diagonal) gives.
void expect_voxels_at_world_points(const LatticeVolume<double>& v, const double (&steps)[3],
                                   const double (&origin)[3], double slope = 1, double inter = 0) {
  for (int k = 0; k < 2; ++k)
    for (int j = 0; j < 4; ++j)
      for (int i = 0; i < 3; ++i) {
        const Vec3 world{origin[0] + steps[0] * i, origin[1] + steps[1] * j,
                         origin[2] + steps[2] * k};
        const Vec3 lattice = v.to_lattice(world);
        const LatticePoint p{std::llround(lattice[0]), std::llround(lattice[1]),
                             std::llround(lattice[2])};
        for (int a = 0; a < 3; ++a) EXPECT_NEAR(lattice[a], static_cast<double>(p[a]), 1e-9);
        EXPECT_EQ(v.value(p), slope * (i + 3 * j + 12 * k) + inter) << i << " " << j << " " << k;
      }
}

TEST_F(VolumeFiles, NiftiSformGivesTheWorldGeometry) {
  for (const char* name : {"s.nii", "s.nii.gz"}) {
    write_nifti(file(name), NiftiSpec{});
    SourceSamples source;
    const LatticeVolume<double> v = read_volume_file<double>(file(name), {}, &source);
    EXPECT_EQ(v.lattice(), CosetLattice::cartesian());
    EXPECT_EQ(v.sizes(), (Sizes{3, 4, 2}));
    EXPECT_EQ(v.axis_spacing(), (Vec3{0.5, 0.75, 1.25}));
    EXPECT_EQ(v.origin(), (Vec3{-10, 20, 5}));
    EXPECT_EQ(source.type, "int16");
    EXPECT_EQ(source.min, 0);
    EXPECT_EQ(source.max, 23);
    expect_voxels_at_world_points(v, {0.5, 0.75, 1.25}, {-10, 20, 5});
  }
}

TEST_F(VolumeFiles, NiftiTwoAndNegativeSformAxesKeepEveryVoxelAtItsWorldPoint) {
  NiftiSpec s;
  s.nifti_type = NIFTI_FTYPE_NIFTI2_1;
  s.sform[0][0] = -2;  // radiological x: the world x decreases with i
  s.sform[2][2] = -0.5;
  write_nifti(file("n2.nii.gz"), s);
  const LatticeVolume<double> v = read_nifti<double>(file("n2.nii.gz"));
  EXPECT_EQ(v.axis_spacing(), (Vec3{2, 0.75, 0.5}));
  EXPECT_EQ(v.origin(), (Vec3{-10 - 2 * 2, 20, 5 - 0.5}));
  expect_voxels_at_world_points(v, {-2, 0.75, -0.5}, {-10, 20, 5});
}

TEST_F(VolumeFiles, NiftiQformIsUsedWhenTheSformCodeIsZero) {
  NiftiSpec s;
  s.sform_code = 0;
  s.qform_code = 1;
  s.qoffset[0] = 7;
  s.qoffset[1] = -3;
  s.qoffset[2] = 2;
  s.pixdim[0] = 0.5;
  s.pixdim[1] = 2;
  s.pixdim[2] = 1.5;
  s.qfac = -1;  // the third axis reversed
  write_nifti(file("q.nii"), s);
  const LatticeVolume<double> v = read_nifti<double>(file("q.nii"));
  expect_voxels_at_world_points(v, {0.5, 2, -1.5}, {7, -3, 2});
}

TEST_F(VolumeFiles, NiftiScaleSlopeAndInterceptApply) {
  NiftiSpec s;
  s.datatype = DT_UINT8;
  s.slope = 0.5;
  s.inter = -3;
  write_nifti(file("scaled.nii.gz"), s);
  SourceSamples source;
  const LatticeVolume<double> v = read_nifti<double>(file("scaled.nii.gz"), {}, &source);
  EXPECT_EQ(source.type, "uint8");
  EXPECT_EQ(source.min, -3);
  EXPECT_EQ(source.max, 0.5 * 23 - 3);
  expect_voxels_at_world_points(v, {0.5, 0.75, 1.25}, {-10, 20, 5}, 0.5, -3);
}

// Each refusal is one line naming the file and saying why.
void expect_refused(const fs::path& path, const std::string& why) {
  try {
    (void)read_volume_file<double>(path);
    ADD_FAILURE() << path << " was read";
  } catch (const NrrdError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find(why), std::string::npos) << what;
    EXPECT_NE(what.find(path.filename().string()), std::string::npos) << what;
    EXPECT_EQ(what.find('\n'), std::string::npos) << what;
  }
}

TEST_F(VolumeFiles, BadNiftiFilesAreRefusedInOneLine) {
  NiftiSpec oblique;
  oblique.sform[0][1] = 0.3;
  write_nifti(file("oblique.nii.gz"), oblique);
  expect_refused(file("oblique.nii.gz"), "oblique");

  NiftiSpec series;
  series.frames = 3;
  write_nifti(file("series.nii"), series);
  expect_refused(file("series.nii"), "time series");

  // A .nii.gz cut in the middle of its data.
  NiftiSpec big;
  big.dims[0] = big.dims[1] = big.dims[2] = 24;
  big.datatype = DT_FLOAT32;
  write_nifti(file("whole.nii.gz"), big);
  std::ifstream in(file("whole.nii.gz"), std::ios::binary);
  std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  std::ofstream(file("cut.nii.gz"), std::ios::binary)
      .write(bytes.data(), static_cast<std::streamsize>(bytes.size() / 2));
  expect_refused(file("cut.nii.gz"), "cut short");

  std::ofstream(file("text.nii")) << "not a NIfTI file\n";
  expect_refused(file("text.nii"), "not a valid NIfTI");
  expect_refused(file("absent.nii.gz"), "no such file");
}

// An MRI template Debian ships (mricron-data; the smaller of the two Fig. 10 candidates):
// 181 x 217 x 181 uint8 voxels of 1 mm, its sform (code 4, MNI) a pure shift, its qform code 0.
TEST_F(VolumeFiles, ShippedTemplateHasItsSformGeometry) {
  const fs::path path = "/usr/share/mricron/templates/ch2.nii.gz";
  if (!fs::exists(path)) GTEST_SKIP() << path << " is not installed (Debian mricron-data)";
  SourceSamples source;
  const LatticeVolume<float> v = read_nifti<float>(path, {}, &source);
  EXPECT_EQ(v.sizes(), (Sizes{181, 217, 181}));
  EXPECT_EQ(v.axis_spacing(), (Vec3{1, 1, 1}));
  EXPECT_EQ(v.origin(), (Vec3{-90, -125, -71}));
  EXPECT_EQ(source.type, "uint8");
  EXPECT_GE(source.min, 0);
  EXPECT_LE(source.max, 255);
  EXPECT_GT(source.max, source.min);
}

// encode_samples: integers round to nearest with ties to even (as NumPy's rint) and clamp beyond
// the type's range, counting; float32 keeps what float holds.
TEST_F(VolumeFiles, EncodedSamplesRoundTiesToEvenAndClampCounting) {
  const std::vector<double> values = {-0.5, 0.5, 1.5, 2.5, -1.5, 127.4, 127.6, -129, 1e9};
  const EncodedSamples i8 = encode_samples<double>(values, SampleType::Int8);
  ASSERT_EQ(i8.bytes.size(), values.size());
  std::vector<std::int8_t> got(values.size());
  std::memcpy(got.data(), i8.bytes.data(), got.size());
  EXPECT_EQ(got, (std::vector<std::int8_t>{0, 0, 2, 2, -2, 127, 127, -128, 127}));
  EXPECT_EQ(i8.clamped, 3u);  // 127.6, -129, 1e9
  const EncodedSamples f =
      encode_samples<double>(std::vector<double>{0.1, 1e300}, SampleType::Float32);
  float fl[2];
  std::memcpy(fl, f.bytes.data(), sizeof fl);
  EXPECT_EQ(fl[0], 0.1f);
  EXPECT_TRUE(std::isinf(fl[1]));
  EXPECT_EQ(f.clamped, 1u);
  EXPECT_EQ(parse_sample_type("float"), SampleType::Float32);
  EXPECT_EQ(parse_sample_type("uint16"), SampleType::UInt16);
  EXPECT_THROW(parse_sample_type("int64"), std::invalid_argument);
}

// write_volume_file by the name: NIfTI-1 written here reads back through read_nifti with the
// grid, spacing, origin and values (float32 by default, any --type), compressed or not; NRRD
// with another type reads back through the NRRD reader.
TEST_F(VolumeFiles, WrittenNiftiAndTypedNrrdReadBack) {
  std::vector<double> values(5 * 4 * 3);
  for (std::size_t i = 0; i < values.size(); ++i) values[i] = static_cast<double>(i) - 7.25;
  const LatticeVolume<double> v(CosetLattice::cartesian(), {5, 4, 3}, Vec3{0.9, 0.9, 3.0},
                                {-4, 5, 6.5}, std::vector<double>(values));
  struct Case {
    const char* name;
    std::optional<SampleType> type;
    const char* source_type;
  };
  for (const Case& c :
       {Case{"a.nii", std::nullopt, "float"}, Case{"a.nii.gz", std::nullopt, "float"},
        Case{"d.nii", SampleType::Float64, "double"}, Case{"i.nii.gz", SampleType::Int16, "int16"},
        Case{"u.nrrd", SampleType::Int32, "int32"}, Case{"f.NRRD", std::nullopt, "double"}}) {
    SCOPED_TRACE(c.name);
    const VolumeWrite w = write_volume_file(file(c.name), v, c.type);
    EXPECT_EQ(w.clamped, 0u);
    SourceSamples source;
    const LatticeVolume<double> back = read_volume_file<double>(file(c.name), {}, &source);
    EXPECT_EQ(source.type, c.source_type);
    EXPECT_EQ(back.sizes(), v.sizes());
    for (int a = 0; a < 3; ++a) {
      EXPECT_NEAR(back.axis_spacing()[a], v.axis_spacing()[a], 1e-6);
      EXPECT_NEAR(back.origin()[a], v.origin()[a], 1e-6);
    }
    for (std::size_t i = 0; i < values.size(); ++i) {
      const double expected = !c.type || !is_integer_type(*c.type)
                                  ? (std::string(c.source_type) == "float"
                                         ? static_cast<double>(static_cast<float>(values[i]))
                                         : values[i])
                                  : std::nearbyint(values[i]);
      ASSERT_EQ(back.samples()[i], expected) << i;
    }
  }
  // A volume tied to no patient: the sform with code 2 (aligned), the qform's code 0 (unknown),
  // as nibabel writes a new image (tests/python/test_output_frames.py compares with nibabel).
  nifti_image* nim = nifti_image_read(file("a.nii").c_str(), 0);
  ASSERT_NE(nim, nullptr);
  EXPECT_EQ(nim->sform_code, NIFTI_XFORM_ALIGNED_ANAT);
  EXPECT_EQ(nim->qform_code, NIFTI_XFORM_UNKNOWN);
  EXPECT_EQ(nim->datatype, DT_FLOAT32);
  nifti_image_free(nim);
}

// The world's anatomical frame goes into the file: a NRRD's space (read back by Teem and by the
// reader, which reports the same letters), a NIfTI's RAS world (an LPS world's x and y negated:
// the voxel at LPS (x, y, z) lies at RAS (-x, -y, z)); an unknown frame is refused, no file.
TEST_F(VolumeFiles, TheAnatomicalFrameIsWrittenAsTheNrrdSpaceAndAsNiftisRas) {
  const LatticeVolume<float> v(CosetLattice::cartesian(), {3, 2, 2}, Vec3{1.5, 2, 2.5}, {4, -5, 6},
                               std::vector<float>(12, 1.0f));
  const LatticeVolume<float> bcc(CosetLattice::bcc(), {2, 2, 2}, 1.0, {0, 0, 0});
  for (const auto& [frame, space] : {std::pair<std::string, int>{"", nrrdSpace3DRightHanded},
                                     {"RAS", nrrdSpaceRightAnteriorSuperior},
                                     {"LAS", nrrdSpaceLeftAnteriorSuperior},
                                     {"LPS", nrrdSpaceLeftPosteriorSuperior}}) {
    SCOPED_TRACE(frame);
    for (const bool lattice : {false, true}) {
      const fs::path path = file(lattice ? "bcc.nrrd" : "grid.nrrd");
      (void)write_volume_file(path, lattice ? bcc : v, SampleType::Int16, frame);
      Nrrd* nrrd = nrrdNew();
      ASSERT_EQ(nrrdLoad(nrrd, path.c_str(), nullptr), 0);
      EXPECT_EQ(nrrd->space, space);
      nrrdNuke(nrrd);
      SourceSamples source;
      (void)read_volume_file<float>(path, {}, &source);
      EXPECT_EQ(source.anatomical, frame);
    }
  }
  (void)write_volume_file(file("lps.nii"), v, std::nullopt, "LPS");
  nifti_image* nim = nifti_image_read(file("lps.nii").c_str(), 0);
  ASSERT_NE(nim, nullptr);
  // A patient's world: both codes 2 (aligned anatomical).
  EXPECT_EQ(nim->sform_code, NIFTI_XFORM_ALIGNED_ANAT);
  EXPECT_EQ(nim->qform_code, NIFTI_XFORM_ALIGNED_ANAT);
  const double want[3][4] = {{-1.5, 0, 0, -4}, {0, -2, 0, 5}, {0, 0, 2.5, 6}};
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 4; ++c) {
      EXPECT_EQ(nim->sto_xyz.m[r][c], want[r][c]) << r << c;
      EXPECT_NEAR(nim->qto_xyz.m[r][c], want[r][c], 1e-6) << r << c;
    }
  nifti_image_free(nim);
  EXPECT_THROW((void)write_volume_file(file("bad.nrrd"), v, std::nullopt, "XYZ"),
               std::invalid_argument);
  EXPECT_FALSE(fs::exists(file("bad.nrrd")));
}

// The codes of a read NIfTI (scanner, MNI, Talairach, ...) are what a NIfTI written from it
// claims: the qform's as they were, the sform's (or the qform's where the file had no sform, so
// that the exact affine keeps a code); a code NIfTI does not define becomes "aligned" (2). Files
// written by the test through nifticlib, read back through nifticlib.
TEST_F(VolumeFiles, NiftiCodesOfTheInputAreWrittenAgain) {
  struct Case {
    int qform, sform;  // the input's
    NiftiCodes read, written;
  };
  for (const Case& c :
       {Case{1, 4, {1, 4}, {1, 4}}, Case{0, 3, {0, 3}, {0, 3}}, Case{1, 0, {1, 0}, {1, 1}},
        Case{5, 1, {5, 1}, {5, 1}}, Case{2, 7, {2, 2}, {2, 2}}}) {
    SCOPED_TRACE(::testing::Message() << c.qform << " " << c.sform);
    NiftiSpec s;
    s.qform_code = c.qform;
    s.sform_code = c.sform;
    write_nifti(file("in.nii.gz"), s);
    SourceSamples source;
    const LatticeVolume<double> v = read_volume_file<double>(file("in.nii.gz"), {}, &source);
    EXPECT_EQ(source.nifti_codes, c.read);
    EXPECT_EQ(source.anatomical, "RAS");
    for (const bool grid : {false, true}) {
      const fs::path out = file(grid ? "grid.nii" : "volume.nii");
      if (grid) {
        const std::span<const double> x = v.samples();
        (void)write_grid_file(
            out,
            CartesianVolume<double>{
                v.sizes(), v.axis_spacing(), v.origin(), {x.begin(), x.end()}, std::nullopt},
            std::nullopt, source.anatomical, source.nifti_codes);
      } else {
        (void)write_volume_file(out, v, std::nullopt, source.anatomical, std::nullopt,
                                source.nifti_codes);
      }
      nifti_image* nim = nifti_image_read(out.c_str(), 0);
      ASSERT_NE(nim, nullptr);
      EXPECT_EQ(nim->qform_code, c.written.qform);
      EXPECT_EQ(nim->sform_code, c.written.sform);
      nifti_image_free(nim);
    }
  }
  // Without a NIfTI's codes: aligned (2) in the sform; in the qform only for a patient's world.
  EXPECT_EQ(nifti_output_codes("", {}), (NiftiCodes{0, 2}));
  EXPECT_EQ(nifti_output_codes("LPS", {}), (NiftiCodes{2, 2}));
  const std::vector<std::byte> bytes(2);
  for (const NiftiCodes& bad : {NiftiCodes{1, 0}, NiftiCodes{6, 2}, NiftiCodes{-1, 2}}) {
    EXPECT_THROW(write_nifti(file("bad.nii"), {1, 1, 2}, Affine::diagonal({1, 1, 1}, {0, 0, 0}),
                             {SampleType::UInt8, bytes, 0}, bad),
                 std::invalid_argument);
    EXPECT_FALSE(fs::exists(file("bad.nii")));
  }
}

TEST_F(VolumeFiles, OutputNamesChooseTheFormatOrAreRefused) {
  EXPECT_EQ(output_format("a/b.nrrd"), VolumeFormat::Nrrd);
  EXPECT_EQ(output_format("B.NII.GZ"), VolumeFormat::Nifti);
  EXPECT_EQ(output_format("c.nii"), VolumeFormat::Nifti);
  for (const char* bad : {"x.vol", "x", "x.nhdr", "x.hdr", "x.img", "x.dcm", "x.nii.bz2"})
    EXPECT_THROW(output_format(bad), NrrdError) << bad;
  const LatticeVolume<float> bcc(CosetLattice::bcc(), {2, 2, 2}, 1.0, {0, 0, 0});
  try {
    (void)write_volume_file(file("b.nii"), bcc);
    ADD_FAILURE() << "a BCC volume was written as NIfTI";
  } catch (const NrrdError& e) {
    EXPECT_NE(std::string(e.what()).find("Cartesian grids only"), std::string::npos) << e.what();
  }
  EXPECT_FALSE(fs::exists(file("b.nii")));
}

}  // namespace
}  // namespace boxgen::runtime
