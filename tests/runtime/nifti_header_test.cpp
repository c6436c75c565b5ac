// NIfTI files that lie: every file here is written byte by byte, as the
// NIfTI-1 standard lays it out (nifti1.h: 348 header bytes, 4 extension bytes, then the data), so
// the reader is tested against the bytes and not against nifticlib's own writer. nifticlib repairs
// such headers silently (NaN samples become 0, a spacing of 0, -2 or NaN becomes 1, a vox_offset
// below 352 reads the extension bytes as voxel (0,0,0), a NaN quaternion becomes the identity, a
// bad magic is read as ANALYZE); each must be refused in one line, and the good files next to them
// must read exactly.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <limits>
#include <string>
#include <vector>

#include "runtime/nifti_io.h"
#include "runtime/nrrd_io.h"
#include "tests/support/scratch_directory.h"

namespace boxgen::runtime {
namespace {

namespace fs = std::filesystem;

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr double kInf = std::numeric_limits<double>::infinity();

// The header fields the tests vary; the rest of the 348 bytes are zero.
struct Header {
  std::int16_t dims[3] = {3, 2, 2};
  std::int16_t datatype = 16;  // DT_FLOAT32
  std::int16_t bitpix = 32;
  float pixdim[4] = {1, 0.5, 0.75, 1.25};  // qfac, then the spacing
  float vox_offset = 352;
  float slope = 1, inter = 0;
  std::int16_t qform_code = 0, sform_code = 1;
  float quatern[3] = {0, 0, 0}, qoffset[3] = {0, 0, 0};
  float srow[3][4] = {{0.5, 0, 0, -10}, {0, 0.75, 0, 20}, {0, 0, 1.25, 5}};
  char magic[4] = {'n', '+', '1', '\0'};
  bool big_endian = false;
};

// The value at `offset` in the file's byte order.
template <class V>
void put(std::string& bytes, std::size_t offset, V value, bool big_endian) {
  char raw[sizeof(V)];
  std::memcpy(raw, &value, sizeof(V));
  if (big_endian)
    for (std::size_t i = 0; i < sizeof(V) / 2; ++i) std::swap(raw[i], raw[sizeof(V) - 1 - i]);
  if (bytes.size() < offset + sizeof(V)) bytes.resize(offset + sizeof(V), '\0');
  std::memcpy(&bytes[offset], raw, sizeof(V));
}

// A single-file NIfTI-1: the header, 4 zero extension bytes, then `samples` (float32 or float64
// as the header says) at byte `data_at`.
template <class S>
std::string nifti1(const Header& h, const std::vector<S>& samples, std::size_t data_at = 352) {
  std::string b(352, '\0');
  const bool be = h.big_endian;
  put<std::int32_t>(b, 0, 348, be);
  put<std::int16_t>(b, 40, 3, be);
  for (int a = 0; a < 3; ++a) put<std::int16_t>(b, 42 + 2 * a, h.dims[a], be);
  for (int a = 3; a < 7; ++a) put<std::int16_t>(b, 42 + 2 * a, 1, be);
  put<std::int16_t>(b, 70, h.datatype, be);
  put<std::int16_t>(b, 72, h.bitpix, be);
  for (int i = 0; i < 4; ++i) put<float>(b, 76 + 4 * i, h.pixdim[i], be);
  put<float>(b, 108, h.vox_offset, be);
  put<float>(b, 112, h.slope, be);
  put<float>(b, 116, h.inter, be);
  put<std::int16_t>(b, 252, h.qform_code, be);
  put<std::int16_t>(b, 254, h.sform_code, be);
  for (int i = 0; i < 3; ++i) put<float>(b, 256 + 4 * i, h.quatern[i], be);
  for (int i = 0; i < 3; ++i) put<float>(b, 268 + 4 * i, h.qoffset[i], be);
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 4; ++c) put<float>(b, 280 + 16 * r + 4 * c, h.srow[r][c], be);
  std::memcpy(&b[344], h.magic, 4);
  b.resize(std::max(b.size(), data_at), '\0');
  for (std::size_t i = 0; i < samples.size(); ++i)
    put<S>(b, data_at + i * sizeof(S), samples[i], be);
  return b;
}

// 12 samples 1, 2, ..., 12 (voxel (i, j, k) holds 1 + i + 3 j + 6 k).
std::vector<float> counting() {
  std::vector<float> v(12);
  for (int i = 0; i < 12; ++i) v[static_cast<std::size_t>(i)] = static_cast<float>(i + 1);
  return v;
}

class NiftiHeader : public test::ScratchDirectoryTest {
 protected:
  NiftiHeader() : ScratchDirectoryTest("boxgen-nifti-header") {}
  fs::path write(const std::string& name, const std::string& bytes) const {
    const fs::path path = dir_ / name;
    std::ofstream(path, std::ios::binary)
        .write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
    return path;
  }
  // The one-line refusal of reading `bytes` as a .nii, which must contain `why`.
  void expect_refused(const std::string& name, const std::string& bytes, const std::string& why,
                      bool allow_non_finite = false) const {
    const fs::path path = write(name, bytes);
    NrrdReadLimits limits;
    limits.allow_non_finite = allow_non_finite;
    try {
      (void)read_volume_file<double>(path, limits);
      ADD_FAILURE() << name << " was read";
    } catch (const NrrdError& e) {
      const std::string what = e.what();
      EXPECT_NE(what.find("cannot read NIfTI volume '" + path.string() + "': "), std::string::npos)
          << what;
      EXPECT_NE(what.find(why), std::string::npos) << name << ": " << what;
      EXPECT_EQ(what.find('\n'), std::string::npos) << what;
    }
  }
  // Reads `bytes` and checks voxel (i, j, k) = 1 + i + 3 j + 6 k at spacing (0.5, 0.75, 1.25).
  void expect_counting(const std::string& name, const std::string& bytes) const {
    const LatticeVolume<double> v = read_volume_file<double>(write(name, bytes));
    ASSERT_EQ(v.sizes(), (Sizes{3, 2, 2})) << name;
    EXPECT_EQ(v.axis_spacing(), (Vec3{0.5, 0.75, 1.25})) << name;
    for (int k = 0; k < 2; ++k)
      for (int j = 0; j < 2; ++j)
        for (int i = 0; i < 3; ++i)
          EXPECT_EQ(v.value({i, j, k}), 1 + i + 3 * j + 6 * k) << name << " " << i << j << k;
  }
};

TEST_F(NiftiHeader, WellFormedFilesReadExactlyInBothByteOrders) {
  expect_counting("little.nii", nifti1(Header{}, counting()));
  Header be;
  be.big_endian = true;
  expect_counting("big.nii", nifti1(be, counting()));
  Header later;  // data further on, as vox_offset says
  later.vox_offset = 400;
  expect_counting("later.nii", nifti1(later, counting(), 400));
  Header q;  // the qform, with its spacing from pixdim
  q.sform_code = 0;
  q.qform_code = 1;
  expect_counting("qform.nii", nifti1(q, counting()));
  Header none;  // neither: pixdim alone
  none.sform_code = 0;
  expect_counting("none.nii", nifti1(none, counting()));
}

// Item 4: nifticlib's loader zeroes "bad floats"; the same data in NRRD is refused.
TEST_F(NiftiHeader, NonFiniteSamplesAreRefusedOrKept) {
  for (const double bad : {kNaN, kInf, -kInf}) {
    std::vector<float> f = counting();
    f[4] = static_cast<float>(bad);
    expect_refused("f32.nii", nifti1(Header{}, f), "non-finite samples are refused");
    Header h64;
    h64.datatype = 64;  // DT_FLOAT64
    h64.bitpix = 64;
    std::vector<double> d(12, 1.0);
    d[4] = bad;
    expect_refused("f64.nii", nifti1(h64, d), "non-finite samples are refused");
    // Allowed, the sample is what the file holds, never 0.
    NrrdReadLimits allow;
    allow.allow_non_finite = true;
    for (const auto& path :
         {write("f32.nii", nifti1(Header{}, f)), write("f64.nii", nifti1(h64, d))}) {
      const LatticeVolume<double> v = read_volume_file<double>(path, allow);
      const double got = v.value({1, 1, 0});
      if (std::isnan(bad))
        EXPECT_TRUE(std::isnan(got)) << got;
      else
        EXPECT_EQ(got, bad);
    }
  }
}

// Item 5: a spacing of 0, -2 or NaN read as 1.
TEST_F(NiftiHeader, BadSpacingIsRefused) {
  for (const float bad : {0.0F, -2.0F, static_cast<float>(kNaN), static_cast<float>(kInf)}) {
    Header q;
    q.sform_code = 0;
    q.qform_code = 1;
    q.pixdim[2] = bad;
    expect_refused("q.nii", nifti1(q, counting()), "pixdim[2]");
    Header none;
    none.sform_code = 0;
    none.pixdim[1] = bad;
    expect_refused("none.nii", nifti1(none, counting()), "pixdim[1]");
  }
}

// Item 6: a vox_offset below 352 read the data from byte 348, so the extension bytes became
// voxel (0,0,0).
TEST_F(NiftiHeader, VoxOffsetInsideTheHeaderIsRefused) {
  for (const float bad : {0.0F, -352.0F, static_cast<float>(kNaN), 100.0F, 348.0F, 351.0F}) {
    Header h;
    h.vox_offset = bad;
    expect_refused("offset.nii", nifti1(h, counting()), "vox_offset");
  }
  Header half;
  half.vox_offset = 352.5F;
  expect_refused("half.nii", nifti1(half, counting()), "not a whole number of bytes");
}

// Item 7: the tolerance was relative to the largest diagonal entry, so a spacing of 1e6 on x hid
// a shear of 0.5 on y.
TEST_F(NiftiHeader, ShearBesideAHugeSpacingIsRefused) {
  Header h;
  h.srow[0][0] = 1e6F;
  h.srow[1][2] = 0.5F;  // srow_y = (0, 0.75, 0.5): the z axis leans along y
  expect_refused("shear.nii", nifti1(h, counting()), "oblique");
  Header small;  // a shear a float quaternion's rounding could not make, on a unit axis
  small.srow[1][0] = 1e-4F;
  expect_refused("small.nii", nifti1(small, counting()), "entry (1, 0)");
}

// Item 8: a NaN quaternion read as the identity, and a bad magic as ANALYZE 7.5; both exit 0.
TEST_F(NiftiHeader, BadQuaternionAndMagicAreRefused) {
  for (int i = 0; i < 3; ++i) {
    Header q;
    q.sform_code = 0;
    q.qform_code = 1;
    q.quatern[i] = static_cast<float>(kNaN);
    expect_refused("nanq.nii", nifti1(q, counting()), "quaternion");
  }
  Header longq;
  longq.sform_code = 0;
  longq.qform_code = 1;
  longq.quatern[0] = 2;
  expect_refused("longq.nii", nifti1(longq, counting()), "longer than 1");
  Header offset;
  offset.sform_code = 0;
  offset.qform_code = 1;
  offset.qoffset[1] = static_cast<float>(kInf);
  expect_refused("qoffset.nii", nifti1(offset, counting()), "qform offset y");
  Header srow;
  srow.srow[2][3] = static_cast<float>(kNaN);
  expect_refused("srow.nii", nifti1(srow, counting()), "sform row z");
  Header slope;
  slope.slope = static_cast<float>(kNaN);
  expect_refused("slope.nii", nifti1(slope, counting()), "scale slope");
  for (const char* magic : {"xyz", "n+2", "\x1b[3"}) {
    Header m;
    std::memcpy(m.magic, magic, 4);
    expect_refused("magic.nii", nifti1(m, counting()), "its magic");
  }
}

}  // namespace
}  // namespace boxgen::runtime
