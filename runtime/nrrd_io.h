// BCC volumes and Cartesian grids as NRRD files, through Teem's nrrd library.
//
// A BCC volume (BccVolume, bcc_volume.h) is a NRRD of dimension 4:
//   type: float or double          encoding: raw (written); any encoding Teem reads (read)
//   sizes: 2 N0 N1 N2              the coset axis fastest, then i, j, k
//   space dimension 3, space directions: none (2h,0,0) (0,2h,0) (0,0,2h)
//   space origin: o                the world position of sample (0, 0, 0, 0)
//   kinds: list domain domain domain
//   lattice:=bcc                   key/value that marks the file as a BCC volume
// so sample (c, i, j, k) is at o + h (2i + c, 2j + c, 2k + c).
//
// A Cartesian grid (CartesianVolume) is a plain 3-D NRRD: sizes N0 N1 N2 (x fastest), space
// directions (sx,0,0) (0,sy,0) (0,0,sz), space origin, kinds domain domain domain; 3D Slicer,
// ParaView and `unu` open it.
//
// Writing goes to a temporary file in the target's directory, which is renamed over the target
// only once it is complete: a failed write never leaves a half-written file behind.
//
// Reading checks everything (magic, dimension, sizes, type, space directions consistent with one
// h, origin, the lattice key, and that the data is all there); any problem is a NrrdError whose
// message is one line naming the file. Reading refuses detached data ("data file:" fields): Teem
// would open whatever file such a header names, even a FIFO or device. Compressed data (gzip,
// bzip2) is Teem's to decode. Teem 1.12 leaks memory on some error paths (a few KB, or the
// decompressor's state for corrupt compressed data: up to a few MB), once per failed read; see
// support/lsan_suppressions.cpp. Teem's state (biff error messages) is global, so every call here
// holds one process-wide lock.
#pragma once
#include <cstdint>
#include <filesystem>
#include <stdexcept>

#include "runtime/bcc_volume.h"
#include "runtime/cartesian_volume.h"

namespace boxgen::runtime {

// A file that cannot be read or written as asked. The message is one line.
struct NrrdError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

struct NrrdReadLimits {
  // Largest data block (in the file's sample type) that reading will allocate. Raw data is also
  // checked against the file's size before anything is allocated; compressed data cannot be, so
  // this bounds what a small hostile file can make us allocate.
  std::uint64_t max_data_bytes = std::uint64_t{1} << 36;
};

// Throws NrrdError (one line) unless `path` names a file in an existing directory: lets a
// program refuse a bad -o before it spends time computing what it would write.
void require_output_directory(const std::filesystem::path& path);

// Throws NrrdError if the file cannot be written (the target is left as it was).
template <class T>
void write_bcc_nrrd(const std::filesystem::path& path, const BccVolume<T>& volume);

// Reads a BCC volume stored as float or double; samples of the other type are converted to T
// (double -> float rounds to nearest). Throws NrrdError (one line) for any problem.
template <class T>
BccVolume<T> read_bcc_nrrd(const std::filesystem::path& path, const NrrdReadLimits& limits = {});

// Throws std::invalid_argument for an inconsistent grid (sizes < 1, values.size() different
// from N0 N1 N2, spacing not finite and > 0, origin not finite) and NrrdError if the file
// cannot be written.
template <class T>
void write_cartesian_nrrd(const std::filesystem::path& path, const CartesianVolume<T>& grid);

extern template void write_bcc_nrrd<float>(const std::filesystem::path&, const BccVolume<float>&);
extern template void write_bcc_nrrd<double>(const std::filesystem::path&, const BccVolume<double>&);
extern template BccVolume<float> read_bcc_nrrd<float>(const std::filesystem::path&, const NrrdReadLimits&);
extern template BccVolume<double> read_bcc_nrrd<double>(const std::filesystem::path&, const NrrdReadLimits&);
extern template void write_cartesian_nrrd<float>(const std::filesystem::path&, const CartesianVolume<float>&);
extern template void write_cartesian_nrrd<double>(const std::filesystem::path&, const CartesianVolume<double>&);

}  // namespace boxgen::runtime
