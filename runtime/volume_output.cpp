#include "runtime/volume_output.h"

#include <fmt/format.h>

#include <algorithm>
#include <cctype>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

#include "runtime/nifti_io.h"
#include "runtime/nrrd_checks.h"
#include "runtime/nrrd_io.h"

namespace boxgen::runtime {

namespace {

namespace fs = std::filesystem;

std::string lower_name(const fs::path& path) {
  std::string name = path.filename().string();
  std::transform(name.begin(), name.end(), name.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return name;
}

template <class T>
constexpr SampleType own_type() {
  return std::is_same_v<T, float> ? SampleType::Float32 : SampleType::Float64;
}

// NIfTI's world is RAS: the map from a world with anatomical frame `anatomical` (SourceSamples)
// to RAS, a sign per axis (L -> R and P -> A flip; "" and "RAS" keep the world as it is).
Affine world_to_ras(const std::string& anatomical) {
  Vec3 sign{1, 1, 1};
  const std::string ras = "RAS";
  for (std::size_t a = 0; a < 3 && anatomical.size() == 3; ++a)
    if (anatomical[a] != ras[a]) sign[a] = -1;
  return Affine::diagonal(sign, {0, 0, 0});
}

// A NIfTI of a Cartesian grid whose index-to-frame map is `in_frame`, in a volume's frame
// (`frame`: its map to world; nothing: the world itself) and anatomical frame: NIfTI's world is
// RAS, and the codes claim what the world is (nifti_output_codes).
void write_nifti_grid(const fs::path& path, const Sizes& sizes, const Affine& in_frame,
                      const std::optional<Affine>& frame, const std::string& anatomical,
                      const NiftiCodes& codes, const EncodedSamples& samples) {
  write_nifti(path, sizes,
              world_to_ras(anatomical).after(frame ? frame->after(in_frame) : in_frame), samples,
              nifti_output_codes(anatomical, codes));
}

}  // namespace

VolumeFormat output_format(const fs::path& path) {
  const std::string name = lower_name(path);
  if (name.ends_with(".nrrd")) return VolumeFormat::Nrrd;
  if (name.ends_with(".nii") || name.ends_with(".nii.gz")) return VolumeFormat::Nifti;
  const std::string shown = nrrd_checks::printable(path.string());
  std::string why = "no writer knows its extension";
  if (name.ends_with(".nhdr"))
    why = "a detached NRRD header (.nhdr) is not written; name it .nrrd (data in the file)";
  else if (name.ends_with(".hdr") || name.ends_with(".img") || name.ends_with(".hdr.gz") ||
           name.ends_with(".img.gz"))
    why = "Analyze and NIfTI .hdr/.img pairs are not written; name it .nii or .nii.gz";
  else if (name.ends_with(".dcm"))
    why = "DICOM is not written";
  throw NrrdError(fmt::format(
      "cannot write volume '{}': {} (volumes are written as .nrrd, .nii or .nii.gz)", shown, why));
}

VolumeFormat require_volume_output(const fs::path& path, std::span<const fs::path> inputs,
                                   int cosets, const char* lattice_name) {
  require_output_file(path, inputs);
  const VolumeFormat format = output_format(path);
  if (format == VolumeFormat::Nifti && cosets != 1)
    throw NrrdError(fmt::format(
        "cannot write volume '{}': a {} volume ({} cosets) cannot be NIfTI, which holds "
        "Cartesian grids only; name it .nrrd",
        nrrd_checks::printable(path.string()), lattice_name, cosets));
  return format;
}

template <class T>
VolumeWrite write_volume_file(const fs::path& path, const LatticeVolume<T>& volume,
                              std::optional<SampleType> type, const std::string& anatomical,
                              const std::optional<Affine>& frame, const NiftiCodes& codes) {
  const CosetLattice& lattice = volume.lattice();
  const VolumeFormat format =
      require_volume_output(path, {}, volume.coset_count(), lattice.name().c_str());
  if (format == VolumeFormat::Nrrd && (!type || *type == own_type<T>())) {
    write_lattice_nrrd(path, volume, anatomical, frame);
    return {own_type<T>(), 0};
  }
  const EncodedSamples samples = encode_samples<T>(
      volume.samples(),
      type.value_or(format == VolumeFormat::Nifti ? SampleType::Float32 : own_type<T>()));
  if (format == VolumeFormat::Nrrd) {
    write_lattice_nrrd(path, volume, samples, anatomical, frame);
    return {samples.type, samples.clamped};
  }
  // One coset: sample (i, j, k) at o + h (d (i, j, k) + offset).
  const double d = lattice.period();
  const Offset& offset = lattice.offsets().front();
  Vec3 step{}, origin{};
  for (int a = 0; a < 3; ++a) {
    step[a] = d * volume.axis_spacing()[a];
    origin[a] = volume.origin()[a] + volume.axis_spacing()[a] * static_cast<double>(offset[a]);
  }
  write_nifti_grid(path, volume.sizes(), Affine::diagonal(step, origin), frame, anatomical, codes,
                   samples);
  return {samples.type, samples.clamped};
}

template <class T>
VolumeWrite write_grid_file(const fs::path& path, const CartesianVolume<T>& grid,
                            std::optional<SampleType> type, const std::string& anatomical,
                            const NiftiCodes& codes) {
  const VolumeFormat format = require_volume_output(path, {}, 1, "cartesian");
  if (format == VolumeFormat::Nrrd && (!type || *type == own_type<T>())) {
    write_cartesian_nrrd(path, grid, anatomical);
    return {own_type<T>(), 0};
  }
  if (format == VolumeFormat::Nrrd) {
    std::vector<T> copy = grid.values;
    const LatticeVolume<T> volume(CosetLattice::cartesian(), grid.sizes, grid.spacing, grid.origin,
                                  std::move(copy));
    return write_volume_file(path, volume, type, anatomical, grid.frame, codes);
  }
  const EncodedSamples samples = encode_samples<T>(grid.values, type.value_or(SampleType::Float32));
  write_nifti_grid(path, grid.sizes, Affine::diagonal(grid.spacing, grid.origin), grid.frame,
                   anatomical, codes, samples);
  return {samples.type, samples.clamped};
}

template VolumeWrite write_volume_file<float>(const fs::path&, const LatticeVolume<float>&,
                                              std::optional<SampleType>, const std::string&,
                                              const std::optional<Affine>&, const NiftiCodes&);
template VolumeWrite write_volume_file<double>(const fs::path&, const LatticeVolume<double>&,
                                               std::optional<SampleType>, const std::string&,
                                               const std::optional<Affine>&, const NiftiCodes&);
template VolumeWrite write_grid_file<float>(const fs::path&, const CartesianVolume<float>&,
                                            std::optional<SampleType>, const std::string&,
                                            const NiftiCodes&);
template VolumeWrite write_grid_file<double>(const fs::path&, const CartesianVolume<double>&,
                                             std::optional<SampleType>, const std::string&,
                                             const NiftiCodes&);

}  // namespace boxgen::runtime
