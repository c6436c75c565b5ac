// The output volume of boxrecon's writing commands (sample, resample, subsample, compare
// --error-volume): its format from its name (.nrrd, .nii, .nii.gz; runtime/volume_output.h) and
// its sample type from --type, one option shared by all of them.
#pragma once
#include <CLI/CLI.hpp>

#include <filesystem>
#include <optional>
#include <span>
#include <string>

#include "runtime/affine.h"
#include "runtime/cartesian_volume.h"
#include "runtime/lattice_volume.h"
#include "runtime/sample_encoding.h"
#include "runtime/source_samples.h"

namespace boxgen::app {

// Adds --type to a command that writes a volume (`what` names the file, e.g. "-o").
CLI::Option* add_type_option(CLI::App* command, std::string& type, const std::string& what);
// --type's value; empty: the format's default (NRRD the command's precision, NIfTI float32).
std::optional<runtime::SampleType> parse_type_option(const std::string& text);

// Before any work: the output may be written, is none of `inputs`, has a known extension, and is
// not NIfTI for a lattice of more than one coset. Throws runtime::NrrdError (one line).
void require_output_volume(const std::filesystem::path& path,
                           std::span<const std::filesystem::path> inputs,
                           const runtime::CosetLattice& lattice);

// Writes the volume or grid (runtime/volume_output.h) in the world of `anatomical` (the
// SourceSamples::anatomical of the volume it came from: its NRRD space, or RAS for NIfTI; an
// oblique volume's `frame`, SourceSamples::frame, composed in; a NIfTI output claims `codes`,
// SourceSamples::nifti_codes, again) and says on stderr how many values an integer --type clamped
// to its range.
template <class T>
void write_output_volume(const std::filesystem::path& path, const runtime::LatticeVolume<T>& volume,
                         std::optional<runtime::SampleType> type,
                         const std::string& anatomical = "",
                         const std::optional<runtime::Affine>& frame = std::nullopt,
                         const runtime::NiftiCodes& codes = {});
template <class T>
void write_output_grid(const std::filesystem::path& path, const runtime::CartesianVolume<T>& grid,
                       std::optional<runtime::SampleType> type, const std::string& anatomical = "",
                       const runtime::NiftiCodes& codes = {});

}  // namespace boxgen::app
