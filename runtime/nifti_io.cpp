#include "runtime/nifti_io.h"

#include <fmt/format.h>
#include <nifti2_io.h>
#include <unistd.h>
#include <zlib.h>

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <limits>
#include <memory>
#include <mutex>
#include <optional>
#include <span>
#include <stdexcept>
#include <string>
#include <system_error>
#include <type_traits>
#include <utility>
#include <vector>

#include "runtime/nifti_header.h"
#include "runtime/nrrd_checks.h"
#include "support/output_file.h"

namespace boxgen::runtime {

namespace {

namespace fs = std::filesystem;

constexpr int kLastXformCode = NIFTI_XFORM_TEMPLATE_OTHER;  // NIfTI-1's codes are 0..5

// A file's qform or sform code as carried to outputs: NIfTI's own codes as they are; a positive
// code NIfTI does not define still placed the world (the reader used it), as an aligned one.
int known_xform_code(int code) {
  if (code <= 0) return NIFTI_XFORM_UNKNOWN;
  return code <= kLastXformCode ? code : NIFTI_XFORM_ALIGNED_ANAT;
}

struct ImageDeleter {
  void operator()(nifti_image* image) const { nifti_image_free(image); }
};
using Image = std::unique_ptr<nifti_image, ImageDeleter>;

// nifticlib keeps its options (the debug level) in globals: one lock for every call.
std::mutex& nifti_mutex() {
  static std::mutex mutex;
  return mutex;
}

struct NiftiType {
  int code;
  const char* name;
};
constexpr NiftiType kTypes[] = {{DT_INT8, "int8"},     {DT_UINT8, "uint8"},   {DT_INT16, "int16"},
                                {DT_UINT16, "uint16"}, {DT_INT32, "int32"},   {DT_UINT32, "uint32"},
                                {DT_FLOAT32, "float"}, {DT_FLOAT64, "double"}};

const char* type_name(int code) {
  for (const NiftiType& t : kTypes)
    if (t.code == code) return t.name;
  return nullptr;
}

// The voxel-to-world affine the standard says to use, and its name for messages.
const nifti_dmat44& world_affine(const nifti_image& image, const char*& which) {
  which = image.sform_code > 0 ? "sform" : "qform";
  return image.sform_code > 0 ? image.sto_xyz : image.qto_xyz;
}

template <class T, class S>
void convert(const void* data, std::size_t count, double slope, double inter, std::vector<T>& out) {
  const std::span<const S> in(static_cast<const S*>(data), count);
  const bool scaled = slope != 0 && !(slope == 1 && inter == 0);
  if (scaled)
    std::transform(in.begin(), in.end(), out.begin(),
                   [&](S x) { return to_sample<T>(slope * static_cast<double>(x) + inter); });
  else
    std::transform(in.begin(), in.end(), out.begin(),
                   [](S x) { return to_sample<T>(static_cast<double>(x)); });
}

// What a file holds that is not one scalar 3-D volume, named as its users know it: "" when it is
// one. Checked before the dimensions, so that a CIFTI matrix or a vector field is not called a
// time series.
std::string unsupported_kind(const nifti_image& im) {
  if (im.nifti_type == NIFTI_FTYPE_ANALYZE)
    return "it is an Analyze 7.5 file (a .hdr/.img pair without the NIfTI magic), whose "
           "orientation is undefined; convert it to NIfTI with the tool that made it";
  bool cifti = im.intent_code >= 3000 && im.intent_code <= 3099;  // NIFTI_INTENT_CONNECTIVITY_*
  for (int e = 0; e < im.num_ext && im.ext_list; ++e)
    cifti = cifti || im.ext_list[e].ecode == NIFTI_ECODE_CIFTI;
  if (cifti)
    return "it is a CIFTI file (surface and grayordinate data), not a volume; only 3-D NIfTI "
           "volumes are read";
  if (im.datatype == DT_RGB24 || im.datatype == DT_RGBA32 ||
      im.intent_code == NIFTI_INTENT_RGB_VECTOR || im.intent_code == NIFTI_INTENT_RGBA_VECTOR)
    return "it holds RGB colours, not scalar samples; only scalar volumes are read";
  const bool vector =
      im.intent_code == NIFTI_INTENT_VECTOR || im.intent_code == NIFTI_INTENT_DISPVECT ||
      im.intent_code == NIFTI_INTENT_SYMMATRIX || im.intent_code == NIFTI_INTENT_GENMATRIX;
  if (vector || (im.dim[0] >= 5 && im.dim[5] > 1))
    return fmt::format(
        "it holds {} values per voxel (a vector, tensor or matrix image: dimension 5 of size {}); "
        "only scalar volumes are read",
        im.dim[0] >= 5 ? im.dim[5] : 1, im.dim[0] >= 5 ? im.dim[5] : 1);
  return {};
}

// The file that holds the header: `path`, or for the .img of a .hdr/.img pair its .hdr (which
// nifticlib finds the same way).
fs::path header_file(const fs::path& path) {
  std::unique_ptr<char, decltype(&std::free)> found(nifti_findhdrname(path.c_str()), &std::free);
  return found ? fs::path(found.get()) : path;
}

int nifti_datatype(SampleType type) {
  switch (type) {
    case SampleType::Int8:
      return DT_INT8;
    case SampleType::UInt8:
      return DT_UINT8;
    case SampleType::Int16:
      return DT_INT16;
    case SampleType::UInt16:
      return DT_UINT16;
    case SampleType::Int32:
      return DT_INT32;
    case SampleType::UInt32:
      return DT_UINT32;
    case SampleType::Float32:
      return DT_FLOAT32;
    case SampleType::Float64:
      break;
  }
  return DT_FLOAT64;
}

bool ends_with_gz(const fs::path& path) {
  std::string name = path.filename().string();
  std::transform(name.begin(), name.end(), name.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return name.ends_with(".gz");
}

// The NIfTI-1 header of a single-file image (magic "n+1", data at byte 352) of `sizes` voxels of
// `type`, with the affine as sform and qform (write_nifti says with which codes).
nifti_1_header nifti1_header(const Sizes& sizes, const Affine& affine, SampleType type,
                             const NiftiCodes& codes) {
  const std::int64_t dims[8] = {3, sizes[0], sizes[1], sizes[2], 1, 1, 1, 1};
  std::unique_ptr<nifti_1_header, decltype(&std::free)> made(
      nifti_make_new_n1_header(dims, nifti_datatype(type)), &std::free);
  if (!made) throw NrrdError("nifticlib could not make a NIfTI-1 header");
  nifti_1_header h = *made;
  nifti_dmat44 m{};
  for (int r = 0; r < 3; ++r) {
    for (int c = 0; c < 3; ++c) m.m[r][c] = affine.linear[r][c];
    m.m[r][3] = affine.translation[r];
  }
  m.m[3][3] = 1;
  double qb = 0, qc = 0, qd = 0, qx = 0, qy = 0, qz = 0, dx = 0, dy = 0, dz = 0, qfac = 0;
  nifti_dmat44_to_quatern(m, &qb, &qc, &qd, &qx, &qy, &qz, &dx, &dy, &dz, &qfac);
  h.qform_code = static_cast<std::int16_t>(codes.qform);
  h.sform_code = static_cast<std::int16_t>(codes.sform);
  h.quatern_b = static_cast<float>(qb);
  h.quatern_c = static_cast<float>(qc);
  h.quatern_d = static_cast<float>(qd);
  h.qoffset_x = static_cast<float>(qx);
  h.qoffset_y = static_cast<float>(qy);
  h.qoffset_z = static_cast<float>(qz);
  h.pixdim[0] = static_cast<float>(qfac);
  h.pixdim[1] = static_cast<float>(dx);
  h.pixdim[2] = static_cast<float>(dy);
  h.pixdim[3] = static_cast<float>(dz);
  float* rows[3] = {h.srow_x, h.srow_y, h.srow_z};
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 4; ++c) rows[r][c] = static_cast<float>(m.m[r][c]);
  h.scl_slope = 1;
  h.scl_inter = 0;
  h.xyzt_units = 0;
  h.vox_offset = 352;
  std::memcpy(h.magic, "n+1", 4);
  return h;
}

}  // namespace

NiftiCodes nifti_output_codes(const std::string& anatomical, const NiftiCodes& read) {
  if (read.any()) return {read.qform, read.sform > 0 ? read.sform : read.qform};
  return {anatomical.empty() ? NIFTI_XFORM_UNKNOWN : NIFTI_XFORM_ALIGNED_ANAT,
          NIFTI_XFORM_ALIGNED_ANAT};
}

void write_nifti(const fs::path& path, const Sizes& sizes, const Affine& affine,
                 const EncodedSamples& samples, const NiftiCodes& codes) {
  if (codes.sform < 1 || codes.sform > kLastXformCode || codes.qform < 0 ||
      codes.qform > kLastXformCode)
    throw std::invalid_argument(fmt::format(
        "NIfTI codes must be 1..{} (sform) and 0..{} (qform), got sform {} and qform {}",
        kLastXformCode, kLastXformCode, codes.sform, codes.qform));
  const auto count = static_cast<std::uint64_t>(sizes[0]) * static_cast<std::uint64_t>(sizes[1]) *
                     static_cast<std::uint64_t>(sizes[2]);
  if (count * sample_type_size(samples.type) != samples.bytes.size())
    throw std::invalid_argument(fmt::format("a NIfTI grid of {} x {} x {} {} voxels holds {} bytes",
                                            sizes[0], sizes[1], sizes[2],
                                            sample_type_name(samples.type), samples.bytes.size()));
  for (int a = 0; a < 3; ++a)
    if (sizes[a] < 1 || sizes[a] > std::numeric_limits<std::int16_t>::max())
      throw NrrdError(fmt::format(
          "cannot write NIfTI-1 '{}': its size {} on axis {} is beyond NIfTI-1's 1..32767",
          nrrd_checks::printable(path.string()), sizes[a], a));
  const auto m = affine.linear;
  const double det = m[0][0] * (m[1][1] * m[2][2] - m[1][2] * m[2][1]) -
                     m[0][1] * (m[1][0] * m[2][2] - m[1][2] * m[2][0]) +
                     m[0][2] * (m[1][0] * m[2][1] - m[1][1] * m[2][0]);
  bool finite = std::isfinite(det) && det != 0;
  for (int r = 0; r < 3; ++r) finite = finite && std::isfinite(affine.translation[r]);
  if (!finite)
    throw std::invalid_argument(
        "a NIfTI grid's affine must be finite with independent axes (a non-zero determinant)");
  nifti_1_header header{};
  {
    std::lock_guard lock(nifti_mutex());
    nifti_set_debug_level(0);
    header = nifti1_header(sizes, affine, samples.type, codes);
  }
  const char extension[4] = {0, 0, 0, 0};  // no header extensions
  const bool gz = ends_with_gz(path);
  int error = 0;  // errno of the failed write
  const auto fill = [&](std::FILE* file) {
    errno = 0;
    if (!gz) {
      const bool ok = std::fwrite(&header, sizeof header, 1, file) == 1 &&
                      std::fwrite(extension, sizeof extension, 1, file) == 1 &&
                      (samples.bytes.empty() ||
                       std::fwrite(samples.bytes.data(), samples.bytes.size(), 1, file) == 1);
      error = ok ? 0 : errno;
      return ok;
    }
    const int fd = ::dup(::fileno(file));
    if (fd < 0) return error = errno, false;
    gzFile z = gzdopen(fd, "wb1");  // the fast level, as nibabel's default
    if (!z) {
      ::close(fd);
      return false;
    }
    bool ok = gzwrite(z, &header, sizeof header) == static_cast<int>(sizeof header) &&
              gzwrite(z, extension, sizeof extension) == static_cast<int>(sizeof extension);
    constexpr std::size_t kChunk = std::size_t{1} << 24;
    for (std::size_t at = 0; ok && at < samples.bytes.size(); at += kChunk) {
      const auto n = static_cast<unsigned>(std::min(kChunk, samples.bytes.size() - at));
      ok = gzwrite(z, samples.bytes.data() + at, n) == static_cast<int>(n);
    }
    if (!ok) error = errno;
    const bool closed = gzclose(z) == Z_OK;
    if (!closed && error == 0) error = errno;
    return ok && closed;
  };
  const auto why = [&] {
    return fmt::format("writing failed: {}", error != 0 ? std::strerror(error) : "unknown error");
  };
  try {
    support::write_output_file(path, fill, why);
  } catch (const support::OutputFileError& e) {
    throw NrrdError(e.what());
  }
}

bool is_nifti_path(const fs::path& path) {
  std::string name = path.filename().string();
  std::transform(name.begin(), name.end(), name.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  for (const char* extension : {".nii", ".hdr", ".img"})
    if (name.ends_with(extension) || name.ends_with(std::string(extension) + ".gz")) return true;
  return false;
}

void refuse_foreign_file(const fs::path& path) {
  std::string name = path.filename().string();
  std::transform(name.begin(), name.end(), name.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  char head[132] = {};
  std::size_t got = 0;
  if (std::FILE* file = fs::is_regular_file(path) ? std::fopen(path.c_str(), "rb") : nullptr) {
    got = std::fread(head, 1, sizeof head, file);
    std::fclose(file);
  }
  // DICOM Part 10: a 128-byte preamble, then "DICM"; older files have neither, but a .dcm name.
  if ((got == sizeof head && std::memcmp(head + 128, "DICM", 4) == 0) || name.ends_with(".dcm"))
    throw NrrdError(fmt::format(
        "cannot read volume '{}': it is a DICOM file; convert the series to NIfTI with dcm2niix "
        "(Debian package dcm2niix: dcm2niix -o OUTDIR DICOMDIR) and read the .nii.gz",
        nrrd_checks::printable(path.string())));
}

namespace {

// The grid's geometry: a diagonal affine (nifti_header::oblique_entry), translation = world point
// of voxel (0, 0, 0); without sform or qform the spacing is pixdim as the file holds it. An
// oblique or permuted affine, where allowed, gives the voxel grid in its own frame (steps = the
// column lengths, origin 0) and the frame's map to world, which keeps the file's affine.
struct Geometry {
  Vec3 steps{}, origin{};
  std::optional<Affine> frame;
};

// "" and `out`, or why the file's geometry is refused.
std::string read_geometry(const nifti_image& im, const nifti_header::RawHeader& raw,
                          bool allow_oblique, Geometry& out) {
  if (im.sform_code <= 0 && im.qform_code <= 0) {
    out.steps = {raw.pixdim[1], raw.pixdim[2], raw.pixdim[3]};
    return {};
  }
  const char* which = nullptr;
  const nifti_dmat44& m = world_affine(im, which);
  double rows[3][4];
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 4; ++c) rows[r][c] = m.m[r][c];
  std::string oblique = nifti_header::oblique_entry(rows, which);
  if (oblique.empty()) {
    for (int a = 0; a < 3; ++a) {
      out.steps[a] = m.m[a][a];
      out.origin[a] = m.m[a][3];
    }
    return {};
  }
  if (!allow_oblique) return oblique;
  Affine a, map;
  for (int r = 0; r < 3; ++r) {
    for (int c = 0; c < 3; ++c) a.linear[r][c] = m.m[r][c];
    a.translation[r] = m.m[r][3];
  }
  if (const std::string why = split_oblique(a, out.steps, map); !why.empty())
    return fmt::format("its {} {}", which, why);
  out.frame = map;
  return {};
}

}  // namespace

template <class T>
LatticeVolume<T> read_nifti(const fs::path& path, const NrrdReadLimits& limits,
                            SourceSamples* source) {
  const std::string shown = nrrd_checks::printable(path.string());
  const auto fail = [&](const std::string& why) {
    throw NrrdError(fmt::format("cannot read NIfTI volume '{}': {}", shown, why));
  };
  std::error_code error;
  const fs::file_status status = fs::status(path, error);
  if (!fs::exists(status)) fail("no such file");
  if (fs::is_directory(status)) fail("it is a directory");
  if (!fs::is_regular_file(status)) fail("not a regular file");

  std::lock_guard lock(nifti_mutex());
  nifti_set_debug_level(0);  // nifticlib prints its errors on stderr; ours are one line
  // The header's bytes first: what nifticlib would repair silently is refused (nifti_header.h).
  std::string refusal;
  const nifti_header::RawHeader raw = nifti_header::read_raw_header(header_file(path), refusal);
  if (!refusal.empty()) fail(refusal);
  Image image(nifti_image_read(path.c_str(), 0));
  if (!image) fail("not a valid NIfTI-1 or NIfTI-2 file (bad header, or not NIfTI)");
  const nifti_image& im = *image;
  if (const std::string why = unsupported_kind(im); !why.empty()) fail(why);
  // NIfTI's world is RAS+ whenever a qform or sform places it (method 2 or 3); pixdim alone
  // (both codes 0) places the voxels in no patient frame.
  const bool anatomical = im.qform_code > 0 || im.sform_code > 0;
  for (int a = 4; a <= 7; ++a)
    if (im.dim[0] >= a && im.dim[a] > 1)
      fail(
          fmt::format("it holds {} volumes along dimension {} (a time series); only one 3-D "
                      "volume is read",
                      im.dim[a], a));
  Sizes sizes{};
  const std::int64_t dims[3] = {im.nx, im.ny, im.nz};
  for (int a = 0; a < 3; ++a) {
    if (dims[a] < 1 || dims[a] > LatticeVolume<T>::kMaxSize)
      fail(fmt::format("its size {} on axis {} is out of range (1..{})", dims[a], a,
                       LatticeVolume<T>::kMaxSize));
    sizes[a] = static_cast<int>(dims[a]);
  }
  const char* type = type_name(im.datatype);
  if (!type)
    fail(fmt::format(
        "its data type '{}' is not supported (int8, uint8, int16, uint16, int32, uint32, float32 "
        "or float64)",
        nifti_datatype_string(im.datatype)));
  const auto count = static_cast<std::uint64_t>(sizes[0]) * static_cast<std::uint64_t>(sizes[1]) *
                     static_cast<std::uint64_t>(sizes[2]);
  if (count * static_cast<std::uint64_t>(im.nbyper) > limits.max_data_bytes)
    fail(fmt::format("its data of {} bytes exceeds the limit of {} bytes",
                     count * static_cast<std::uint64_t>(im.nbyper), limits.max_data_bytes));
  // Before anything is allocated: the file's data and the samples made from it.
  if (const std::string why = nrrd_checks::check_memory_for(
          count * (static_cast<std::uint64_t>(im.nbyper) + sizeof(T)));
      !why.empty())
    fail(why);

  Geometry geometry;
  if (const std::string why = read_geometry(im, raw, limits.allow_oblique, geometry); !why.empty())
    fail(why);
  if (geometry.frame && !source)
    throw std::logic_error("read_nifti: allow_oblique needs a SourceSamples");
  Vec3& steps = geometry.steps;
  Vec3& origin = geometry.origin;
  const std::optional<Affine>& frame = geometry.frame;
  for (int a = 0; a < 3; ++a)
    if (!std::isfinite(steps[a]) || steps[a] == 0 || !std::isfinite(origin[a]))
      fail(
          fmt::format("its voxel spacing {} on axis {} is zero or not finite (or the origin is "
                      "not finite)",
                      steps[a], a));

  // The data as the file holds it: nifticlib's loader would turn NaN and infinite floats into 0.
  const auto n = static_cast<std::size_t>(count);
  std::vector<unsigned char> data(n * static_cast<std::size_t>(im.nbyper));
  if (const std::string problem = nifti_header::read_data(im.iname, im.iname_offset, data.size(),
                                                          raw.swapped, im.nbyper, data.data());
      !problem.empty())
    fail(problem);
  // `im` is *image: what is still needed of the header is read before the image is freed.
  const NiftiCodes codes{known_xform_code(im.qform_code), known_xform_code(im.sform_code)};
  image.reset();
  std::vector<T> samples(n);
  (void)visit_sample_type(type, [&](auto tag) {
    convert<T, decltype(tag)>(data.data(), n, raw.scl_slope, raw.scl_inter, samples);
  });
  data = {};  // the file's copy of the data is no longer needed
  if (!limits.allow_non_finite)
    if (const std::string why = nrrd_checks::check_finite<T>(samples, 1, sizes); !why.empty())
      fail(why);
  if (!frame) orient_axes_positive(std::span<T>(samples), sizes, steps, origin);
  LatticeVolume<T> volume(CosetLattice::cartesian(), sizes, steps, origin, std::move(samples));
  if (source) {
    *source = describe_samples<T>(volume.samples(), type);
    source->frame = frame;
    source->anatomical = anatomical ? "RAS" : "";
    source->nifti_codes = codes;
  }
  return volume;
}

template LatticeVolume<float> read_nifti<float>(const fs::path&, const NrrdReadLimits&,
                                                SourceSamples*);
template LatticeVolume<double> read_nifti<double>(const fs::path&, const NrrdReadLimits&,
                                                  SourceSamples*);

}  // namespace boxgen::runtime
