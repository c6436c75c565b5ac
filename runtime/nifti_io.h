// NIfTI-1 and NIfTI-2 volumes (.nii, .nii.gz and .hdr/.img pairs; the format of MRI and fMRI
// scanners and templates) read through nifticlib (Debian libnifti2-dev) as Cartesian lattice
// volumes, and Cartesian grids written as NIfTI-1 (write_nifti).
//
// Geometry: voxel (i, j, k) sits at the world point the sform gives (the qform when the sform
// code is 0; pixdim scaling from the origin when both codes are 0), as stored: the world frame is
// the file's (RAS+ for scanner data), with no change of handedness. The affine must be diagonal
// (axis-aligned voxels with any spacings, anisotropic included); an axis with a negative spacing
// is stored flipped (source_samples.h), which keeps every value at its world point. An oblique or
// permuted affine is refused unless NrrdReadLimits::allow_oblique: the volume is then its voxel
// grid in its own frame and SourceSamples::frame maps that frame to world.
//
// Samples: int8, uint8, int16, uint16, int32, uint32, float32, float64, converted to T; a scale
// slope other than 0 applies value = slope x + intercept (to every type, as the NIfTI standard
// says). Only one scalar 3-D volume: a time series (dim[4] > 1), a vector or matrix image
// (dim[5] > 1 or a vector intent), RGB voxels, CIFTI files and Analyze 7.5 pairs (no NIfTI magic,
// no defined orientation) are refused, each by its name. Every failure is a NrrdError (the one
// file error of the runtime) whose message is one line naming the file; nifticlib's own messages
// are switched off.
#pragma once
#include <filesystem>
#include <optional>
#include <string>

#include "runtime/affine.h"
#include "runtime/nrrd_io.h"
#include "runtime/sample_encoding.h"
#include "runtime/source_samples.h"

namespace boxgen::runtime {

// Throws NrrdError (one line) for any problem; limits.max_data_bytes bounds the data nifticlib
// may allocate (checked from the header before any data is read) and limits.allow_non_finite
// admits NaN and infinite samples.
template <class T>
LatticeVolume<T> read_nifti(const std::filesystem::path& path, const NrrdReadLimits& limits = {},
                            SourceSamples* source = nullptr);

// Whether `path` names a NIfTI file by its extension (.nii, .nii.gz, or one file of a .hdr/.img
// pair, also gzipped; any case). nifticlib reads a pair from either name.
bool is_nifti_path(const std::filesystem::path& path);

// Throws NrrdError (one line, with what to do) when `path` is a file of a format neither reader
// takes but users have: DICOM (by its "DICM" marker or a .dcm name). Returns otherwise.
void refuse_foreign_file(const std::filesystem::path& path);

// Writes a Cartesian grid as one NIfTI-1 file (.nii; gzip-compressed when the name ends in .gz):
// `sizes` voxels, x fastest, of `samples` (their type is the file's datatype), voxel (i, j, k) at
// the world point affine(i, j, k). The affine is the sform (exact) and the qform (its rotation,
// voxel sizes and qfac: exact for every grid without shear), with the codes `codes` (what the
// world is: nifti_output_codes chooses them; the sform's must be 1..5, the qform's 0..5, else
// std::invalid_argument). Units unknown, as nibabel writes them. Written through output_file.h
// (atomic; links followed, special files refused). Throws NrrdError (one line).
void write_nifti(const std::filesystem::path& path, const Sizes& sizes, const Affine& affine,
                 const EncodedSamples& samples, const NiftiCodes& codes);

// The codes a NIfTI written from a volume claims. A volume read from NIfTI keeps its file's
// (`read`: SourceSamples::nifti_codes), as nibabel keeps a header's: the qform's as it was, the
// sform's, or the qform's when the file had no sform, so that the exact affine always has one.
// Otherwise the world is "aligned anatomical" (2) in the sform, and in the qform too only when
// it is tied to a patient (`anatomical`: a RAS/LAS/LPS NRRD space); a world tied to none
// (3D-right-handed NRRD, Python arrays) leaves the qform's 0, as nibabel writes a new image, so
// that no reader takes it for a scanner's.
NiftiCodes nifti_output_codes(const std::string& anatomical, const NiftiCodes& read);

// The one reader of volume files: NIfTI by extension (is_nifti_path), NRRD otherwise (after
// refuse_foreign_file).
template <class T>
LatticeVolume<T> read_volume_file(const std::filesystem::path& path,
                                  const NrrdReadLimits& limits = {},
                                  SourceSamples* source = nullptr) {
  if (is_nifti_path(path)) return read_nifti<T>(path, limits, source);
  refuse_foreign_file(path);
  return read_lattice_nrrd<T>(path, limits, source);
}

// The lattice of a volume file without reading its samples: Cartesian for NIfTI, the declared
// one for NRRD (read_nrrd_lattice); nothing when the file cannot be read (reading it says why).
inline std::optional<CosetLattice> read_volume_lattice(const std::filesystem::path& path) {
  if (is_nifti_path(path)) return CosetLattice::cartesian();
  return read_nrrd_lattice(path);
}

extern template LatticeVolume<float> read_nifti<float>(const std::filesystem::path&,
                                                       const NrrdReadLimits&, SourceSamples*);
extern template LatticeVolume<double> read_nifti<double>(const std::filesystem::path&,
                                                         const NrrdReadLimits&, SourceSamples*);

}  // namespace boxgen::runtime
