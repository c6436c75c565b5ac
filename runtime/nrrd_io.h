// Lattice volumes and Cartesian grids as NRRD files, through Teem's nrrd library.
//
// A volume on any lattice L = G Z^3 (LatticeVolume, lattice_volume.h), stored as K cosets of
// d Z^3, is a NRRD of dimension 4 (dimension 3 when K = 1):
//   type: float or double (written; read: also signed and unsigned 8, 16 and 32-bit integers)
//   encoding: raw (written); any encoding Teem reads (read)
//   sizes: K N0 N1 N2              the coset axis fastest (N0 N1 N2 when K = 1)
//   space directions: none (dh,0,0) (0,dh,0) (0,0,dh)    (no "none" when K = 1)
//   space origin: o                the world position of lattice point (0, 0, 0)
//   kinds: list domain domain domain
//   lattice:=bcc|fcc|cartesian|custom
//   lattice_rows:=a,b,c; d,e,f; g,h,i        (custom: the rows of G)
//   coset_offsets:=(x,y,z) (x,y,z) ...        (custom, or a named lattice whose cosets are
//                                             stored in another order: off_0 ... off_{K-1})
// so sample (c, i, j, k) is at o + h (d i + off_c.x, d j + off_c.y, d k + off_c.z). A BCC volume
// is sizes 2 N0 N1 N2, space directions none (2h,0,0) (0,2h,0) (0,0,2h), lattice:=bcc: sample
// (c, i, j, k) at o + h (2i + c, 2j + c, 2k + c). A named lattice may
// carry lattice_rows and coset_offsets too (they must then agree with it: the offsets may come in
// another order, which is then the order of the coset axis).
//
// A Cartesian grid (CartesianVolume) is a plain 3-D NRRD: sizes N0 N1 N2 (x fastest), space
// directions (sx,0,0) (0,sy,0) (0,0,sz), space origin, kinds domain domain domain; 3D Slicer,
// ParaView and `unu` open it.
//
// An oblique volume (scanners tilt their slices) has its grid in its own frame, which a map with
// unit columns takes to world: its space directions are that map's columns times the steps (dh
// for a lattice, sx sy sz for a grid), its space origin the world point of sample (0, 0, 0)
// (lattice point 0). Readers take such a file only with NrrdReadLimits::allow_oblique.
//
// Both are written with `space: 3D-right-handed`, or, when the world is tied to a patient, its
// anatomical space (right-anterior-superior, left-anterior-superior, left-posterior-superior):
// the space of the volume they came from, so that readers know its orientation.
//
// Writing follows output_file.h: symbolic links are written through, special files (FIFOs,
// devices) refused, and the data goes to a temporary file in the target's directory, renamed over
// the target only once it is complete: a failed write never leaves a half-written file behind.
//
// Reading checks everything (magic, dimension, sizes, type, space directions consistent with one
// h, origin, the lattice key; nrrd_checks.h checks what Teem does not, before and after Teem reads
// the file) and believes no header that lies: the data must be exactly as long
// as type and sizes say (raw: bytes, ascii: numbers, hex: digits, gzip and bzip2: decompressed
// bytes, counted before Teem decodes them), it is read in the byte order the header
// declares, and a file whose declared byte order is evidently wrong (at least half of the
// non-zero samples not finite or beyond 1e+-150 for double, 1e+-20 for float, while the other
// byte order makes every sample plausible) is refused. Non-finite samples (NaN, +-inf) are refused
// unless NrrdReadLimits::allow_non_finite is set. Any problem is a NrrdError whose message is one
// line naming the file. Reading refuses detached data ("data file:" fields): Teem
// would open whatever file such a header names, even a FIFO or device. Compressed data (gzip,
// bzip2) is Teem's to decode. Teem 1.12 leaks memory on some error paths (a few KB, or the
// decompressor's state for corrupt compressed data: up to a few MB), once per failed read; see
// support/lsan_suppressions.cpp. Teem's state (biff error messages) is global, so every call here
// holds one process-wide lock.
#pragma once
#include <cstdint>
#include <filesystem>
#include <optional>
#include <span>
#include <stdexcept>
#include <string>

#include "runtime/cartesian_volume.h"
#include "runtime/lattice_volume.h"
#include "runtime/sample_encoding.h"
#include "runtime/source_samples.h"

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
  // Accept NaN and infinite samples (a reconstruction near them is NaN or infinite too).
  bool allow_non_finite = false;
  // The lattice the caller needs (a filter's): a file that does not say its lattice where that
  // lattice needs saying (a 3-D NRRD or a missing lattice key for BCC) is refused in its terms
  // ("a bcc volume is a 4-D NRRD"). A file that says another lattice reads as what it says:
  // the filter refuses it (SplineFilter::check_lattice), naming both.
  std::optional<CosetLattice> lattice;
  // Accept an oblique or axis-permuting NIfTI affine (a scanner's tilted slices): the volume is
  // then read in its own frame and the frame's map to world is SourceSamples::frame (the reader
  // needs a SourceSamples to return it). Commands that do not map world points through the frame
  // leave this false: such a file is then refused, naming its affine.
  bool allow_oblique = false;
};

// Throws NrrdError (one line) unless `path` may be written (output_file.h: a regular file, or a
// new file in an existing directory, after following links) and is none of `inputs`: lets a
// program refuse a bad -o before it spends time computing what it would write.
void require_output_file(const std::filesystem::path& path,
                         std::span<const std::filesystem::path> inputs);
// require_output_file(path, {}).
void require_output_directory(const std::filesystem::path& path);

// A volume on any lattice (lattice_volume.h): the layout in the comment at the top. Its space
// is the world's anatomical frame (SourceSamples::anatomical: "RAS", "LAS" or "LPS" write
// right-anterior-superior, left-anterior-superior or left-posterior-superior, so that readers
// know the patient's orientation; "" 3D-right-handed). `frame`: an oblique volume's map from its
// own frame (where the volume's grid lies) to world (SourceSamples::frame): the space directions
// are then its columns times d h, and the space origin the volume's origin mapped to world.
// Throws NrrdError if the file cannot be written, std::invalid_argument for another `anatomical`.
template <class T>
void write_lattice_nrrd(const std::filesystem::path& path, const LatticeVolume<T>& volume,
                        const std::string& anatomical = "",
                        const std::optional<Affine>& frame = std::nullopt);
// The same with `samples` (volume.sample_count() of them, encode_samples) stored in place of the
// volume's own: another sample type (boxrecon's --type).
template <class T>
void write_lattice_nrrd(const std::filesystem::path& path, const LatticeVolume<T>& volume,
                        const EncodedSamples& samples, const std::string& anatomical = "",
                        const std::optional<Affine>& frame = std::nullopt);

// Reads a lattice volume (any lattice; a 3-D NRRD without a lattice key is a Cartesian volume).
// Samples of any type in int8, uint8, int16, uint16, int32, uint32, float, double are converted
// to T (exact, except double -> float and integers beyond 2^24 -> float, which round to nearest);
// `source`, when given, receives the file's type and the samples' range. A Cartesian file may
// have a spacing per axis (anisotropic voxels) and negative ones: such an axis is stored flipped
// (the origin moved to its other end), so that every world point keeps its sample. Throws
// NrrdError (one line) for any problem.
template <class T>
LatticeVolume<T> read_lattice_nrrd(const std::filesystem::path& path,
                                   const NrrdReadLimits& limits = {},
                                   SourceSamples* source = nullptr);

// The lattice a NRRD file declares (its header only: the lattice keys, a plain 3-D NRRD being
// Cartesian), or nothing when the header cannot be read; read_lattice_nrrd then says why.
std::optional<CosetLattice> read_nrrd_lattice(const std::filesystem::path& path);

// Throws std::invalid_argument for an inconsistent grid (sizes < 1, values.size() different
// from N0 N1 N2, spacing not finite and > 0, origin not finite) and NrrdError if the file
// cannot be written. Its space: as write_lattice_nrrd's.
template <class T>
void write_cartesian_nrrd(const std::filesystem::path& path, const CartesianVolume<T>& grid,
                          const std::string& anatomical = "");

extern template void write_lattice_nrrd<float>(const std::filesystem::path&,
                                               const LatticeVolume<float>&, const std::string&,
                                               const std::optional<Affine>&);
extern template void write_lattice_nrrd<double>(const std::filesystem::path&,
                                                const LatticeVolume<double>&, const std::string&,
                                                const std::optional<Affine>&);
extern template void write_lattice_nrrd<float>(const std::filesystem::path&,
                                               const LatticeVolume<float>&, const EncodedSamples&,
                                               const std::string&, const std::optional<Affine>&);
extern template void write_lattice_nrrd<double>(const std::filesystem::path&,
                                                const LatticeVolume<double>&, const EncodedSamples&,
                                                const std::string&, const std::optional<Affine>&);
extern template LatticeVolume<float> read_lattice_nrrd<float>(const std::filesystem::path&,
                                                              const NrrdReadLimits&,
                                                              SourceSamples*);
extern template LatticeVolume<double> read_lattice_nrrd<double>(const std::filesystem::path&,
                                                                const NrrdReadLimits&,
                                                                SourceSamples*);
extern template void write_cartesian_nrrd<float>(const std::filesystem::path&,
                                                 const CartesianVolume<float>&, const std::string&);
extern template void write_cartesian_nrrd<double>(const std::filesystem::path&,
                                                  const CartesianVolume<double>&,
                                                  const std::string&);

}  // namespace boxgen::runtime
