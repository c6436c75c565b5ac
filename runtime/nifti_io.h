// NIfTI-1 and NIfTI-2 volumes (.nii, .nii.gz; the format of MRI and fMRI scanners and
// templates) read through nifticlib (Debian libnifti2-dev), as Cartesian lattice volumes.
//
// Geometry: voxel (i, j, k) sits at the world point the sform gives (the qform when the sform
// code is 0; pixdim scaling from the origin when both codes are 0), as stored: the world frame is
// the file's (RAS+ for scanner data), with no change of handedness. The affine must be diagonal
// (axis-aligned voxels with any spacings, anisotropic included); an axis with a negative spacing
// is stored flipped (source_samples.h), which keeps every value at its world point. An oblique or
// permuted affine is refused: the volume would have to be resampled.
//
// Samples: int8, uint8, int16, uint16, int32, uint32, float32, float64, converted to T; a scale
// slope other than 0 applies value = slope x + intercept (to every type, as the NIfTI standard
// says). Only one 3-D volume: a time series (dim[4] > 1) is refused. Every failure is a NrrdError
// (the one file error of the runtime) whose message is one line naming the file; nifticlib's own
// messages are switched off.
#pragma once
#include <filesystem>

#include "runtime/nrrd_io.h"

namespace boxgen::runtime {

// Throws NrrdError (one line) for any problem; limits.max_data_bytes bounds the data nifticlib
// may allocate (checked from the header before any data is read) and limits.allow_non_finite
// admits NaN and infinite samples.
template <class T>
LatticeVolume<T> read_nifti(const std::filesystem::path& path, const NrrdReadLimits& limits = {},
                            SourceSamples* source = nullptr);

// Whether `path` names a NIfTI file by its extension (.nii or .nii.gz, any case).
bool is_nifti_path(const std::filesystem::path& path);

// The one reader of volume files: NIfTI by extension (is_nifti_path), NRRD otherwise.
template <class T>
LatticeVolume<T> read_volume_file(const std::filesystem::path& path,
                                  const NrrdReadLimits& limits = {},
                                  SourceSamples* source = nullptr) {
  return is_nifti_path(path) ? read_nifti<T>(path, limits, source)
                             : read_lattice_nrrd<T>(path, limits, source);
}

extern template LatticeVolume<float> read_nifti<float>(const std::filesystem::path&,
                                                       const NrrdReadLimits&, SourceSamples*);
extern template LatticeVolume<double> read_nifti<double>(const std::filesystem::path&,
                                                         const NrrdReadLimits&, SourceSamples*);

}  // namespace boxgen::runtime
