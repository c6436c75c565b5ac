#include "runtime/nifti_io.h"

#include <fmt/format.h>
#include <nifti2_io.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdint>
#include <memory>
#include <mutex>
#include <span>
#include <string>
#include <system_error>
#include <type_traits>
#include <utility>
#include <vector>

#include "runtime/nifti_header.h"
#include "runtime/nrrd_checks.h"

namespace boxgen::runtime {

namespace {

namespace fs = std::filesystem;

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

}  // namespace

bool is_nifti_path(const fs::path& path) {
  std::string name = path.filename().string();
  std::transform(name.begin(), name.end(), name.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return name.ends_with(".nii") || name.ends_with(".nii.gz");
}

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
  const nifti_header::RawHeader raw = nifti_header::read_raw_header(path, refusal);
  if (!refusal.empty()) fail(refusal);
  Image image(nifti_image_read(path.c_str(), 0));
  if (!image) fail("not a valid NIfTI-1 or NIfTI-2 file (bad header, or not NIfTI)");
  const nifti_image& im = *image;
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

  // Geometry: a diagonal affine (nifti_header::oblique_entry), translation = world point of voxel
  // (0, 0, 0). Without sform or qform the spacing is pixdim as the file holds it.
  Vec3 steps{}, origin{};
  if (im.sform_code <= 0 && im.qform_code <= 0) {
    steps = {raw.pixdim[1], raw.pixdim[2], raw.pixdim[3]};
  } else {
    const char* which = nullptr;
    const nifti_dmat44& m = world_affine(im, which);
    double rows[3][4];
    for (int r = 0; r < 3; ++r)
      for (int c = 0; c < 4; ++c) rows[r][c] = m.m[r][c];
    if (const std::string oblique = nifti_header::oblique_entry(rows, which); !oblique.empty())
      fail(oblique);
    for (int a = 0; a < 3; ++a) {
      steps[a] = m.m[a][a];
      origin[a] = m.m[a][3];
    }
  }
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
  image.reset();
  std::vector<T> samples(n);
  (void)visit_sample_type(type, [&](auto tag) {
    convert<T, decltype(tag)>(data.data(), n, raw.scl_slope, raw.scl_inter, samples);
  });
  data = {};  // the file's copy of the data is no longer needed
  if (!limits.allow_non_finite)
    if (const std::string why = nrrd_checks::check_finite<T>(samples, 1, sizes); !why.empty())
      fail(why);
  orient_axes_positive(std::span<T>(samples), sizes, steps, origin);
  LatticeVolume<T> volume(CosetLattice::cartesian(), sizes, steps, origin, std::move(samples));
  if (source) *source = describe_samples<T>(volume.samples(), type);
  return volume;
}

template LatticeVolume<float> read_nifti<float>(const fs::path&, const NrrdReadLimits&,
                                                SourceSamples*);
template LatticeVolume<double> read_nifti<double>(const fs::path&, const NrrdReadLimits&,
                                                  SourceSamples*);

}  // namespace boxgen::runtime
