// The checks of a NIfTI file that nifticlib does not make, on the bytes as the file holds them
// (docs/errors.md "NIfTI files"). nifticlib repairs what it finds wrong instead of refusing it: a
// NaN or infinite float sample becomes 0, a spacing of 0, -2 or NaN becomes 1, a vox_offset below
// the header's end reads the data from inside it, a NaN quaternion becomes the identity and a
// header without NIfTI's magic is read as ANALYZE 7.5. Each of these would be a silently wrong
// volume, so the header is read here as raw bytes and checked before nifticlib sees it, and the
// data is read here too, without nifticlib's repairs.
#pragma once
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <string>

namespace boxgen::runtime::nifti_header {

// The fields the checks need, as the file holds them (byte order already made native).
struct RawHeader {
  int version = 0;           // 1 or 2
  bool single_file = false;  // magic n+1 / n+2 (header and data in one file); ni1 / ni2: a pair
  bool swapped = false;      // the file's byte order is not this machine's
  double vox_offset = 0;
  double pixdim[8] = {};
  double scl_slope = 0, scl_inter = 0;
  int qform_code = 0, sform_code = 0;
  double quatern[3] = {}, qoffset[3] = {};
  double srow[3][4] = {};
};

// Reads and checks the header of `path` (.nii or .nii.gz): its size field (348 or 540, in either
// byte order), its magic, its vox_offset (a whole number of bytes at or after the header's end,
// 352 or 544 in a single file), the spacing the world affine uses (pixdim[1..3] positive and
// finite when the qform or no transform is used), the qform's quaternion (finite, b^2 + c^2 + d^2
// at most 1) and offsets, the sform's rows (finite) and the scale slope and intercept (finite).
// Returns the fields, and in `why` the reason the header is refused (empty when it passes).
RawHeader read_raw_header(const std::filesystem::path& path, std::string& why);

// Why the voxel-to-world affine `m` (rows of a 3 x 4 matrix) is not axis-aligned, or empty. An
// off-diagonal entry counts when it exceeds 1e-6 of its column's length (the rounding of a
// quaternion stored in float), so a large spacing on one axis never hides a shear of another.
std::string oblique_entry(const double (&m)[3][4], const char* which);

// Reads `bytes` bytes of voxel data from `file` (.nii, .nii.gz or .img) at `offset`, swapping each
// value of `value_bytes` bytes when `swap`, into `out`. Returns the reason on failure (a file cut
// short), else empty. NaN and infinite samples are kept as they are (checked by the caller).
std::string read_data(const std::string& file, std::int64_t offset, std::size_t bytes, bool swap,
                      int value_bytes, void* out);

}  // namespace boxgen::runtime::nifti_header
