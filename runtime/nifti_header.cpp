#include "runtime/nifti_header.h"

#include <fmt/format.h>
#include <nifti2_io.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <vector>

#include "runtime/nrrd_checks.h"

namespace boxgen::runtime::nifti_header {

namespace {

static_assert(sizeof(nifti_1_header) == 348 && sizeof(nifti_2_header) == 540,
              "nifticlib's header structs must be the files' layouts");

// An open znz file, closed when it goes.
struct Znz {
  znzFile file = nullptr;
  explicit Znz(const std::string& path)
      : file(znzopen(path.c_str(), "rb", nifti_is_gzfile(path.c_str()))) {}
  ~Znz() {
    if (!znz_isnull(file)) znzclose(file);
  }
  Znz(const Znz&) = delete;
  Znz& operator=(const Znz&) = delete;
};

std::int32_t swapped_int(std::int32_t v) {
  nifti_swap_4bytes(1, &v);
  return v;
}

std::string magic_text(const char* magic) {
  std::string out;
  for (int i = 0; i < 4 && magic[i] != '\0'; ++i) out += magic[i];
  return "'" + nrrd_checks::printable(out) + "'";
}

template <class H>
void copy_fields(const H& h, RawHeader& r) {
  r.vox_offset = static_cast<double>(h.vox_offset);
  for (int i = 0; i < 8; ++i) r.pixdim[i] = static_cast<double>(h.pixdim[i]);
  r.scl_slope = static_cast<double>(h.scl_slope);
  r.scl_inter = static_cast<double>(h.scl_inter);
  r.qform_code = h.qform_code;
  r.sform_code = h.sform_code;
  r.quatern[0] = static_cast<double>(h.quatern_b);
  r.quatern[1] = static_cast<double>(h.quatern_c);
  r.quatern[2] = static_cast<double>(h.quatern_d);
  r.qoffset[0] = static_cast<double>(h.qoffset_x);
  r.qoffset[1] = static_cast<double>(h.qoffset_y);
  r.qoffset[2] = static_cast<double>(h.qoffset_z);
  for (int c = 0; c < 4; ++c) {
    r.srow[0][c] = static_cast<double>(h.srow_x[c]);
    r.srow[1][c] = static_cast<double>(h.srow_y[c]);
    r.srow[2][c] = static_cast<double>(h.srow_z[c]);
  }
}

std::string check_fields(const RawHeader& r) {
  const std::int64_t header_end = r.version == 1 ? 348 + 4 : 540 + 4;  // with the extender
  if (!std::isfinite(r.vox_offset) || r.vox_offset < 0 || r.vox_offset != std::floor(r.vox_offset))
    return fmt::format("its vox_offset {} is not a whole number of bytes", r.vox_offset);
  if (r.single_file && r.vox_offset < static_cast<double>(header_end))
    return fmt::format(
        "its vox_offset {} lies inside the header (the data of a single-file NIfTI-{} starts at "
        "byte {} or later)",
        r.vox_offset, r.version, header_end);
  if (!std::isfinite(r.scl_slope) || !std::isfinite(r.scl_inter))
    return "its scale slope or intercept is not finite";
  if (r.sform_code > 0) {
    for (int i = 0; i < 3; ++i)
      for (int c = 0; c < 4; ++c)
        if (!std::isfinite(r.srow[i][c]))
          return fmt::format("its sform row {} is not finite (entry {} = {})", "xyz"[i], c,
                             r.srow[i][c]);
    return {};
  }
  // The qform, or no transform at all: the spacing is pixdim[1..3] (nifticlib would read 0, a
  // negative value or NaN as 1).
  for (int a = 1; a <= 3; ++a)
    if (!std::isfinite(r.pixdim[a]) || r.pixdim[a] <= 0)
      return fmt::format(
          "its voxel spacing pixdim[{}] = {} is not positive and finite ({} uses it)", a,
          r.pixdim[a], r.qform_code > 0 ? "the qform" : "a file without sform or qform");
  if (r.qform_code > 0) {
    const double b = r.quatern[0], c = r.quatern[1], d = r.quatern[2];
    if (!std::isfinite(b) || !std::isfinite(c) || !std::isfinite(d))
      return fmt::format("its qform quaternion ({}, {}, {}) is not finite", b, c, d);
    // a^2 = 1 - (b^2 + c^2 + d^2) must not be negative (beyond the rounding of floats).
    if (b * b + c * c + d * d > 1 + 1e-5)
      return fmt::format("its qform quaternion ({}, {}, {}) is longer than 1: no rotation", b, c,
                         d);
    for (int a = 0; a < 3; ++a)
      if (!std::isfinite(r.qoffset[a]))
        return fmt::format("its qform offset {} is not finite", "xyz"[a]);
    if (!std::isfinite(r.pixdim[0])) return "its qfac (pixdim[0]) is not finite";
  }
  return {};
}

}  // namespace

RawHeader read_raw_header(const std::filesystem::path& path, std::string& why) {
  RawHeader r;
  Znz in(path.string());
  if (znz_isnull(in.file)) return why = "it cannot be opened", r;
  char bytes[540] = {};
  const std::size_t got = znzread(bytes, 1, sizeof bytes, in.file);
  std::int32_t size = 0;
  std::memcpy(&size, bytes, 4);
  if (size != 348 && size != 540) {
    r.swapped = true;
    size = swapped_int(size);
  }
  if ((size != 348 && size != 540) || got < static_cast<std::size_t>(size))
    return why = "not a valid NIfTI-1 or NIfTI-2 file (bad header, or not NIfTI)", r;
  r.version = size == 348 ? 1 : 2;
  if (r.version == 1) {
    nifti_1_header h;
    std::memcpy(&h, bytes, sizeof h);
    if (r.swapped) nifti_swap_as_nifti1(&h);
    if (std::memcmp(h.magic, "n+1", 4) != 0 && std::memcmp(h.magic, "ni1", 4) != 0)
      return why = fmt::format(
                 "its magic {} is not NIfTI-1's ('n+1' or 'ni1'): an ANALYZE 7.5 header or a "
                 "damaged file",
                 magic_text(h.magic)),
             r;
    r.single_file = h.magic[1] == '+';
    copy_fields(h, r);
  } else {
    nifti_2_header h;
    std::memcpy(&h, bytes, sizeof h);
    if (r.swapped) nifti_swap_as_nifti2(&h);
    if (std::memcmp(h.magic, "n+2", 4) != 0 && std::memcmp(h.magic, "ni2", 4) != 0)
      return why =
                 fmt::format("its magic {} is not NIfTI-2's ('n+2' or 'ni2')", magic_text(h.magic)),
             r;
    r.single_file = h.magic[1] == '+';
    copy_fields(h, r);
  }
  why = check_fields(r);
  return r;
}

std::string oblique_entry(const double (&m)[3][4], const char* which) {
  for (int c = 0; c < 3; ++c) {
    const double length = std::hypot(m[0][c], m[1][c], m[2][c]);
    for (int r = 0; r < 3; ++r)
      if (r != c && !(std::fabs(m[r][c]) <= 1e-6 * length))
        return fmt::format(
            "its {} is oblique or permutes the axes (entry ({}, {}) = {}); only axis-aligned "
            "voxels are supported: resample it first",
            which, r, c, m[r][c]);
  }
  return {};
}

std::string read_data(const std::string& file, std::int64_t offset, std::size_t bytes, bool swap,
                      int value_bytes, void* out) {
  Znz in(file);
  if (znz_isnull(in.file)) return "its data file cannot be opened";
  if (znzseek(in.file, static_cast<znz_off_t>(offset), SEEK_SET) < 0)
    return "its data is missing or cut short (a truncated or corrupt file)";
  auto* at = static_cast<char*>(out);
  for (std::size_t done = 0; done < bytes;) {
    // znzread takes at most an int's worth at once (zlib's gzread).
    const std::size_t chunk = std::min<std::size_t>(bytes - done, std::size_t{1} << 30);
    const std::size_t n = znzread(at + done, 1, chunk, in.file);
    if (n == 0) return "its data is missing or cut short (a truncated or corrupt file)";
    done += n;
  }
  if (swap && value_bytes > 1)
    nifti_swap_Nbytes(static_cast<std::int64_t>(bytes / static_cast<std::size_t>(value_bytes)),
                      value_bytes, out);
  return {};
}

}  // namespace boxgen::runtime::nifti_header
