// What the NRRD reader (nrrd_io.cpp) checks itself, before and after Teem reads a file, so that
// it believes no header that lies and never lets Teem's words reach a user: the header text
// (magic, detached data, length, sizes and space fields written as Teem would misread them), the
// length of the stored data in every encoding (gzip and bzip2 data are decompressed and counted),
// the declared byte order, and the samples themselves (non-finite, beyond float). Nothing here
// includes Teem. Each check returns "" when the file passes, else why it is refused: one line,
// without the path (the reader adds "cannot read ... 'path': ").
#pragma once
#include <cstdint>
#include <cstdio>
#include <span>
#include <string>
#include <string_view>

#include "runtime/lattice_volume.h"

namespace boxgen::runtime::nrrd_checks {

// Text from a file or path made fit for a one-line message: control characters become '?', and at
// most `limit` characters are kept.
std::string printable(std::string_view text, std::size_t limit = 200);

// Why a read that allocates `bytes` (the file's data and the samples made from it) cannot be
// done: more than the memory this process may still take (support/available_memory.h). Empty
// when it fits (or when the available memory cannot be read).
std::string check_memory_for(std::uint64_t bytes);

// Largest header the reader looks at.
inline constexpr std::size_t kMaxHeaderBytes = std::size_t{1} << 20;

// The header text, read from the file's start: the magic "NRRD000x" (Teem's other formats, PNG,
// PNM, VTK, text tables, stay out), no detached data ("data file:" in any case or spacing: Teem
// would open whatever file it names), the empty line that ends the header within
// kMaxHeaderBytes, and the fields Teem reads loosely: every "sizes" entry a positive integer
// ("23.5" would read as 23, "-3" as a size of zero), every number of "space origin" and "space
// directions" finite.
std::string check_header_text(std::FILE* file, std::uint64_t file_size);

enum class Encoding { Raw, Ascii, Hex, Gzip, Bzip2, Other };

// The data after the header (from byte `data_start`) must be exactly what type and sizes
// describe: `data_bytes` bytes (raw; gzip and bzip2 once decompressed), `sample_count` numbers
// (ascii) or 2 data_bytes hex digits (hex). Gzip data without the gzip magic counts as stored
// uncompressed, as Teem reads it; concatenated gzip members or bzip2 streams count together.
// Encodings it cannot count (Other) pass.
std::string check_data_length(std::FILE* file, long data_start, Encoding encoding,
                              std::uint64_t file_size, std::uint64_t data_bytes,
                              std::uint64_t sample_count);

// The byte order a binary file declares (`declared`, as the header writes it) is the one its data
// is read in; it is refused when that reading is evidently a lie: at least half of the non-zero
// samples not finite or beyond 1e+-150 (double) or 1e+-20 (float), while the other byte order
// makes every sample plausible.
template <class T>
std::string check_byte_order(std::span<const T> samples, std::string_view declared);

// NaN and infinite samples, named by their index and (coset, i, j, k) in a volume of `cosets`
// cosets of `sizes`.
template <class T>
std::string check_finite(std::span<const T> samples, int cosets, const Sizes& sizes);

// Samples read in double that float cannot hold (finite, beyond float's range: converting them
// is undefined).
std::string check_float_range(std::span<const double> samples);

extern template std::string check_byte_order<float>(std::span<const float>, std::string_view);
extern template std::string check_byte_order<double>(std::span<const double>, std::string_view);
extern template std::string check_finite<float>(std::span<const float>, int, const Sizes&);
extern template std::string check_finite<double>(std::span<const double>, int, const Sizes&);

}  // namespace boxgen::runtime::nrrd_checks
