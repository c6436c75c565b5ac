// The one writer of volume files: the format is the output's name, NRRD (.nrrd) or NIfTI-1
// (.nii, .nii.gz), and nothing is written under a name no writer knows. A lattice volume of more
// than one coset (BCC, FCC, custom) is NRRD only: NIfTI holds Cartesian grids.
//
// The sample type is the caller's choice (boxrecon's --type, sample_encoding.h); by default NRRD
// stores the volume's own float or double and NIfTI float32 (what nibabel, FSL and ITK expect of
// a resampled image). Every write is atomic (output_file.h).
#pragma once
#include <cstdint>
#include <filesystem>
#include <optional>
#include <span>
#include <string>

#include "runtime/affine.h"
#include "runtime/cartesian_volume.h"
#include "runtime/lattice_volume.h"
#include "runtime/sample_encoding.h"
#include "runtime/source_samples.h"

namespace boxgen::runtime {

enum class VolumeFormat { Nrrd, Nifti };

// What a write stored: the sample type, and how many values were beyond its range and clamped.
struct VolumeWrite {
  SampleType type = SampleType::Float32;
  std::uint64_t clamped = 0;
};

// The format a name asks for: .nrrd is NRRD, .nii and .nii.gz NIfTI-1 (any case). Any other
// name is NrrdError (one line naming the extensions known); .nhdr (a detached header), Analyze's
// .hdr/.img and DICOM are named as such.
VolumeFormat output_format(const std::filesystem::path& path);

// Before any work: `path` may be written and is none of `inputs` (require_output_file), its
// format is known (output_format), and a NIfTI name is not given a volume of more than one coset
// (`cosets`, the lattice's K). Throws NrrdError (one line).
VolumeFormat require_volume_output(const std::filesystem::path& path,
                                   std::span<const std::filesystem::path> inputs, int cosets,
                                   const char* lattice_name);

// Writes `volume` in the format of its name with samples of `type` (default: NRRD the volume's T,
// NIfTI float32). `anatomical` is the world's frame (SourceSamples::anatomical of the volume the
// output came from: "RAS", "LAS", "LPS" or ""): NRRD writes it as its space, NIfTI (whose world
// is RAS) maps the world to RAS. `frame`: an oblique volume's map from its own frame to world
// (SourceSamples::frame), composed into the file's affine (NRRD: oblique space directions).
// `codes`: the qform and sform codes of the NIfTI the output came from (SourceSamples::
// nifti_codes), which a NIfTI output claims again (nifti_output_codes; NRRD has none).
// Returns the type written and how many values were clamped to its range. Throws NrrdError (one
// line) for a name or lattice require_volume_output refuses, or a failed write.
template <class T>
VolumeWrite write_volume_file(const std::filesystem::path& path, const LatticeVolume<T>& volume,
                              std::optional<SampleType> type = std::nullopt,
                              const std::string& anatomical = "",
                              const std::optional<Affine>& frame = std::nullopt,
                              const NiftiCodes& codes = {});
// The same for a Cartesian grid (an oblique one's frame is its own, CartesianVolume::frame).
template <class T>
VolumeWrite write_grid_file(const std::filesystem::path& path, const CartesianVolume<T>& grid,
                            std::optional<SampleType> type = std::nullopt,
                            const std::string& anatomical = "", const NiftiCodes& codes = {});

extern template VolumeWrite write_volume_file<float>(const std::filesystem::path&,
                                                     const LatticeVolume<float>&,
                                                     std::optional<SampleType>, const std::string&,
                                                     const std::optional<Affine>&,
                                                     const NiftiCodes&);
extern template VolumeWrite write_volume_file<double>(const std::filesystem::path&,
                                                      const LatticeVolume<double>&,
                                                      std::optional<SampleType>, const std::string&,
                                                      const std::optional<Affine>&,
                                                      const NiftiCodes&);
extern template VolumeWrite write_grid_file<float>(const std::filesystem::path&,
                                                   const CartesianVolume<float>&,
                                                   std::optional<SampleType>, const std::string&,
                                                   const NiftiCodes&);
extern template VolumeWrite write_grid_file<double>(const std::filesystem::path&,
                                                    const CartesianVolume<double>&,
                                                    std::optional<SampleType>, const std::string&,
                                                    const NiftiCodes&);

}  // namespace boxgen::runtime
