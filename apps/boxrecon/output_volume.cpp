#include "apps/boxrecon/output_volume.h"

#include <fmt/format.h>

#include <iostream>

#include "runtime/nrrd_checks.h"
#include "runtime/volume_output.h"

namespace boxgen::app {

namespace {

void report_clamped(const std::filesystem::path& path, const runtime::VolumeWrite& written) {
  const std::uint64_t clamped = written.clamped;
  const runtime::SampleType type = written.type;
  if (clamped == 0) return;
  std::cerr << fmt::format(
      "boxrecon: note: {} value{} beyond the {} range [{:.9g}, {:.9g}] and clamped to it in "
      "'{}'\n",
      clamped, clamped == 1 ? " was" : "s were", runtime::sample_type_name(type),
      runtime::sample_type_lowest(type), runtime::sample_type_highest(type),
      runtime::nrrd_checks::printable(path.string()));
}

}  // namespace

CLI::Option* add_type_option(CLI::App* command, std::string& type, const std::string& what) {
  return command->add_option(
      "--type", type,
      "the sample type of " + what +
          ": int8 | uint8 | int16 | uint16 | int32 | uint32 | float32 | float64 (default: "
          "float32 for NIfTI, the precision for NRRD); integers are rounded, values beyond the "
          "range clamped (and counted on stderr)");
}

std::optional<runtime::SampleType> parse_type_option(const std::string& text) {
  if (text.empty()) return std::nullopt;
  return runtime::parse_sample_type(text);
}

void require_output_volume(const std::filesystem::path& path,
                           std::span<const std::filesystem::path> inputs,
                           const runtime::CosetLattice& lattice) {
  (void)runtime::require_volume_output(path, inputs, lattice.coset_count(), lattice.name().c_str());
}

template <class T>
void write_output_volume(const std::filesystem::path& path, const runtime::LatticeVolume<T>& volume,
                         std::optional<runtime::SampleType> type, const std::string& anatomical,
                         const std::optional<runtime::Affine>& frame,
                         const runtime::NiftiCodes& codes) {
  report_clamped(path, runtime::write_volume_file(path, volume, type, anatomical, frame, codes));
}

template <class T>
void write_output_grid(const std::filesystem::path& path, const runtime::CartesianVolume<T>& grid,
                       std::optional<runtime::SampleType> type, const std::string& anatomical,
                       const runtime::NiftiCodes& codes) {
  report_clamped(path, runtime::write_grid_file(path, grid, type, anatomical, codes));
}

template void write_output_volume<float>(const std::filesystem::path&,
                                         const runtime::LatticeVolume<float>&,
                                         std::optional<runtime::SampleType>, const std::string&,
                                         const std::optional<runtime::Affine>&,
                                         const runtime::NiftiCodes&);
template void write_output_volume<double>(const std::filesystem::path&,
                                          const runtime::LatticeVolume<double>&,
                                          std::optional<runtime::SampleType>, const std::string&,
                                          const std::optional<runtime::Affine>&,
                                          const runtime::NiftiCodes&);
template void write_output_grid<float>(const std::filesystem::path&,
                                       const runtime::CartesianVolume<float>&,
                                       std::optional<runtime::SampleType>, const std::string&,
                                       const runtime::NiftiCodes&);
template void write_output_grid<double>(const std::filesystem::path&,
                                        const runtime::CartesianVolume<double>&,
                                        std::optional<runtime::SampleType>, const std::string&,
                                        const runtime::NiftiCodes&);

}  // namespace boxgen::app
