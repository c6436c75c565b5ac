#include "runtime/nrrd_checks.h"

#include <bzlib.h>
#include <zlib.h>

#include <fmt/format.h>

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cmath>
#include <cstring>
#include <limits>
#include <type_traits>
#include <vector>

#include "support/available_memory.h"

namespace boxgen::runtime::nrrd_checks {

std::string printable(std::string_view text, std::size_t limit) {
  std::string out;
  for (char ch : text.substr(0, limit))
    out += (static_cast<unsigned char>(ch) < 0x20 || ch == 0x7f) ? '?' : ch;
  if (text.size() > limit) out += "...";
  return out;
}

std::string check_memory_for(std::uint64_t bytes) {
  const double available = support::available_memory_bytes();
  if (available <= 0 || static_cast<double>(bytes) <= available) return {};
  constexpr double kGiB = 1024.0 * 1024.0 * 1024.0;
  return fmt::format(
      "reading it needs {:.2f} GiB (its data and the samples made from it), more than the {:.2f} "
      "GiB this process may still take (MemAvailable, ulimit -v, cgroup memory.max)",
      static_cast<double>(bytes) / kGiB, available / kGiB);
}

namespace {

// A header line's field name as Teem matches it (any case, any spacing) and its value.
struct Field {
  std::string name;  // lower case, without spaces
  std::string_view value;
};
Field field_of(std::string_view line) {
  const std::size_t colon = line.find(':');
  Field f{{}, colon == std::string_view::npos ? std::string_view{} : line.substr(colon + 1)};
  while (!f.value.empty() && std::isspace(static_cast<unsigned char>(f.value.front())))
    f.value.remove_prefix(1);
  for (char ch : line.substr(0, colon))
    if (!std::isspace(static_cast<unsigned char>(ch)))
      f.name += static_cast<char>(std::tolower(static_cast<unsigned char>(ch)));
  return f;
}

// Why a field Teem would misread is refused, or "": sizes that are not positive integers (Teem
// reads "23.5" as 23 and "-3" as a size it then calls zero), and non-finite numbers in the space
// fields (which Teem reports as inconsistent "space vector coefficients").
std::string check_field(const Field& f) {
  if (f.name == "sizes") {
    std::size_t pos = 0;
    const std::string_view v = f.value;
    while (pos < v.size()) {
      while (pos < v.size() && std::isspace(static_cast<unsigned char>(v[pos]))) ++pos;
      std::size_t end = pos;
      while (end < v.size() && !std::isspace(static_cast<unsigned char>(v[end]))) ++end;
      const std::string_view token = v.substr(pos, end - pos);
      const bool digits = !token.empty() && std::all_of(token.begin(), token.end(), [](char c) {
        return std::isdigit(static_cast<unsigned char>(c)) != 0;
      });
      if (!token.empty() && (!digits || token.find_first_not_of('0') == std::string_view::npos))
        return fmt::format("its sizes '{}' are not all positive integers ('{}')", printable(v, 80),
                           printable(token, 40));
      pos = end;
    }
  }
  if (f.name == "spaceorigin" || f.name == "spacedirections") {
    std::string lower;
    for (char ch : f.value)
      lower += static_cast<char>(std::tolower(static_cast<unsigned char>(ch)));
    if (lower.find("nan") != std::string::npos || lower.find("inf") != std::string::npos)
      return fmt::format("its {} '{}' has a number that is not finite",
                         f.name == "spaceorigin" ? "space origin" : "space directions",
                         printable(f.value, 80));
  }
  return {};
}

// The header as Teem will read it (lines end at "\n", "\r" or "\r\n"; Teem keeps a line only up
// to its first NUL; the header ends at the first empty line), line by line: a line that names a
// detached data file (the field "data file" or "datafile" in any case or spacing, checked loosely,
// so that anything Teem could take for that field is caught) or a field check_field refuses.
// Sets header_complete when the empty line that ends the header lies within `head`.
std::string scan_header(std::string_view head, bool& header_complete) {
  header_complete = false;
  std::size_t pos = 0;
  while (pos < head.size()) {
    std::size_t end = head.find_first_of("\r\n", pos);
    const bool terminated = end != std::string_view::npos;
    if (!terminated) end = head.size();  // scanned too: a later Teem may keep an unterminated line
    std::string_view line = head.substr(pos, end - pos);
    pos = end + 1;
    if (terminated && head[end] == '\r' && pos < head.size() && head[pos] == '\n') ++pos;
    if (terminated && line.empty()) {
      header_complete = true;
      return {};
    }
    line = line.substr(0, line.find('\0'));
    if (line.starts_with("#")) continue;
    std::string squeezed;
    for (char ch : line)
      if (!std::isspace(static_cast<unsigned char>(ch)))
        squeezed += static_cast<char>(std::tolower(static_cast<unsigned char>(ch)));
    if (squeezed.find("datafile:") != std::string::npos)
      return "detached data files ('data file:' in the header) are not supported; keep the data "
             "in the .nrrd file";
    if (line.find(":=") == std::string_view::npos)  // a field, not a key/value pair
      if (std::string why = check_field(field_of(line)); !why.empty()) return why;
  }
  return {};
}

// The file's bytes from its current position in 64 KiB chunks; `used` is how far the consumer
// got in the current chunk.
struct ChunkReader {
  std::FILE* file;
  std::vector<unsigned char> in = std::vector<unsigned char>(1 << 16);
  std::size_t have = 0, used = 0;

  explicit ChunkReader(std::FILE* f) : file(f) { have = std::fread(in.data(), 1, in.size(), file); }
  // Makes unread bytes available; false at the end of the file.
  bool refill() {
    if (used < have) return true;
    have = std::fread(in.data(), 1, in.size(), file);
    used = 0;
    return have > 0;
  }
  bool starts_with_gzip_magic() const { return have >= 2 && in[0] == 0x1f && in[1] == 0x8b; }
};

// One gzip member: adds its decompressed length to `count` (stopping beyond `cap`); returns why
// it does not decompress, or "".
std::string count_gzip_member(ChunkReader& r, std::vector<unsigned char>& out, std::uint64_t cap,
                              std::uint64_t& count) {
  z_stream z{};
  if (inflateInit2(&z, 15 + 16) != Z_OK) return "cannot start zlib";
  int status = Z_OK;
  while (status != Z_STREAM_END && count <= cap && r.refill()) {
    z.next_in = r.in.data() + r.used;
    z.avail_in = static_cast<uInt>(r.have - r.used);
    z.next_out = out.data();
    z.avail_out = static_cast<uInt>(out.size());
    status = inflate(&z, Z_NO_FLUSH);
    r.used = r.have - z.avail_in;
    count += out.size() - z.avail_out;
    if (status != Z_OK && status != Z_STREAM_END && status != Z_BUF_ERROR) break;
  }
  inflateEnd(&z);
  if (status == Z_STREAM_END || count > cap) return {};
  return status == Z_OK || status == Z_BUF_ERROR ? "its gzip data end too early"
                                                 : "its gzip data are corrupt";
}

// One bzip2 stream, as count_gzip_member.
std::string count_bzip2_stream(ChunkReader& r, std::vector<unsigned char>& out, std::uint64_t cap,
                               std::uint64_t& count) {
  bz_stream b{};
  if (BZ2_bzDecompressInit(&b, 0, 0) != BZ_OK) return "cannot start bzip2";
  int status = BZ_OK;
  while (status != BZ_STREAM_END && count <= cap && r.refill()) {
    b.next_in = reinterpret_cast<char*>(r.in.data() + r.used);
    b.avail_in = static_cast<unsigned>(r.have - r.used);
    b.next_out = reinterpret_cast<char*>(out.data());
    b.avail_out = static_cast<unsigned>(out.size());
    status = BZ2_bzDecompress(&b);
    r.used = r.have - b.avail_in;
    count += out.size() - b.avail_out;
    if (status != BZ_OK && status != BZ_STREAM_END) break;
  }
  BZ2_bzDecompressEnd(&b);
  if (status == BZ_STREAM_END || count > cap) return {};
  return status == BZ_OK ? "its bzip2 data end too early" : "its bzip2 data are corrupt";
}

// The decompressed length of the gzip or bzip2 data from the file's current position, counted up
// to `cap` bytes (counting stops beyond it). As Teem's reader does, gzip data without the gzip
// magic is taken as stored uncompressed; concatenated gzip members or bzip2 streams count
// together. Sets `problem` for data that does not decompress.
void count_decompressed(std::FILE* file, bool gzip, std::uint64_t cap, std::uint64_t& count,
                        std::string& problem) {
  ChunkReader r(file);
  count = 0;
  if (gzip && !r.starts_with_gzip_magic()) {  // not gzip: Teem reads it as it is
    for (count = r.have; count <= cap;) {
      r.used = r.have;
      if (!r.refill()) break;
      count += r.have;
    }
    return;
  }
  std::vector<unsigned char> out(1 << 16);
  while (count <= cap && r.refill()) {  // one gzip member or bzip2 stream per pass
    problem = gzip ? count_gzip_member(r, out, cap, count) : count_bzip2_stream(r, out, cap, count);
    if (!problem.empty()) return;
  }
}

// The amount of data after the header, counted in the unit the encoding stores: bytes (raw,
// and decompressed bytes for gzip and bzip2, counted up to `cap`), numbers (ascii: whitespace-
// separated tokens) or hex digits (hex). Returns false for an encoding it cannot count.
bool count_stored_data(std::FILE* file, long data_start, Encoding encoding, std::uint64_t file_size,
                       std::uint64_t cap, std::uint64_t& count, std::string& problem) {
  const auto start = static_cast<std::uint64_t>(std::max(0L, data_start));
  if (encoding == Encoding::Raw) {
    count = file_size - std::min(file_size, start);
    return true;
  }
  if (encoding == Encoding::Gzip || encoding == Encoding::Bzip2) {
    if (std::fseek(file, data_start, SEEK_SET) != 0)
      problem = std::strerror(errno);
    else
      count_decompressed(file, encoding == Encoding::Gzip, cap, count, problem);
    return true;
  }
  const bool ascii = encoding == Encoding::Ascii;
  if (!ascii && encoding != Encoding::Hex) return false;
  if (std::fseek(file, data_start, SEEK_SET) != 0) {
    problem = std::strerror(errno);
    return true;
  }
  count = 0;
  bool in_token = false;
  char buffer[65536];
  for (std::size_t got; (got = std::fread(buffer, 1, sizeof buffer, file)) > 0;)
    for (std::size_t i = 0; i < got; ++i) {
      const auto ch = static_cast<unsigned char>(buffer[i]);
      const bool space = std::isspace(ch) != 0;
      if (ascii) {
        if (!space && !in_token) ++count;
        in_token = !space;
      } else if (std::isxdigit(ch)) {
        ++count;
      } else if (!space) {
        problem = "its hex data holds a character that is not a hex digit";
        return true;
      }
    }
  return true;
}

// Reverses the bytes of x: the sample as the other byte order would read it.
template <class T>
T byte_swapped(T x) {
  unsigned char bytes[sizeof(T)];
  std::memcpy(bytes, &x, sizeof(T));
  std::reverse(bytes, bytes + sizeof(T));
  std::memcpy(&x, bytes, sizeof(T));
  return x;
}

// A value no sampled field holds, but a byte-swapped one typically does: not finite, or a
// magnitude far outside any physical scale (1.0 byte-swapped is about 3e-317 as a double and
// 5e-41 as a float).
template <class T>
bool implausible(T x) {
  constexpr double kScale = std::is_same_v<T, float> ? 1e20 : 1e150;
  const double m = std::fabs(static_cast<double>(x));
  return !std::isfinite(m) || (m != 0 && (m < 1 / kScale || m > kScale));
}

}  // namespace

template <class T>
std::string check_byte_order(std::span<const T> samples, std::string_view declared_order) {
  std::size_t nonzero = 0, declared = 0, swapped = 0;
  for (const T x : samples) {
    if (x == 0) continue;
    ++nonzero;
    declared += implausible(x) ? 1 : 0;
    swapped += implausible(byte_swapped(x)) ? 1 : 0;
  }
  if (declared == 0 || swapped != 0 || 2 * declared < nonzero) return {};
  return fmt::format(
      "its data do not match the byte order its header declares ('endian: {}'): read so, {} of its "
      "{} non-zero "
      "samples are not finite or beyond 1e+-{}, and none are in the other byte order; correct its "
      "'endian' field",
      printable(declared_order, 80), declared, nonzero, std::is_same_v<T, float> ? 20 : 150);
}

std::string check_header_text(std::FILE* file, std::uint64_t file_size) {
  std::string head(std::min<std::uint64_t>(file_size, kMaxHeaderBytes), '\0');
  head.resize(std::fread(head.data(), 1, head.size(), file));
  if (!head.starts_with("NRRD000") || head.size() < 8 ||
      !std::isdigit(static_cast<unsigned char>(head[7])))
    return "not a NRRD file (it does not start with the magic 'NRRD000x')";
  bool header_complete = false;
  if (std::string why = scan_header(head, header_complete); !why.empty()) return why;
  if (!header_complete && file_size > head.size())
    return fmt::format("its header is longer than {} bytes", kMaxHeaderBytes);
  return {};
}

// The data must be exactly what the header describes: a wrong type or too few sizes over the
// right data would otherwise read as other numbers.
std::string check_data_length(std::FILE* file, long data_start, Encoding encoding,
                              std::uint64_t file_size, std::uint64_t data_bytes,
                              std::uint64_t sample_count) {
  std::uint64_t stored = 0;
  std::string problem;
  const bool raw = encoding == Encoding::Raw, ascii = encoding == Encoding::Ascii,
             hex = encoding == Encoding::Hex;
  const std::uint64_t expected = ascii ? sample_count : hex ? 2 * data_bytes : data_bytes;
  if (!count_stored_data(file, data_start, encoding, file_size, expected, stored, problem))
    return {};
  if (!problem.empty()) return problem;
  const char* unit = raw     ? "bytes of raw data"
                     : ascii ? "numbers"
                     : hex   ? "hex digits"
                             : "bytes of decompressed data";
  if (stored < expected)
    return (fmt::format("the file is truncated: its header announces {} {}, but only {} follow it",
                        expected, unit, stored));
  if (stored > expected)
    return (
        fmt::format("{}{} {} follow its header, which announces {} (its type and sizes must "
                    "describe the data exactly)",
                    raw || ascii || hex ? "" : "more than ",
                    raw || ascii || hex ? stored : expected, unit, expected));
  return {};
}

template <class T>
std::string check_finite(std::span<const T> samples, int cosets, const Sizes& n) {
  for (std::size_t s = 0; s < samples.size(); ++s) {
    if (std::isfinite(samples[s])) continue;
    const auto k = static_cast<std::size_t>(cosets);
    const std::size_t cell = s / k, n0 = static_cast<std::size_t>(n[0]),
                      n1 = static_cast<std::size_t>(n[1]);
    return fmt::format(
        "its sample {} (coset {}, {}, {}, {}) is {}; non-finite samples are refused unless "
        "allowed (boxrecon --allow-nonfinite)",
        s, s % k, cell % n0, cell / n0 % n1, cell / n0 / n1, static_cast<double>(samples[s]));
  }
  return {};
}

std::string check_float_range(std::span<const double> samples) {
  for (std::size_t s = 0; s < samples.size(); ++s)
    if (std::isfinite(samples[s]) && std::fabs(samples[s]) > std::numeric_limits<float>::max())
      return fmt::format(
          "its sample {} = {} is beyond the range of float; read it in double precision", s,
          samples[s]);
  return {};
}

template std::string check_byte_order<float>(std::span<const float>, std::string_view);
template std::string check_byte_order<double>(std::span<const double>, std::string_view);
template std::string check_finite<float>(std::span<const float>, int, const Sizes&);
template std::string check_finite<double>(std::span<const double>, int, const Sizes&);

}  // namespace boxgen::runtime::nrrd_checks
