#include "runtime/nrrd_io.h"

#include "support/output_file.h"

#include <bzlib.h>
#include <fcntl.h>
#include <sys/stat.h>
#include <teem/biff.h>
#include <teem/nrrd.h>
#include <unistd.h>
#include <zlib.h>

#include <fmt/format.h>

#include <algorithm>
#include <atomic>
#include <cctype>
#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <functional>
#include <limits>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <string_view>
#include <type_traits>

namespace boxgen::runtime {

using support::check_output_file;
using support::OutputFileError;
using support::write_output_file;

namespace {

namespace fs = std::filesystem;

// Teem reports errors through biff, a global message store: one lock for every Teem call.
std::mutex& teem_mutex() {
  static std::mutex mutex;
  return mutex;
}

// Text from a file or path, made fit for a one-line message: control characters become '?',
// and at most `limit` characters are kept.
std::string printable(std::string_view text, std::size_t limit = 200) {
  std::string out;
  for (char ch : text.substr(0, limit))
    out += (static_cast<unsigned char>(ch) < 0x20 || ch == 0x7f) ? '?' : ch;
  if (text.size() > limit) out += "...";
  return out;
}

// Teem's biff message is several lines, outermost call first ("[nrrd] nrrdRead: trouble", ...,
// "[nrrd] _nrrdEncodingRaw_read: fread got only ..."): keep the innermost line that says
// something, without its "[nrrd] function: " prefix.
std::string teem_error() {
  char* raw = biffGetDone(NRRD);
  const std::string all = raw ? raw : "";
  std::free(raw);
  std::string best;
  std::size_t start = 0;
  while (start < all.size()) {
    std::size_t end = all.find('\n', start);
    if (end == std::string::npos) end = all.size();
    std::string_view line(all.data() + start, end - start);
    start = end + 1;
    if (line.starts_with("[")) {
      const std::size_t bracket = line.find("] ");
      if (bracket != std::string_view::npos) line.remove_prefix(bracket + 2);
      const std::size_t colon = line.find(':');
      if (colon != std::string_view::npos &&
          line.substr(0, colon).find(' ') == std::string_view::npos)
        line.remove_prefix(colon + 1);
    }
    while (!line.empty() && std::isspace(static_cast<unsigned char>(line.front())))
      line.remove_prefix(1);
    while (!line.empty() && std::isspace(static_cast<unsigned char>(line.back())))
      line.remove_suffix(1);
    if (!line.empty()) best = std::string(line);
  }
  return best.empty() ? std::string("Teem reported an unspecified error") : printable(best);
}

struct NrrdDeleter {
  void operator()(Nrrd* n) const { nrrdNuke(n); }  // frees the data too
};
struct NrrdShellDeleter {
  void operator()(Nrrd* n) const { nrrdNix(n); }  // the data belongs to someone else
};
struct IoStateDeleter {
  void operator()(NrrdIoState* s) const { nrrdIoStateNix(s); }
};
struct FileCloser {
  void operator()(std::FILE* f) const { std::fclose(f); }
};
using NrrdOwner = std::unique_ptr<Nrrd, NrrdDeleter>;
using NrrdShell = std::unique_ptr<Nrrd, NrrdShellDeleter>;
using IoState = std::unique_ptr<NrrdIoState, IoStateDeleter>;
using File = std::unique_ptr<std::FILE, FileCloser>;

template <class T>
constexpr int teem_type() {
  return std::is_same_v<T, float> ? nrrdTypeFloat : nrrdTypeDouble;
}

// ---------------------------------------------------------------------------------------------
// Writing

}  // namespace

void require_output_directory(const fs::path& path) { require_output_file(path, {}); }

void require_output_file(const fs::path& path, std::span<const fs::path> inputs) {
  try {
    (void)check_output_file(path, inputs);
  } catch (const OutputFileError& e) {
    throw NrrdError(e.what());
  }
}

namespace {

// output_file.h's write (links followed, special files refused, temporary file then rename),
// with its errors as NrrdError. Teem's own message explains a failed nrrdWrite.
void write_atomically(const fs::path& path, const std::function<bool(std::FILE*)>& write) {
  try {
    write_output_file(path, write, [] { return teem_error(); });
  } catch (const OutputFileError& e) {
    throw NrrdError(e.what());
  }
}

bool write_nrrd(std::FILE* file, const Nrrd* nrrd) {
  IoState io(nrrdIoStateNew());
  if (!io) return false;
  io->format = nrrdFormatNRRD;
  io->encoding = nrrdEncodingRaw;
  return nrrdWrite(file, nrrd, io.get()) == 0;
}

// Wraps `data` (not copied, not freed) in a Nrrd with the given sizes, space directions and
// origin in a 3-D right-handed space.
template <class T>
NrrdShell wrap(const T* data, unsigned dim, const std::size_t* sizes) {
  NrrdShell nrrd(nrrdNew());
  if (!nrrd || nrrdWrap_nva(nrrd.get(), const_cast<T*>(data), teem_type<T>(), dim, sizes) != 0 ||
      nrrdSpaceSet(nrrd.get(), nrrdSpace3DRightHanded) != 0)
    throw NrrdError("cannot describe the volume to Teem: " + teem_error());
  for (unsigned a = 0; a < dim; ++a)
    for (int b = 0; b < 3; ++b) nrrd->axis[a].spaceDirection[b] = AIR_NAN;
  return nrrd;
}

void set_origin(Nrrd* nrrd, const Vec3& origin) {
  double o[3] = {origin[0], origin[1], origin[2]};
  if (nrrdSpaceOriginSet(nrrd, o) != 0)
    throw NrrdError("cannot describe the volume to Teem: " + teem_error());
}

// ---------------------------------------------------------------------------------------------
// Reading

constexpr std::size_t kMaxHeaderBytes = std::size_t{1} << 20;

// The header as Teem will read it (lines end at "\n", "\r" or "\r\n"; Teem keeps a line only up
// to its first NUL; the header ends at the first empty line). Returns true if a line names a
// detached data file: the field "data file" or "datafile" in any case or spacing (checked
// loosely, so that anything Teem could take for that field is caught). Sets header_complete when
// the empty line that ends the header lies within `head`.
bool header_names_data_file(std::string_view head, bool& header_complete) {
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
      return false;
    }
    line = line.substr(0, line.find('\0'));
    if (line.starts_with("#")) continue;
    std::string squeezed;
    for (char ch : line)
      if (!std::isspace(static_cast<unsigned char>(ch)))
        squeezed += static_cast<char>(std::tolower(static_cast<unsigned char>(ch)));
    if (squeezed.find("datafile:") != std::string::npos) return true;
  }
  return false;
}

// The value of key/value `key`, or nothing.
std::optional<std::string> key_value(const Nrrd* nrrd, const char* key) {
  char* value = nrrdKeyValueGet(nrrd, key);
  if (!value) return std::nullopt;
  std::string text = value;
  std::free(value);
  return text;
}

struct VolumeHeader {
  CosetLattice lattice = CosetLattice::bcc();
  Sizes sizes;
  double h;
  Vec3 origin;
  int type;  // nrrdTypeFloat or nrrdTypeDouble
  std::uint64_t data_bytes;
};

// Checks that `nrrd` describes a BCC volume; returns what it says or an error text.
std::string check_bcc_header(const Nrrd* nrrd, VolumeHeader& header) {
  // A volume of another lattice is named as such first, before its sizes disagree with BCC's.
  if (const auto lattice = key_value(nrrd, "lattice"); lattice && *lattice != "bcc")
    return fmt::format("its lattice is '{}', not 'bcc'", printable(*lattice, 40));
  if (nrrd->dim != 4)
    return fmt::format(
        "it has dimension {}; a BCC volume is a 4-D NRRD (sizes 2 N0 N1 N2, the coset axis first)",
        nrrd->dim);
  if (nrrd->axis[0].size != 2)
    return fmt::format("axis 0 has size {}; the coset axis of a BCC volume must have size 2",
                       nrrd->axis[0].size);
  std::uint64_t count = 2;
  for (int a = 0; a < 3; ++a) {
    const std::size_t n = nrrd->axis[a + 1].size;
    if (n < 1 || n > static_cast<std::size_t>(BccVolume<double>::kMaxSize))
      return fmt::format("axis {} has size {} (each must be in 1..{})", a + 1, n,
                         BccVolume<double>::kMaxSize);
    header.sizes[a] = static_cast<int>(n);
    count *= n;
    if (count > BccVolume<double>::kMaxSamples)
      return fmt::format("its {} x {} x {} x {} samples are too many (at most {})",
                         nrrd->axis[0].size, nrrd->axis[1].size, nrrd->axis[2].size,
                         nrrd->axis[3].size, BccVolume<double>::kMaxSamples);
  }
  if (nrrd->type != nrrdTypeFloat && nrrd->type != nrrdTypeDouble)
    return fmt::format("its sample type '{}' is not supported (float or double)",
                       printable(airEnumStr(nrrdType, nrrd->type)));
  header.type = nrrd->type;
  header.data_bytes = count * (nrrd->type == nrrdTypeFloat ? 4 : 8);

  if (nrrd->spaceDim != 3)
    return "it has no 3-D space directions; a BCC volume needs 'space directions: none (2h,0,0) "
           "(0,2h,0) (0,0,2h)'";
  for (int b = 0; b < 3; ++b)
    if (!std::isnan(nrrd->axis[0].spaceDirection[b]))
      return "axis 0 (the coset axis) must have the space direction 'none'";
  const double d = nrrd->axis[1].spaceDirection[0];
  bool consistent = std::isfinite(d) && d / 2 > 0;  // h = d/2 must not underflow to 0
  for (int a = 0; a < 3 && consistent; ++a)
    for (int b = 0; b < 3; ++b) {
      const double v = nrrd->axis[a + 1].spaceDirection[b];
      const double expected = a == b ? d : 0.0;
      // A relative tolerance admits files whose writer printed 2h with fewer digits.
      if (!std::isfinite(v) || std::fabs(v - expected) > 1e-9 * d) consistent = false;
    }
  if (!consistent) {
    const auto& s = nrrd->axis;
    return fmt::format(
        "its space directions ({},{},{}) ({},{},{}) ({},{},{}) are not (2h,0,0) (0,2h,0) (0,0,2h) "
        "for one h > 0",
        s[1].spaceDirection[0], s[1].spaceDirection[1], s[1].spaceDirection[2],
        s[2].spaceDirection[0], s[2].spaceDirection[1], s[2].spaceDirection[2],
        s[3].spaceDirection[0], s[3].spaceDirection[1], s[3].spaceDirection[2]);
  }
  header.h = d / 2;
  for (int b = 0; b < 3; ++b) {
    header.origin[b] = nrrd->spaceOrigin[b];
    if (!std::isfinite(header.origin[b])) return "its space origin is missing or not finite";
  }

  char* lattice = nrrdKeyValueGet(nrrd, "lattice");
  const std::string value = lattice ? lattice : "";
  const bool present = lattice != nullptr;
  std::free(lattice);
  if (!present) return "the key/value 'lattice:=bcc' that marks a BCC volume is missing";
  if (value != "bcc") return fmt::format("its lattice is '{}', not 'bcc'", printable(value, 40));
  return {};
}

// "(x,y,z) (x,y,z) ..." as written by CosetLattice::offsets_text.
std::optional<std::vector<Offset>> parse_offsets(std::string_view text) {
  std::vector<Offset> offsets;
  std::size_t pos = 0;
  while (true) {
    while (pos < text.size() && std::isspace(static_cast<unsigned char>(text[pos]))) ++pos;
    if (pos == text.size()) break;
    if (text[pos] != '(') return std::nullopt;
    const std::size_t close = text.find(')', pos);
    if (close == std::string_view::npos) return std::nullopt;
    std::string_view inner = text.substr(pos + 1, close - pos - 1);
    Offset o{};
    for (int a = 0; a < 3; ++a) {
      const std::size_t comma = inner.find(',');
      if ((comma == std::string_view::npos) != (a == 2)) return std::nullopt;
      std::string_view entry = inner.substr(0, comma);
      inner.remove_prefix(comma == std::string_view::npos ? inner.size() : comma + 1);
      while (!entry.empty() && std::isspace(static_cast<unsigned char>(entry.front())))
        entry.remove_prefix(1);
      while (!entry.empty() && std::isspace(static_cast<unsigned char>(entry.back())))
        entry.remove_suffix(1);
      const auto [end, error] = std::from_chars(entry.data(), entry.data() + entry.size(), o[a]);
      if (entry.empty() || error != std::errc() || end != entry.data() + entry.size())
        return std::nullopt;
    }
    offsets.push_back(o);
    if (offsets.size() > 1u << 18) return std::nullopt;
    pos = close + 1;
  }
  return offsets;
}

// The lattice a file declares: lattice:=bcc|fcc|cartesian|custom, with lattice_rows:= and
// coset_offsets:= for custom (optional for the named lattices: they must then agree). A 3-D NRRD
// without the key is a Cartesian grid.
std::string file_lattice(const Nrrd* nrrd, VolumeHeader& header) {
  const auto name = key_value(nrrd, "lattice");
  const auto rows = key_value(nrrd, "lattice_rows");
  const auto offsets = key_value(nrrd, "coset_offsets");
  if (!name && nrrd->dim != 3)
    return "the key/value 'lattice:=bcc|fcc|cartesian|custom' that marks a lattice volume is "
           "missing";
  const std::string value = name.value_or("cartesian");
  try {
    if (value == "custom") {
      if (!rows)
        return "its lattice is 'custom' but the key/value 'lattice_rows:=a,b,c; d,e,f; g,h,i' is "
               "missing";
      if (!offsets)
        return "its lattice is 'custom' but the key/value 'coset_offsets:=(x,y,z) ...' is missing";
    } else if (value != "bcc" && value != "fcc" && value != "cartesian") {
      return fmt::format("its lattice is '{}', not bcc, fcc, cartesian or custom",
                         printable(value, 40));
    }
    CosetLattice lattice =
        value == "custom" ? CosetLattice::parse(*rows) : CosetLattice::parse(value);
    if (value != "custom" && rows) {
      const CosetLattice declared = CosetLattice::parse(*rows);
      if (declared.name() != value)
        return fmt::format("its lattice_rows '{}' do not generate the {} lattice",
                           printable(*rows, 80), value);
    }
    if (offsets) {
      const auto parsed = parse_offsets(*offsets);
      if (!parsed)
        return fmt::format("its coset_offsets '{}' are not of the form '(x,y,z) (x,y,z) ...'",
                           printable(*offsets, 80));
      lattice = lattice.with_offsets(*parsed);
    }
    header.lattice = lattice;
  } catch (const std::invalid_argument& e) {
    return printable(e.what());
  }
  return {};
}

// Checks that `nrrd` describes a lattice volume (nrrd_io.h); returns what it says or an error text.
std::string check_lattice_header(const Nrrd* nrrd, VolumeHeader& header) {
  if (std::string why = file_lattice(nrrd, header); !why.empty()) return why;
  const int k = header.lattice.coset_count(), d = header.lattice.period();
  const std::string& name = header.lattice.name();
  unsigned first = 0;  // the first domain axis
  if (nrrd->dim == 4) {
    if (nrrd->axis[0].size != static_cast<std::size_t>(k))
      return fmt::format("axis 0 has size {}; the coset axis of a {} volume must have size K = {}",
                         nrrd->axis[0].size, name, k);
    first = 1;
  } else if (nrrd->dim != 3 || k != 1) {
    return fmt::format(
        "it has dimension {}; a {} volume is a 4-D NRRD (sizes {} N0 N1 N2, the coset axis "
        "first){}",
        nrrd->dim, name, k, k == 1 ? " or a 3-D one" : "");
  }
  std::uint64_t count = static_cast<std::uint64_t>(k);
  for (int a = 0; a < 3; ++a) {
    const std::size_t n = nrrd->axis[first + a].size;
    if (n < 1 || n > static_cast<std::size_t>(LatticeVolume<double>::kMaxSize))
      return fmt::format("axis {} has size {} (each must be in 1..{})", first + a, n,
                         LatticeVolume<double>::kMaxSize);
    header.sizes[a] = static_cast<int>(n);
    count *= n;
    if (count > LatticeVolume<double>::kMaxSamples)
      return fmt::format("its samples are too many (at most {})",
                         LatticeVolume<double>::kMaxSamples);
  }
  if (nrrd->type != nrrdTypeFloat && nrrd->type != nrrdTypeDouble)
    return fmt::format("its sample type '{}' is not supported (float or double)",
                       printable(airEnumStr(nrrdType, nrrd->type)));
  header.type = nrrd->type;
  header.data_bytes = count * (nrrd->type == nrrdTypeFloat ? 4 : 8);
  if (nrrd->spaceDim != 3)
    return fmt::format(
        "it has no 3-D space directions; a {} volume needs (dh,0,0) (0,dh,0) (0,0,dh), d = {}",
        name, d);
  if (first == 1)
    for (int b = 0; b < 3; ++b)
      if (!std::isnan(nrrd->axis[0].spaceDirection[b]))
        return "axis 0 (the coset axis) must have the space direction 'none'";
  const double step = nrrd->axis[first].spaceDirection[0];
  bool consistent = std::isfinite(step) && step / d > 0;
  for (int a = 0; a < 3 && consistent; ++a)
    for (int b = 0; b < 3; ++b) {
      const double v = nrrd->axis[first + a].spaceDirection[b];
      if (!std::isfinite(v) || std::fabs(v - (a == b ? step : 0.0)) > 1e-9 * step)
        consistent = false;
    }
  if (!consistent)
    return fmt::format(
        "its space directions are not (dh,0,0) (0,dh,0) (0,0,dh) for one h > 0 (d = {} for the {} "
        "lattice)",
        d, name);
  header.h = step / d;
  for (int b = 0; b < 3; ++b) {
    header.origin[b] = nrrd->spaceOrigin[b];
    if (!std::isfinite(header.origin[b])) return "its space origin is missing or not finite";
  }
  return {};
}

// Where and how the data of an attached NRRD is stored, as Teem read it from the header.
struct DataLayout {
  const NrrdEncoding* encoding = nullptr;
  long start = -1;                // file offset of the first data byte (the header's end)
  int endian = airEndianUnknown;  // the byte order the header declares (binary encodings)
};

// Reads `file` (from its start) into `nrrd`, header only or whole; returns an error text or "".
std::string teem_read(std::FILE* file, Nrrd* nrrd, bool header_only, DataLayout& layout) {
  std::rewind(file);
  IoState io(nrrdIoStateNew());
  if (!io) return "out of memory";
  io->skipData = header_only ? 1 : 0;
  if (nrrdRead(nrrd, file, io.get()) != 0) return teem_error();
  if (io->format != nrrdFormatNRRD) return "not a NRRD file";
  if (io->dataFNArr && io->dataFNArr->len != 0)
    return "detached data files are not supported; keep the data in the .nrrd file";
  // Skipped lines or bytes would hide data the exact size check below could not account for.
  if (io->lineSkip != 0 || io->byteSkip != 0)
    return "'line skip' and 'byte skip' are not supported; the data must follow the header";
  layout.encoding = io->encoding;
  layout.endian = io->endian;
  layout.start = header_only ? std::ftell(file) : layout.start;
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
bool count_stored_data(std::FILE* file, const DataLayout& layout, std::uint64_t file_size,
                       std::uint64_t cap, std::uint64_t& count, std::string& problem) {
  const auto start = static_cast<std::uint64_t>(std::max(0L, layout.start));
  if (layout.encoding == nrrdEncodingRaw) {
    count = file_size - std::min(file_size, start);
    return true;
  }
  if (layout.encoding == nrrdEncodingGzip || layout.encoding == nrrdEncodingBzip2) {
    if (std::fseek(file, layout.start, SEEK_SET) != 0)
      problem = std::strerror(errno);
    else
      count_decompressed(file, layout.encoding == nrrdEncodingGzip, cap, count, problem);
    return true;
  }
  const bool ascii = layout.encoding == nrrdEncodingAscii;
  if (!ascii && layout.encoding != nrrdEncodingHex) return false;
  if (std::fseek(file, layout.start, SEEK_SET) != 0) {
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

// The byte order a binary file declares is the one its data is read in; it is refused when that
// reading is evidently a lie: at least half of the non-zero samples implausible, while the other
// byte order makes every sample plausible.
template <class T>
std::string check_byte_order(const T* data, std::size_t count, int endian) {
  std::size_t nonzero = 0, declared = 0, swapped = 0;
  for (std::size_t s = 0; s < count; ++s) {
    if (data[s] == 0) continue;
    ++nonzero;
    declared += implausible(data[s]) ? 1 : 0;
    swapped += implausible(byte_swapped(data[s])) ? 1 : 0;
  }
  if (declared == 0 || swapped != 0 || 2 * declared < nonzero) return {};
  return fmt::format(
      "its data do not match the byte order its header declares ('endian: {}'): read so, {} of its "
      "{} non-zero "
      "samples are not finite or beyond 1e+-{}, and none are in the other byte order; correct its "
      "'endian' field",
      printable(airEnumStr(airEndian, endian)), declared, nonzero,
      std::is_same_v<T, float> ? 20 : 150);
}

}  // namespace

template <class T>
void write_bcc_nrrd(const fs::path& path, const BccVolume<T>& volume) {
  std::lock_guard lock(teem_mutex());
  const Sizes& n = volume.sizes();
  const std::size_t sizes[4] = {2, static_cast<std::size_t>(n[0]), static_cast<std::size_t>(n[1]),
                                static_cast<std::size_t>(n[2])};
  NrrdShell nrrd = wrap(volume.samples().data(), 4, sizes);
  nrrd->axis[0].kind = nrrdKindList;
  for (int a = 0; a < 3; ++a) {
    nrrd->axis[a + 1].kind = nrrdKindDomain;
    for (int b = 0; b < 3; ++b)
      nrrd->axis[a + 1].spaceDirection[b] = a == b ? 2 * volume.spacing() : 0.0;
  }
  set_origin(nrrd.get(), volume.origin());
  if (nrrdKeyValueAdd(nrrd.get(), "lattice", "bcc") != 0)
    throw NrrdError("cannot describe the volume to Teem: " + teem_error());
  write_atomically(path, [&](std::FILE* file) { return write_nrrd(file, nrrd.get()); });
}

template <class T>
void write_lattice_nrrd(const fs::path& path, const LatticeVolume<T>& volume) {
  std::lock_guard lock(teem_mutex());
  const Sizes& n = volume.sizes();
  const CosetLattice& lattice = volume.lattice();
  const int k = volume.coset_count();
  const double step = lattice.period() * volume.spacing();
  // K = 1: a plain 3-D NRRD, which any NRRD reader takes for what it is.
  const unsigned first = k == 1 ? 0 : 1, dim = 3 + first;
  const std::size_t sizes[4] = {
      static_cast<std::size_t>(k == 1 ? n[0] : k), static_cast<std::size_t>(k == 1 ? n[1] : n[0]),
      static_cast<std::size_t>(k == 1 ? n[2] : n[1]), static_cast<std::size_t>(n[2])};
  NrrdShell nrrd = wrap(volume.samples().data(), dim, sizes);
  if (first == 1) nrrd->axis[0].kind = nrrdKindList;
  for (unsigned a = 0; a < 3; ++a) {
    nrrd->axis[first + a].kind = nrrdKindDomain;
    for (unsigned b = 0; b < 3; ++b) nrrd->axis[first + a].spaceDirection[b] = a == b ? step : 0.0;
  }
  set_origin(nrrd.get(), volume.origin());
  bool ok = nrrdKeyValueAdd(nrrd.get(), "lattice", lattice.name().c_str()) == 0;
  const bool custom = lattice.name() == "custom";
  if (ok && custom)
    ok = nrrdKeyValueAdd(nrrd.get(), "lattice_rows", lattice.rows_text().c_str()) == 0;
  // A named lattice's offsets are implied unless the volume stores its cosets in another order.
  if (ok && (custom || !(lattice == CosetLattice::parse(lattice.name()))))
    ok = nrrdKeyValueAdd(nrrd.get(), "coset_offsets", lattice.offsets_text().c_str()) == 0;
  if (!ok) throw NrrdError("cannot describe the volume to Teem: " + teem_error());
  write_atomically(path, [&](std::FILE* file) { return write_nrrd(file, nrrd.get()); });
}

template <class T>
void write_cartesian_nrrd(const fs::path& path, const CartesianVolume<T>& grid) {
  std::uint64_t count = 1;
  for (int a = 0; a < 3; ++a) {
    if (grid.sizes[a] < 1)
      throw std::invalid_argument(
          fmt::format("Cartesian grid size {} on axis {} must be at least 1", grid.sizes[a], a));
    count *= static_cast<std::uint64_t>(grid.sizes[a]);
    if (!std::isfinite(grid.spacing[a]) || grid.spacing[a] <= 0)
      throw std::invalid_argument(fmt::format(
          "Cartesian grid spacing {} on axis {} must be finite and positive", grid.spacing[a], a));
    if (!std::isfinite(grid.origin[a]))
      throw std::invalid_argument(fmt::format("Cartesian grid origin on axis {} is not finite", a));
  }
  if (count != grid.values.size())
    throw std::invalid_argument(fmt::format("Cartesian grid of {} x {} x {} holds {} values",
                                            grid.sizes[0], grid.sizes[1], grid.sizes[2],
                                            grid.values.size()));
  std::lock_guard lock(teem_mutex());
  const std::size_t sizes[3] = {static_cast<std::size_t>(grid.sizes[0]),
                                static_cast<std::size_t>(grid.sizes[1]),
                                static_cast<std::size_t>(grid.sizes[2])};
  NrrdShell nrrd = wrap(grid.values.data(), 3, sizes);
  for (int a = 0; a < 3; ++a) {
    nrrd->axis[a].kind = nrrdKindDomain;
    for (int b = 0; b < 3; ++b) nrrd->axis[a].spaceDirection[b] = a == b ? grid.spacing[a] : 0.0;
  }
  set_origin(nrrd.get(), grid.origin);
  write_atomically(path, [&](std::FILE* file) { return write_nrrd(file, nrrd.get()); });
}

namespace {

using HeaderCheck = std::string (*)(const Nrrd*, VolumeHeader&);

// Throws the one-line error of a file that cannot be read: "cannot read <kind> '<path>': why".
struct ReadFailure {
  const char* kind;
  std::string shown;
  [[noreturn]] void operator()(const std::string& why) const {
    throw NrrdError(fmt::format("cannot read {} '{}': {}", kind, shown, why));
  }
};

// Opens `path` if it is a regular file (a FIFO or a device could block or never end); its size.
File open_regular_file(const fs::path& path, const ReadFailure& fail, std::uint64_t& size) {
  std::error_code error;
  const fs::file_status status = fs::status(path, error);
  if (error && error != std::errc::no_such_file_or_directory) fail(error.message());
  if (!fs::exists(status)) fail("no such file");
  if (fs::is_directory(status)) fail("it is a directory");
  if (!fs::is_regular_file(status)) fail("not a regular file");
  File file(std::fopen(path.c_str(), "rb"));
  if (!file) fail(std::strerror(errno));
  struct stat info {};
  if (::fstat(::fileno(file.get()), &info) != 0) fail(std::strerror(errno));
  if (!S_ISREG(info.st_mode)) fail("not a regular file");
  size = static_cast<std::uint64_t>(info.st_size);
  return file;
}

// Looks at the header before Teem does: the magic keeps Teem's other formats (PNG, PNM, VTK,
// text tables) out, and a detached data file is refused before Teem would open it.
void check_header_text(std::FILE* file, std::uint64_t file_size, const ReadFailure& fail) {
  std::string head(std::min<std::uint64_t>(file_size, kMaxHeaderBytes), '\0');
  head.resize(std::fread(head.data(), 1, head.size(), file));
  if (!head.starts_with("NRRD000") || head.size() < 8 ||
      !std::isdigit(static_cast<unsigned char>(head[7])))
    fail("not a NRRD file (it does not start with the magic 'NRRD000x')");
  bool header_complete = false;
  if (header_names_data_file(head, header_complete))
    fail(
        "detached data files ('data file:' in the header) are not supported; keep the data in the "
        ".nrrd file");
  if (!header_complete && file_size > head.size())
    fail(fmt::format("its header is longer than {} bytes", kMaxHeaderBytes));
}

// The data must be exactly what the header describes: a wrong type or too few sizes over the
// right data would otherwise read as other numbers.
void check_data_length(std::FILE* file, const DataLayout& layout, std::uint64_t file_size,
                       const VolumeHeader& header, std::uint64_t sample_count,
                       const ReadFailure& fail) {
  std::uint64_t stored = 0;
  std::string problem;
  const bool raw = layout.encoding == nrrdEncodingRaw, ascii = layout.encoding == nrrdEncodingAscii,
             hex = layout.encoding == nrrdEncodingHex;
  const std::uint64_t expected = ascii ? sample_count
                                 : hex ? 2 * header.data_bytes
                                       : header.data_bytes;
  if (!count_stored_data(file, layout, file_size, expected, stored, problem)) return;
  if (!problem.empty()) fail(problem);
  const char* unit = raw     ? "bytes of raw data"
                     : ascii ? "numbers"
                     : hex   ? "hex digits"
                             : "bytes of decompressed data";
  if (stored < expected)
    fail(fmt::format("the file is truncated: its header announces {} {}, but only {} follow it",
                     expected, unit, stored));
  if (stored > expected)
    fail(
        fmt::format("{}{} {} follow its header, which announces {} (its type and sizes must "
                    "describe the data exactly)",
                    raw || ascii || hex ? "" : "more than ",
                    raw || ascii || hex ? stored : expected, unit, expected));
}

// Teem's samples converted to T; a finite double beyond float's range has no float value
// (converting it is undefined), so it is refused.
template <class T>
std::vector<T> converted_samples(const Nrrd* nrrd, int type, std::size_t count,
                                 const ReadFailure& fail) {
  std::vector<T> out(count);
  if (type == teem_type<T>()) {
    std::memcpy(out.data(), nrrd->data, count * sizeof(T));
  } else if (type == nrrdTypeFloat) {
    std::copy_n(static_cast<const float*>(nrrd->data), count, out.begin());
  } else {
    for (std::size_t s = 0; s < count; ++s) {
      const double x = static_cast<const double*>(nrrd->data)[s];
      if (std::isfinite(x) && std::fabs(x) > std::numeric_limits<float>::max())
        fail(fmt::format(
            "its sample {} = {} is beyond the range of float; read it in double precision", s, x));
      out[s] = static_cast<T>(x);
    }
  }
  return out;
}

template <class T>
void refuse_non_finite(const std::vector<T>& samples, const VolumeHeader& full,
                       const ReadFailure& fail) {
  for (std::size_t s = 0; s < samples.size(); ++s) {
    if (std::isfinite(samples[s])) continue;
    const Sizes& n = full.sizes;
    const auto k = static_cast<std::size_t>(full.lattice.coset_count());
    const std::size_t cell = s / k, n0 = static_cast<std::size_t>(n[0]),
                      n1 = static_cast<std::size_t>(n[1]);
    fail(fmt::format(
        "its sample {} (coset {}, {}, {}, {}) is {}; non-finite samples are refused unless "
        "allowed (boxrecon --allow-nonfinite)",
        s, s % k, cell % n0, cell / n0 % n1, cell / n0 / n1, static_cast<double>(samples[s])));
  }
}

// Reads the volume file `path` whose header `check` accepts (`kind` names it in messages):
// everything but building the volume, which the caller does from the header and the samples.
template <class T>
std::vector<T> read_volume(const fs::path& path, const NrrdReadLimits& limits, HeaderCheck check,
                           const char* kind, VolumeHeader& full) {
  const ReadFailure fail{kind, printable(path.string())};
  std::uint64_t file_size = 0;
  const File file = open_regular_file(path, fail, file_size);
  check_header_text(file.get(), file_size, fail);

  std::lock_guard lock(teem_mutex());
  VolumeHeader header{};
  DataLayout layout;
  {
    NrrdOwner nrrd(nrrdNew());
    if (std::string why = teem_read(file.get(), nrrd.get(), true, layout); !why.empty()) fail(why);
    if (std::string why = check(nrrd.get(), header); !why.empty()) fail(why);
  }
  if (header.data_bytes > limits.max_data_bytes)
    fail(fmt::format("its data of {} bytes exceeds the limit of {} bytes", header.data_bytes,
                     limits.max_data_bytes));
  const std::uint64_t sample_count = header.data_bytes / (header.type == nrrdTypeFloat ? 4 : 8);
  check_data_length(file.get(), layout, file_size, header, sample_count, fail);

  NrrdOwner nrrd(nrrdNew());
  if (std::string why = teem_read(file.get(), nrrd.get(), false, layout); !why.empty()) fail(why);
  if (std::string why = check(nrrd.get(), full); !why.empty())
    fail(why);  // the file may have changed
  if (full.data_bytes != header.data_bytes) fail("the file changed while it was read");
  if (!nrrd->data) fail("Teem returned no data");
  const auto count = static_cast<std::size_t>(sample_count);
  if (layout.encoding != nrrdEncodingAscii) {
    const std::string why =
        full.type == nrrdTypeFloat
            ? check_byte_order(static_cast<const float*>(nrrd->data), count, layout.endian)
            : check_byte_order(static_cast<const double*>(nrrd->data), count, layout.endian);
    if (!why.empty()) fail(why);
  }
  std::vector<T> out = converted_samples<T>(nrrd.get(), full.type, count, fail);
  if (!limits.allow_non_finite) refuse_non_finite(out, full, fail);
  return out;
}

}  // namespace

template <class T>
BccVolume<T> read_bcc_nrrd(const fs::path& path, const NrrdReadLimits& limits) {
  VolumeHeader header{};
  std::vector<T> samples = read_volume<T>(path, limits, check_bcc_header, "BCC volume", header);
  return BccVolume<T>(header.sizes, header.h, header.origin, std::move(samples));
}

template <class T>
LatticeVolume<T> read_lattice_nrrd(const fs::path& path, const NrrdReadLimits& limits) {
  VolumeHeader header{};
  std::vector<T> samples =
      read_volume<T>(path, limits, check_lattice_header, "lattice volume", header);
  return LatticeVolume<T>(header.lattice, header.sizes, header.h, header.origin,
                          std::move(samples));
}

template void write_bcc_nrrd<float>(const fs::path&, const BccVolume<float>&);
template void write_bcc_nrrd<double>(const fs::path&, const BccVolume<double>&);
template BccVolume<float> read_bcc_nrrd<float>(const fs::path&, const NrrdReadLimits&);
template BccVolume<double> read_bcc_nrrd<double>(const fs::path&, const NrrdReadLimits&);
template void write_lattice_nrrd<float>(const fs::path&, const LatticeVolume<float>&);
template void write_lattice_nrrd<double>(const fs::path&, const LatticeVolume<double>&);
template LatticeVolume<float> read_lattice_nrrd<float>(const fs::path&, const NrrdReadLimits&);
template LatticeVolume<double> read_lattice_nrrd<double>(const fs::path&, const NrrdReadLimits&);
template void write_cartesian_nrrd<float>(const fs::path&, const CartesianVolume<float>&);
template void write_cartesian_nrrd<double>(const fs::path&, const CartesianVolume<double>&);

}  // namespace boxgen::runtime
