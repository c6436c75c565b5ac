#include "runtime/nrrd_io.h"

#include "runtime/affine.h"
#include "runtime/nrrd_checks.h"
#include "support/output_file.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <teem/biff.h>
#include <teem/nrrd.h>
#include <unistd.h>

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
#include <stdexcept>
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

using nrrd_checks::printable;

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

int teem_type(SampleType type) {
  switch (type) {
    case SampleType::Int8:
      return nrrdTypeChar;
    case SampleType::UInt8:
      return nrrdTypeUChar;
    case SampleType::Int16:
      return nrrdTypeShort;
    case SampleType::UInt16:
      return nrrdTypeUShort;
    case SampleType::Int32:
      return nrrdTypeInt;
    case SampleType::UInt32:
      return nrrdTypeUInt;
    case SampleType::Float32:
      return nrrdTypeFloat;
    case SampleType::Float64:
      break;
  }
  return nrrdTypeDouble;
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

// Writes `nrrd` raw through output_file.h (links followed, special files refused, temporary file
// then rename), with its errors as NrrdError. A failed nrrdWrite is the file system's doing (a
// full disk, a file size limit): its reason is errno's, not Teem's words ("fwrite wrote only
// 7630 8-sized things").
void write_atomically(const fs::path& path, const Nrrd* nrrd) {
  int error = 0;
  const auto fill = [&](std::FILE* file) {
    IoState io(nrrdIoStateNew());
    if (!io) return false;
    io->format = nrrdFormatNRRD;
    io->encoding = nrrdEncodingRaw;
    errno = 0;
    if (nrrdWrite(file, nrrd, io.get()) == 0) return true;
    error = std::ferror(file) && errno != 0 ? errno : 0;
    return false;
  };
  const auto why = [&] {
    const std::string teem = teem_error();  // read, so that biff holds nothing more
    return error != 0 ? fmt::format("writing failed: {}", std::strerror(error))
                      : "Teem could not write the volume: " + teem;
  };
  try {
    write_output_file(path, fill, why);
  } catch (const OutputFileError& e) {
    throw NrrdError(e.what());
  }
}

// The NRRD space of a world tied to a patient (SourceSamples::anatomical: "RAS", "LAS", "LPS"),
// 3D-right-handed for one that is not (""); std::invalid_argument for any other text.
int nrrd_space(const std::string& anatomical) {
  if (anatomical.empty()) return nrrdSpace3DRightHanded;
  if (anatomical == "RAS") return nrrdSpaceRightAnteriorSuperior;
  if (anatomical == "LAS") return nrrdSpaceLeftAnteriorSuperior;
  if (anatomical == "LPS") return nrrdSpaceLeftPosteriorSuperior;
  throw std::invalid_argument("no NRRD space for the anatomical frame '" + anatomical.substr(0, 8) +
                              "' (RAS, LAS or LPS)");
}

// Wraps `data` (not copied, not freed) in a Nrrd with the given sizes in the space of
// `anatomical` (nrrd_space); the caller sets the space directions and the origin.
NrrdShell wrap(const void* data, int type, unsigned dim, const std::size_t* sizes,
               const std::string& anatomical) {
  const int space = nrrd_space(anatomical);
  NrrdShell nrrd(nrrdNew());
  if (!nrrd || nrrdWrap_nva(nrrd.get(), const_cast<void*>(data), type, dim, sizes) != 0 ||
      nrrdSpaceSet(nrrd.get(), space) != 0)
    throw NrrdError("cannot describe the volume to Teem: " + teem_error());
  for (unsigned a = 0; a < dim; ++a)
    for (int b = 0; b < 3; ++b) nrrd->axis[a].spaceDirection[b] = AIR_NAN;
  return nrrd;
}

// The domain axes first..first+2 (kind domain) with steps `steps` along the axes of `frame`
// (nothing: the world's), and the space origin: the grid's `origin` in that frame, mapped to world.
// An oblique frame gives oblique space directions, the columns of frame.linear times the steps.
void set_geometry(Nrrd* nrrd, unsigned first, const Vec3& steps, const Vec3& origin,
                  const std::optional<Affine>& frame) {
  const Affine to_world = frame.value_or(Affine::diagonal({1, 1, 1}, {0, 0, 0}));
  for (unsigned a = 0; a < 3; ++a) {
    nrrd->axis[first + a].kind = nrrdKindDomain;
    for (unsigned b = 0; b < 3; ++b)
      nrrd->axis[first + a].spaceDirection[b] = to_world.linear[b][a] * steps[a];
  }
  const Vec3 world = to_world.apply(origin);
  double o[3] = {world[0], world[1], world[2]};
  if (nrrdSpaceOriginSet(nrrd, o) != 0)
    throw NrrdError("cannot describe the volume to Teem: " + teem_error());
}

// ---------------------------------------------------------------------------------------------
// Reading

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
  Vec3 steps;  // the space direction of each domain axis, divided by d (negative: a flipped axis)
  Vec3 origin;
  std::string anatomical;  // SourceSamples::anatomical
  int type;                // one of kSampleTypes
  std::uint64_t data_bytes;
  // NrrdReadLimits::allow_oblique (in), and an oblique Cartesian file's frame (out): its voxel
  // grid is then in its own frame (steps = the directions' lengths, origin 0), as a NIfTI file's.
  bool allow_oblique = false;
  std::optional<Affine> frame;
};

// The sample types the reader converts, with the names SourceSamples::type gives them. Teem's
// 64-bit integers are refused: neither float nor double holds them all exactly.
struct SampleType {
  int teem;
  const char* name;
};
constexpr SampleType kSampleTypes[] = {{nrrdTypeChar, "int8"},   {nrrdTypeUChar, "uint8"},
                                       {nrrdTypeShort, "int16"}, {nrrdTypeUShort, "uint16"},
                                       {nrrdTypeInt, "int32"},   {nrrdTypeUInt, "uint32"},
                                       {nrrdTypeFloat, "float"}, {nrrdTypeDouble, "double"}};

const char* sample_type_name(int teem) {
  for (const SampleType& t : kSampleTypes)
    if (t.teem == teem) return t.name;
  return nullptr;
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
  std::optional<CosetLattice> declared;
  try {
    if (rows) declared = CosetLattice::parse(*rows);
  } catch (const std::invalid_argument& e) {
    return "its lattice_rows are no lattice: " + printable(e.what());
  }
  if (value != "custom" && declared && declared->name() != value)
    return fmt::format("its lattice_rows '{}' do not generate the {} lattice", printable(*rows, 80),
                       value);
  CosetLattice lattice = value == "custom" ? *declared : CosetLattice::parse(value);
  if (offsets) {
    const auto parsed = parse_offsets(*offsets);
    if (!parsed)
      return fmt::format("its coset_offsets '{}' are not of the form '(x,y,z) (x,y,z) ...'",
                         printable(*offsets, 80));
    try {
      lattice = lattice.with_offsets(*parsed);
    } catch (const std::invalid_argument& e) {
      return "its coset_offsets do not fit its lattice: " + printable(e.what());
    }
  }
  header.lattice = lattice;
  return {};
}

// An oblique (or axis-permuting) Cartesian file's directions, where allowed: its voxel grid in its
// own frame and that frame's map to world (split_oblique, as the NIfTI reader's; the space origin,
// read after this, becomes the frame's translation).
std::string read_oblique_steps(const Nrrd* nrrd, unsigned first, VolumeHeader& header) {
  Affine a, frame;
  for (unsigned c = 0; c < 3; ++c)
    for (unsigned r = 0; r < 3; ++r) {
      const double v = nrrd->axis[first + c].spaceDirection[r];
      if (!std::isfinite(v))
        return fmt::format("its space direction of axis {} is not finite", first + c);
      a.linear[r][c] = v;
    }
  if (const std::string why = split_oblique(a, header.steps, frame); !why.empty())
    return "the matrix of its space directions " + why;
  header.frame = frame;
  return {};
}

// The one spacing h of a lattice of period d (every lattice but Z^3): space directions d h along
// the axes, or, where allowed, along the unit axes of an oblique frame (read_oblique_steps).
std::string read_lattice_steps(const Nrrd* nrrd, unsigned first, int d, const std::string& name,
                               VolumeHeader& header) {
  const double step = nrrd->axis[first].spaceDirection[0];
  bool consistent = std::isfinite(step) && step / d > 0;
  for (unsigned a = 0; a < 3 && consistent; ++a)
    for (unsigned b = 0; b < 3; ++b) {
      const double v = nrrd->axis[first + a].spaceDirection[b];
      if (!std::isfinite(v) || std::fabs(v - (a == b ? step : 0.0)) > 1e-9 * step)
        consistent = false;
    }
  if (consistent) {
    header.steps = {step / d, step / d, step / d};
    return {};
  }
  if (!header.allow_oblique)
    return fmt::format(
        "its space directions are not (dh,0,0) (0,dh,0) (0,0,dh) for one h > 0 (d = {} for the "
        "{} lattice)",
        d, name);
  if (std::string why = read_oblique_steps(nrrd, first, header); !why.empty()) return why;
  const Vec3 s = header.steps;
  if (std::fabs(s[1] - s[0]) > 1e-9 * s[0] || std::fabs(s[2] - s[0]) > 1e-9 * s[0])
    return fmt::format(
        "its space directions have lengths {:.9g}, {:.9g}, {:.9g}; a {} volume's are all d h", s[0],
        s[1], s[2], name);
  header.steps = {s[0] / d, s[0] / d, s[0] / d};
  return {};
}

// The spacing of each domain axis from the space directions (header.steps): Z^3 may have one per
// axis, and negative ones (read_lattice_nrrd flips those axes); every other lattice has one h > 0.
std::string read_steps(const Nrrd* nrrd, unsigned first, int k, int d, const std::string& name,
                       VolumeHeader& header) {
  if (k != 1 || d != 1) return read_lattice_steps(nrrd, first, d, name, header);
  // The domain axes start at `first`: a 4-D file with a coset axis of size 1 (the layout
  // boxrecon once wrote for Cartesian volumes) has its directions on axes 1..3.
  for (int a = 0; a < 3; ++a) {
    const double* direction = nrrd->axis[first + a].spaceDirection;
    const double step = direction[a];
    bool aligned = std::isfinite(step) && step != 0;
    for (int b = 0; b < 3; ++b)
      if (b != a && !(std::fabs(direction[b]) <= 1e-9 * std::fabs(step))) aligned = false;
    if (!aligned && header.allow_oblique) return read_oblique_steps(nrrd, first, header);
    if (!aligned) {
      std::string found;
      for (int c = 0; c < 3; ++c) {
        const double* v = nrrd->axis[first + c].spaceDirection;
        found += fmt::format("{}({:.9g},{:.9g},{:.9g})", c ? " " : "", v[0], v[1], v[2]);
      }
      return fmt::format(
          "its space directions {} are not along the axes ((sx,0,0) (0,sy,0) (0,0,sz)): axis {} "
          "is oblique or permuted",
          found, first + a);
    }
    header.steps[a] = step;
  }
  return {};
}

// Checks that `nrrd` describes a lattice volume (nrrd_io.h); a file without a lattice key where
// `expected` needs one is refused in `expected`'s terms. Returns what it says or an error text.
std::string check_lattice_header(const Nrrd* nrrd, const std::optional<CosetLattice>& expected,
                                 VolumeHeader& header) {
  if (expected && !key_value(nrrd, "lattice") && (nrrd->dim != 3 || expected->coset_count() != 1)) {
    if (nrrd->dim != 4)
      return fmt::format(
          "it has dimension {}; a {} volume is a 4-D NRRD (sizes {} N0 N1 N2, the coset axis "
          "first)",
          nrrd->dim, expected->name(), expected->coset_count());
    return fmt::format("the key/value 'lattice:={}' that marks a {} volume is missing",
                       expected->name(), expected->label());
  }
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
  if (!sample_type_name(nrrd->type))
    return fmt::format(
        "its sample type '{}' is not supported (int8, uint8, int16, uint16, int32, uint32, float "
        "or double)",
        printable(airEnumStr(nrrdType, nrrd->type)));
  header.type = nrrd->type;
  header.data_bytes = count * nrrdTypeSize[nrrd->type];
  if (nrrd->spaceDim != 3)
    return fmt::format(
        "it has no 3-D space directions; a {} volume needs (dh,0,0) (0,dh,0) (0,0,dh), d = {}",
        name, d);
  header.anatomical = nrrd->space == nrrdSpaceRightAnteriorSuperior   ? "RAS"
                      : nrrd->space == nrrdSpaceLeftAnteriorSuperior  ? "LAS"
                      : nrrd->space == nrrdSpaceLeftPosteriorSuperior ? "LPS"
                                                                      : "";
  if (first == 1)
    for (int b = 0; b < 3; ++b)
      if (!std::isnan(nrrd->axis[0].spaceDirection[b]))
        return "axis 0 (the coset axis) must have the space direction 'none'";
  if (std::string why = read_steps(nrrd, first, k, d, name, header); !why.empty()) return why;
  for (int b = 0; b < 3; ++b) {
    header.origin[b] = nrrd->spaceOrigin[b];
    if (!std::isfinite(header.origin[b])) return "its space origin is missing or not finite";
  }
  if (header.frame) {  // the origin is the frame's translation; the grid starts at its 0
    header.frame->translation = header.origin;
    header.origin = {0, 0, 0};
  }
  return {};
}

// Where and how the data of an attached NRRD is stored, as Teem read it from the header.
struct DataLayout {
  nrrd_checks::Encoding encoding = nrrd_checks::Encoding::Other;
  long start = -1;     // file offset of the first data byte (the header's end)
  std::string endian;  // the byte order the header declares (binary encodings)
};

nrrd_checks::Encoding encoding_of(const NrrdEncoding* e) {
  using nrrd_checks::Encoding;
  if (e == nrrdEncodingRaw) return Encoding::Raw;
  if (e == nrrdEncodingAscii) return Encoding::Ascii;
  if (e == nrrdEncodingHex) return Encoding::Hex;
  if (e == nrrdEncodingGzip) return Encoding::Gzip;
  return e == nrrdEncodingBzip2 ? Encoding::Bzip2 : Encoding::Other;
}

// Reads `file` (from its start) into `nrrd`, header only or whole; returns an error text or "".
std::string teem_read(std::FILE* file, Nrrd* nrrd, bool header_only, DataLayout& layout) {
  std::rewind(file);
  IoState io(nrrdIoStateNew());
  if (!io) return "out of memory";
  io->skipData = header_only ? 1 : 0;
  if (nrrdRead(nrrd, file, io.get()) != 0) {
    std::string teem = teem_error();
    if (!header_only) return teem;
    // A header Teem cannot parse, in our words where we know Teem's phrase.
    if (teem.find("size is zero") != std::string::npos) return "its sizes must be positive";
    if (teem.find("space vector coefficients") != std::string::npos)
      return "its space directions and space origin must be given in full, as finite numbers";
    return "its header is not valid NRRD: " + teem;
  }
  if (io->format != nrrdFormatNRRD) return "not a NRRD file";
  if (io->dataFNArr && io->dataFNArr->len != 0)
    return "detached data files are not supported; keep the data in the .nrrd file";
  // Skipped lines or bytes would hide data the exact size check below could not account for.
  if (io->lineSkip != 0 || io->byteSkip != 0)
    return "'line skip' and 'byte skip' are not supported; the data must follow the header";
  layout.encoding = encoding_of(io->encoding);
  layout.endian = airEnumStr(airEndian, io->endian);
  layout.start = header_only ? std::ftell(file) : layout.start;
  return {};
}

}  // namespace

namespace {

// The lattice volume layout of nrrd_io.h for `volume`'s geometry, with the samples at `data` of
// Teem type `type`.
template <class T>
void write_lattice(const fs::path& path, const LatticeVolume<T>& volume, const void* data, int type,
                   const std::string& anatomical, const std::optional<Affine>& frame) {
  std::lock_guard lock(teem_mutex());
  const Sizes& n = volume.sizes();
  const CosetLattice& lattice = volume.lattice();
  const int k = volume.coset_count();
  const Vec3& h = volume.axis_spacing();
  // K = 1: a plain 3-D NRRD, which any NRRD reader takes for what it is.
  const unsigned first = k == 1 ? 0 : 1, dim = 3 + first;
  const std::size_t sizes[4] = {
      static_cast<std::size_t>(k == 1 ? n[0] : k), static_cast<std::size_t>(k == 1 ? n[1] : n[0]),
      static_cast<std::size_t>(k == 1 ? n[2] : n[1]), static_cast<std::size_t>(n[2])};
  NrrdShell nrrd = wrap(data, type, dim, sizes, anatomical);
  if (first == 1) nrrd->axis[0].kind = nrrdKindList;
  const double d = lattice.period();
  set_geometry(nrrd.get(), first, {d * h[0], d * h[1], d * h[2]}, volume.origin(), frame);
  bool ok = nrrdKeyValueAdd(nrrd.get(), "lattice", lattice.name().c_str()) == 0;
  const bool custom = lattice.name() == "custom";
  if (ok && custom)
    ok = nrrdKeyValueAdd(nrrd.get(), "lattice_rows", lattice.rows_text().c_str()) == 0;
  // A named lattice's offsets are implied unless the volume stores its cosets in another order.
  if (ok && (custom || !(lattice == CosetLattice::parse(lattice.name()))))
    ok = nrrdKeyValueAdd(nrrd.get(), "coset_offsets", lattice.offsets_text().c_str()) == 0;
  if (!ok) throw NrrdError("cannot describe the volume to Teem: " + teem_error());
  write_atomically(path, nrrd.get());
}

}  // namespace

template <class T>
void write_lattice_nrrd(const fs::path& path, const LatticeVolume<T>& volume,
                        const std::string& anatomical, const std::optional<Affine>& frame) {
  write_lattice(path, volume, volume.samples().data(), teem_type<T>(), anatomical, frame);
}

template <class T>
void write_lattice_nrrd(const fs::path& path, const LatticeVolume<T>& volume,
                        const EncodedSamples& samples, const std::string& anatomical,
                        const std::optional<Affine>& frame) {
  if (samples.bytes.size() != volume.sample_count() * sample_type_size(samples.type))
    throw std::invalid_argument(fmt::format("{} samples of {} bytes for a volume of {} samples",
                                            samples.bytes.size() / sample_type_size(samples.type),
                                            sample_type_size(samples.type), volume.sample_count()));
  write_lattice(path, volume, samples.bytes.data(), teem_type(samples.type), anatomical, frame);
}

template <class T>
void write_cartesian_nrrd(const fs::path& path, const CartesianVolume<T>& grid,
                          const std::string& anatomical) {
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
  NrrdShell nrrd = wrap(grid.values.data(), teem_type<T>(), 3, sizes, anatomical);
  set_geometry(nrrd.get(), 0, grid.spacing, grid.origin, grid.frame);
  write_atomically(path, nrrd.get());
}

namespace {

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

// Reads the volume file `path` whose header `check` accepts (`kind` names it in messages):
// everything but building the volume, which the caller does from the header and the samples.
template <class T>
std::vector<T> read_volume(const fs::path& path, const NrrdReadLimits& limits, const char* kind,
                           VolumeHeader& full) {
  const ReadFailure fail{kind, printable(path.string())};
  const auto check = [&](const std::string& why) {
    if (!why.empty()) fail(why);
  };
  std::uint64_t file_size = 0;
  const File file = open_regular_file(path, fail, file_size);
  check(nrrd_checks::check_header_text(file.get(), file_size));

  std::lock_guard lock(teem_mutex());
  VolumeHeader header{};
  header.allow_oblique = full.allow_oblique = limits.allow_oblique;
  DataLayout layout;
  {
    NrrdOwner nrrd(nrrdNew());
    check(teem_read(file.get(), nrrd.get(), true, layout));
    check(check_lattice_header(nrrd.get(), limits.lattice, header));
  }
  if (header.data_bytes > limits.max_data_bytes)
    fail(fmt::format("its data of {} bytes exceeds the limit of {} bytes", header.data_bytes,
                     limits.max_data_bytes));
  const std::uint64_t sample_count = header.data_bytes / nrrdTypeSize[header.type];
  check(nrrd_checks::check_data_length(file.get(), layout.start, layout.encoding, file_size,
                                       header.data_bytes, sample_count));
  // Before anything is allocated (a file cut short is the more precise refusal, above).
  check(nrrd_checks::check_memory_for(header.data_bytes + sample_count * sizeof(T)));

  NrrdOwner nrrd(nrrdNew());
  check(teem_read(file.get(), nrrd.get(), false, layout));
  check(check_lattice_header(nrrd.get(), limits.lattice, full));  // the file may have changed
  if (full.data_bytes != header.data_bytes) fail("the file changed while it was read");
  if (!nrrd->data) fail("Teem returned no data");
  const auto count = static_cast<std::size_t>(sample_count);
  std::vector<T> out(count);
  const auto convert = [&](auto type_tag) {
    using S = decltype(type_tag);
    const std::span<const S> in(static_cast<const S*>(nrrd->data), count);
    if constexpr (std::is_floating_point_v<S>) {
      if (layout.encoding != nrrd_checks::Encoding::Ascii)
        check(nrrd_checks::check_byte_order(in, layout.endian));
      if constexpr (std::is_same_v<T, float> && std::is_same_v<S, double>)
        check(nrrd_checks::check_float_range(in));
    }
    std::transform(in.begin(), in.end(), out.begin(), [](S x) { return static_cast<T>(x); });
  };
  if (!visit_sample_type(sample_type_name(full.type), convert)) fail("unknown sample type");
  if (!limits.allow_non_finite)
    check(nrrd_checks::check_finite<T>(out, full.lattice.coset_count(), full.sizes));
  return out;
}

}  // namespace

std::optional<CosetLattice> read_nrrd_lattice(const fs::path& path) {
  try {
    const ReadFailure fail{"lattice volume", printable(path.string())};
    std::uint64_t file_size = 0;
    const File file = open_regular_file(path, fail, file_size);
    if (!nrrd_checks::check_header_text(file.get(), file_size).empty()) return std::nullopt;
    std::lock_guard lock(teem_mutex());
    NrrdOwner nrrd(nrrdNew());
    DataLayout layout;
    VolumeHeader header{};
    if (!teem_read(file.get(), nrrd.get(), true, layout).empty() ||
        !file_lattice(nrrd.get(), header).empty())
      return std::nullopt;
    return header.lattice;
  } catch (const NrrdError&) {
    return std::nullopt;
  }
}

template <class T>
LatticeVolume<T> read_lattice_nrrd(const fs::path& path, const NrrdReadLimits& limits,
                                   SourceSamples* source) {
  VolumeHeader header{};
  const std::string kind =
      limits.lattice ? limits.lattice->label() + " volume" : std::string("lattice volume");
  std::vector<T> samples = read_volume<T>(path, limits, kind.c_str(), header);
  if (header.frame && !source)
    throw std::logic_error("read_lattice_nrrd: allow_oblique needs a SourceSamples");
  Vec3 spacing = header.steps, origin = header.origin;
  orient_axes_positive(std::span<T>(samples), header.sizes, spacing, origin);  // none if oblique
  LatticeVolume<T> volume(header.lattice, header.sizes, spacing, origin, std::move(samples));
  if (source) {
    *source = describe_samples<T>(volume.samples(), sample_type_name(header.type));
    source->anatomical = header.anatomical;
    source->frame = header.frame;
  }
  return volume;
}

template void write_lattice_nrrd<float>(const fs::path&, const LatticeVolume<float>&,
                                        const std::string&, const std::optional<Affine>&);
template void write_lattice_nrrd<double>(const fs::path&, const LatticeVolume<double>&,
                                         const std::string&, const std::optional<Affine>&);
template void write_lattice_nrrd<float>(const fs::path&, const LatticeVolume<float>&,
                                        const EncodedSamples&, const std::string&,
                                        const std::optional<Affine>&);
template void write_lattice_nrrd<double>(const fs::path&, const LatticeVolume<double>&,
                                         const EncodedSamples&, const std::string&,
                                         const std::optional<Affine>&);
template LatticeVolume<float> read_lattice_nrrd<float>(const fs::path&, const NrrdReadLimits&,
                                                       SourceSamples*);
template LatticeVolume<double> read_lattice_nrrd<double>(const fs::path&, const NrrdReadLimits&,
                                                         SourceSamples*);
template void write_cartesian_nrrd<float>(const fs::path&, const CartesianVolume<float>&,
                                          const std::string&);
template void write_cartesian_nrrd<double>(const fs::path&, const CartesianVolume<double>&,
                                           const std::string&);

}  // namespace boxgen::runtime
