// NRRD files: bit-exact round trips, the header fields read back with Teem itself, hand-written
// files, and every kind of bad file giving one clear error (never a crash: these run under ASan).
#include "runtime/nrrd_io.h"
#include "tests/support/scratch_directory.h"
#include "tests/support/volume_expectations.h"

#include <gtest/gtest.h>
#include <signal.h>
#include <sys/resource.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <teem/biff.h>
#include <teem/nrrd.h>
#include <unistd.h>

#include <algorithm>
#include <bit>
#include <cerrno>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>
#include <memory>
#include <random>
#include <sstream>
#include <string>
#include <vector>

namespace boxgen::runtime {
namespace {

namespace fs = std::filesystem;

class BccNrrd : public test::ScratchDirectoryTest {
 protected:
  BccNrrd() : ScratchDirectoryTest("boxgen-runtime") {}

  fs::path file(const std::string& name) const { return dir_ / name; }
  std::vector<std::string> listing() const {
    std::vector<std::string> names;
    for (const auto& entry : fs::directory_iterator(dir_))
      names.push_back(entry.path().filename().string());
    std::sort(names.begin(), names.end());
    return names;
  }
};

void write_bytes(const fs::path& path, const std::string& bytes) {
  std::ofstream out(path, std::ios::binary);
  out.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
}

std::string read_bytes(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

// A BCC volume's file read as the BCC filters read it (NrrdReadLimits::lattice).
template <class T>
LatticeVolume<T> read_bcc(const fs::path& path, NrrdReadLimits limits = {}) {
  limits.lattice = CosetLattice::bcc();
  return read_lattice_nrrd<T>(path, limits);
}

// Sample values that use every bit: random patterns of finite doubles (or floats), both signs,
// tiny and huge magnitudes.
template <class T>
LatticeVolume<T> random_volume(Sizes sizes, double h, Vec3 origin, unsigned seed) {
  LatticeVolume<T> v(CosetLattice::bcc(), sizes, h, origin);
  std::mt19937_64 random(seed);
  std::uniform_real_distribution<double> mantissa(-1, 1);
  std::uniform_int_distribution<int> exponent(-30, 30);
  for (T& x : v.samples()) x = static_cast<T>(std::ldexp(mantissa(random), exponent(random)));
  return v;
}

using test::expect_identical;

// Teem's own view of a file.
struct TeemNrrd {
  explicit TeemNrrd(const fs::path& path) : nrrd(nrrdNew()) {
    if (nrrdLoad(nrrd, path.c_str(), nullptr) != 0) {
      char* e = biffGetDone(NRRD);
      ADD_FAILURE() << "Teem cannot load " << path << ": " << e;
      std::free(e);
    }
  }
  ~TeemNrrd() { nrrdNuke(nrrd); }
  TeemNrrd(const TeemNrrd&) = delete;
  TeemNrrd& operator=(const TeemNrrd&) = delete;
  std::string key(const char* name) const {
    char* v = nrrdKeyValueGet(nrrd, name);
    std::string s = v ? v : "<missing>";
    std::free(v);
    return s;
  }
  Nrrd* nrrd;
};

TEST_F(BccNrrd, RoundTripDoubleIsBitExact) {
  // h = 1/9 and this origin have no short decimal form: the header must carry all 17 digits.
  const auto v = random_volume<double>({3, 4, 5}, 1.0 / 9, {-1.2345678901234567, 0.1, 3e-7}, 1);
  write_lattice_nrrd(file("v.nrrd"), v);
  expect_identical(read_bcc<double>(file("v.nrrd")), v);
}

TEST_F(BccNrrd, RoundTripFloatIsBitExact) {
  const auto v = random_volume<float>({5, 1, 2}, 0.7, {1e10, -2.0 / 3, 0}, 2);
  write_lattice_nrrd(file("v.nrrd"), v);
  expect_identical(read_bcc<float>(file("v.nrrd")), v);
  // A single-sample-per-coset volume works too.
  const auto tiny = random_volume<float>({1, 1, 1}, 2, {0, 0, 0}, 3);
  write_lattice_nrrd(file("tiny.nrrd"), tiny);
  expect_identical(read_bcc<float>(file("tiny.nrrd")), tiny);
}

TEST_F(BccNrrd, HeaderFieldsAreAsSpecified) {
  const double h = 0.125;
  const auto v = random_volume<double>({3, 4, 5}, h, {-1, 2, 0.5}, 4);
  write_lattice_nrrd(file("v.nrrd"), v);
  EXPECT_TRUE(read_bytes(file("v.nrrd")).starts_with("NRRD000"));
  const TeemNrrd t(file("v.nrrd"));
  ASSERT_EQ(t.nrrd->dim, 4u);
  EXPECT_EQ(t.nrrd->type, nrrdTypeDouble);
  EXPECT_EQ(t.nrrd->axis[0].size, 2u);
  EXPECT_EQ(t.nrrd->axis[1].size, 3u);
  EXPECT_EQ(t.nrrd->axis[2].size, 4u);
  EXPECT_EQ(t.nrrd->axis[3].size, 5u);
  EXPECT_EQ(t.nrrd->spaceDim, 3u);
  for (int b = 0; b < 3; ++b)
    EXPECT_TRUE(std::isnan(t.nrrd->axis[0].spaceDirection[b])) << "axis 0 has no space direction";
  for (int a = 1; a <= 3; ++a)
    for (int b = 0; b < 3; ++b)
      EXPECT_EQ(t.nrrd->axis[a].spaceDirection[b], a - 1 == b ? 2 * h : 0.0) << a << " " << b;
  EXPECT_EQ(t.nrrd->spaceOrigin[0], -1.0);
  EXPECT_EQ(t.nrrd->spaceOrigin[1], 2.0);
  EXPECT_EQ(t.nrrd->spaceOrigin[2], 0.5);
  EXPECT_EQ(t.key("lattice"), "bcc");
  EXPECT_EQ(t.nrrd->axis[0].kind, nrrdKindList);
  for (int a = 1; a <= 3; ++a) EXPECT_EQ(t.nrrd->axis[a].kind, nrrdKindDomain);
  // Coset fastest: Teem's linear order is exactly samples().
  ASSERT_NE(t.nrrd->data, nullptr);
  EXPECT_EQ(std::memcmp(t.nrrd->data, v.samples().data(), v.samples().size_bytes()), 0);
  EXPECT_EQ(static_cast<const double*>(t.nrrd->data)[v.index(1, 2, 3, 4)], v.at(1, 2, 3, 4));
}

TEST_F(BccNrrd, CartesianGridIsAPlain3dNrrd) {
  CartesianVolume<float> grid;
  grid.sizes = {4, 3, 2};
  grid.spacing = {0.5, 0.25, 2};
  grid.origin = {-1, 0, 3};
  for (int s = 0; s < 24; ++s) grid.values.push_back(static_cast<float>(s) * 1.5f - 7);
  write_cartesian_nrrd(file("grid.nrrd"), grid);
  const TeemNrrd t(file("grid.nrrd"));
  ASSERT_EQ(t.nrrd->dim, 3u);
  EXPECT_EQ(t.nrrd->type, nrrdTypeFloat);
  for (int a = 0; a < 3; ++a) {
    EXPECT_EQ(t.nrrd->axis[a].size, static_cast<std::size_t>(grid.sizes[a]));
    EXPECT_EQ(t.nrrd->axis[a].kind, nrrdKindDomain);
    for (int b = 0; b < 3; ++b)
      EXPECT_EQ(t.nrrd->axis[a].spaceDirection[b], a == b ? grid.spacing[a] : 0.0);
    EXPECT_EQ(t.nrrd->spaceOrigin[a], grid.origin[a]);
  }
  EXPECT_EQ(t.key("lattice"), "<missing>");
  ASSERT_NE(t.nrrd->data, nullptr);
  EXPECT_EQ(std::memcmp(t.nrrd->data, grid.values.data(), grid.values.size() * sizeof(float)), 0);
  EXPECT_EQ(static_cast<const float*>(t.nrrd->data)[grid.index(3, 1, 1)],
            grid.values[3 + 4 * (1 + 3 * 1)]);
  // It is no lattice volume (its spacings differ per axis).
  EXPECT_THROW((void)read_bcc<float>(file("grid.nrrd")), NrrdError);

  CartesianVolume<double> bad;
  bad.sizes = {2, 2, 2};
  bad.spacing = {1, 1, 1};
  bad.values.resize(7);
  EXPECT_THROW(write_cartesian_nrrd(file("bad.nrrd"), bad), std::invalid_argument);
  bad.values.resize(8);
  bad.spacing[1] = 0;
  EXPECT_THROW(write_cartesian_nrrd(file("bad.nrrd"), bad), std::invalid_argument);
  EXPECT_FALSE(fs::exists(file("bad.nrrd")));
}

TEST_F(BccNrrd, SamplesOfTheOtherTypeAreConverted) {
  const auto f = random_volume<float>({2, 3, 2}, 0.5, {0, 0, 0}, 5);
  write_lattice_nrrd(file("f.nrrd"), f);
  const auto as_double = read_bcc<double>(file("f.nrrd"));
  for (std::size_t s = 0; s < f.sample_count(); ++s)
    EXPECT_EQ(as_double.samples()[s], static_cast<double>(f.samples()[s]));

  auto d = random_volume<double>({2, 3, 2}, 0.5, {0, 0, 0}, 6);
  write_lattice_nrrd(file("d.nrrd"), d);
  const auto as_float = read_bcc<float>(file("d.nrrd"));
  for (std::size_t s = 0; s < d.sample_count(); ++s)
    EXPECT_EQ(as_float.samples()[s], static_cast<float>(d.samples()[s]));

  // A finite double that no float can hold is an error, not an undefined conversion.
  d.samples()[3] = 1e300;
  write_lattice_nrrd(file("huge.nrrd"), d);
  EXPECT_EQ(read_bcc<double>(file("huge.nrrd")).samples()[3], 1e300);
  EXPECT_THROW((void)read_bcc<float>(file("huge.nrrd")), NrrdError);
}

// ---------------------------------------------------------------------------------------------
// Hand-written files. The base header describes a valid 2 x 2 x 1 x 1 float volume, h = 0.25; each
// bad case changes one thing, so the positive control shows that only that change is rejected.

const char* kEndian = std::endian::native == std::endian::little ? "little" : "big";

std::string base_header() {
  return std::string(
             "NRRD0004\n"
             "# hand-written test volume\n"
             "type: float\n"
             "dimension: 4\n"
             "sizes: 2 2 1 1\n"
             "space dimension: 3\n"
             "space directions: none (0.5,0,0) (0,0.5,0) (0,0,0.5)\n"
             "space origin: (1,2,3)\n"
             "encoding: raw\n"
             "endian: ") +
         kEndian + "\nlattice:=bcc\n\n";
}

std::string raw_floats(const std::vector<float>& values) {
  std::string bytes(values.size() * sizeof(float), '\0');
  std::memcpy(bytes.data(), values.data(), bytes.size());
  return bytes;
}

const std::vector<float> kValues = {1.5f, -2, 0.25f, 8};

std::string fmt_hex(unsigned char byte) {
  const char* digits = "0123456789abcdef";
  return {digits[byte >> 4], digits[byte & 15]};
}

std::string replace(std::string text, const std::string& from, const std::string& to) {
  const std::size_t at = text.find(from);
  if (at == std::string::npos)
    ADD_FAILURE() << "'" << from << "' is not in the header";
  else
    text.replace(at, from.size(), to);
  return text;
}

TEST_F(BccNrrd, HandWrittenFilesRead) {
  write_bytes(file("raw.nrrd"), base_header() + raw_floats(kValues));
  const auto v = read_bcc<float>(file("raw.nrrd"));
  EXPECT_EQ(v.sizes(), (Sizes{2, 1, 1}));
  EXPECT_EQ(v.spacing(), 0.25);
  EXPECT_EQ(v.origin(), (Vec3{1, 2, 3}));
  EXPECT_EQ(std::vector<float>(v.samples().begin(), v.samples().end()), kValues);
  EXPECT_EQ(v.value(3, 1, 1), 8.0f);  // coset 1, i = 1

  // Other encodings and byte orders are Teem's business: ASCII, and raw in the other byte order.
  write_bytes(file("ascii.nrrd"),
              replace(base_header(), "encoding: raw", "encoding: ascii") + "1.5 -2\n0.25 8\n");
  const auto a = read_bcc<double>(file("ascii.nrrd"));
  EXPECT_EQ(std::vector<double>(a.samples().begin(), a.samples().end()),
            (std::vector<double>{1.5, -2, 0.25, 8}));
  std::string swapped = raw_floats(kValues);
  for (std::size_t s = 0; s < swapped.size(); s += 4)
    std::reverse(swapped.begin() + static_cast<std::ptrdiff_t>(s),
                 swapped.begin() + static_cast<std::ptrdiff_t>(s + 4));
  const std::string other = std::endian::native == std::endian::little ? "big" : "little";
  write_bytes(
      file("swapped.nrrd"),
      replace(base_header(), std::string("endian: ") + kEndian, "endian: " + other) + swapped);
  const auto s = read_bcc<float>(file("swapped.nrrd"));
  EXPECT_EQ(std::vector<float>(s.samples().begin(), s.samples().end()), kValues);
  // Windows line ends are fine.
  std::string crlf;
  for (char ch : base_header()) crlf += ch == '\n' ? std::string("\r\n") : std::string(1, ch);
  write_bytes(file("crlf.nrrd"), crlf + raw_floats(kValues));
  EXPECT_EQ(read_bcc<float>(file("crlf.nrrd")).value(3, 1, 1), 8.0f);
}

struct BadFile {
  const char* name;
  std::string bytes;
  const char* expected;  // part of the message
};

std::vector<BadFile> bad_files() {
  const std::string h = base_header();
  const std::string data = raw_floats(kValues);
  std::string long_header = "NRRD0004\n";
  while (long_header.size() < (std::size_t{1} << 21))
    long_header += "# a comment line that goes on and on and on and on\n";
  return {
      {"empty", "", "not a NRRD file"},
      {"text", "hello, world\n", "not a NRRD file"},
      {"png", std::string("\x89PNG\r\n\x1a\n", 8) + std::string(100, 'x'), "not a NRRD file"},
      {"magic only", "NRRD0004", ""},
      {"header cut", h.substr(0, 60), ""},
      {"no data", h, "truncated"},
      {"data cut", h + data.substr(0, 13), "truncated"},
      {"wrong dimension",
       replace(
           replace(replace(h, "dimension: 4", "dimension: 3"), "sizes: 2 2 1 1", "sizes: 2 2 1"),
           "none (0.5,0,0) (0,0.5,0) (0,0,0.5)", "(0.5,0,0) (0,0.5,0) (0,0,0.5)") +
           data,
       "dimension 3"},
      {"axis 0 size 4", replace(h, "sizes: 2 2 1 1", "sizes: 4 1 1 1") + data, "axis 0 has size 4"},
      {"missing lattice key", replace(h, "lattice:=bcc\n", "") + data, "lattice:=bcc"},
      {"other lattice", replace(h, "lattice:=bcc", "lattice:=fcc") + data, "fcc volume"},
      {"inconsistent spacing", replace(h, "(0,0.5,0)", "(0,0.25,0)") + data, "space directions"},
      {"rotated directions", replace(h, "(0.5,0,0)", "(0.5,0.1,0)") + data, "space directions"},
      {"negative h",
       replace(h, "none (0.5,0,0) (0,0.5,0) (0,0,0.5)", "none (-0.5,0,0) (0,-0.5,0) (0,0,-0.5)") +
           data,
       "space directions"},
      {"h underflows to 0",
       replace(h, "none (0.5,0,0) (0,0.5,0) (0,0,0.5)",
               "none (4.9e-324,0,0) (0,4.9e-324,0) (0,0,4.9e-324)") +
           data,
       "space directions"},
      {"coset axis with direction", replace(h, "none (0.5,0,0)", "(1,0,0) (0.5,0,0)") + data,
       "axis 0"},
      {"spacings instead of directions",
       replace(replace(replace(h, "space dimension: 3\n", ""),
                       "space directions: none (0.5,0,0) (0,0.5,0) (0,0,0.5)\n",
                       "spacings: nan 0.5 0.5 0.5\n"),
               "space origin: (1,2,3)\n", "") +
           data,
       "space directions"},
      {"missing origin", replace(h, "space origin: (1,2,3)\n", "") + data, "origin"},
      {"64-bit integer samples", replace(h, "type: float", "type: int64") + data, "not supported"},
      {"unparsable sizes", replace(h, "sizes: 2 2 1 1", "sizes: 2 two 1 1") + data, ""},
      {"unknown field", replace(h, "encoding: raw", "encoding: raw\nfrobnicate: yes") + data, ""},
      {"detached data", replace(h, "encoding: raw", "data file: missing.raw\nencoding: raw"),
       "detached"},
      {"detached from stdin",
       replace(h, "encoding: raw", "DATA  File: /dev/stdin\nencoding: raw") + data, "detached"},
      {"detached after CR",
       replace(h, "encoding: raw\n", "encoding: raw\rdatafile: /dev/stdin\n") + data, "detached"},
      {"huge raw", replace(h, "sizes: 2 2 1 1", "sizes: 2 1000 1000 1000") + data, "truncated"},
      {"huge sizes",
       replace(h, "sizes: 2 2 1 1", "sizes: 2 4000000000 4000000000 4000000000") + data, ""},
      {"long header", long_header, "header is longer"},
  };
}

TEST_F(BccNrrd, BadFilesGiveOneLineErrors) {
  // Positive control: the base file reads.
  write_bytes(file("good.nrrd"), base_header() + raw_floats(kValues));
  ASSERT_NO_THROW((void)read_bcc<float>(file("good.nrrd")));

  int index = 0;
  for (const BadFile& bad : bad_files()) {
    const fs::path path = file("bad-" + std::to_string(index++) + ".nrrd");
    write_bytes(path, bad.bytes);
    for (int precision = 0; precision < 2; ++precision) {
      try {
        if (precision == 0)
          (void)read_bcc<float>(path);
        else
          (void)read_bcc<double>(path);
        ADD_FAILURE() << bad.name << ": no error";
      } catch (const NrrdError& e) {
        const std::string message = e.what();
        EXPECT_EQ(message.find('\n'), std::string::npos) << bad.name << ": " << message;
        EXPECT_NE(message.find(path.filename().string()), std::string::npos)
            << bad.name << ": " << message;
        EXPECT_NE(message.find(bad.expected), std::string::npos) << bad.name << ": " << message;
        EXPECT_LT(message.size(), 400u) << bad.name << ": " << message;
      }
    }
  }
}

TEST_F(BccNrrd, MissingPathsAndDirectoriesAreErrors) {
  try {
    (void)read_bcc<double>(file("does-not-exist.nrrd"));
    ADD_FAILURE() << "no error";
  } catch (const NrrdError& e) {
    EXPECT_NE(std::string(e.what()).find("no such file"), std::string::npos) << e.what();
  }
  EXPECT_THROW((void)read_bcc<double>(dir_), NrrdError);
  EXPECT_THROW((void)read_bcc<double>(file("no-dir") / "v.nrrd"), NrrdError);
  EXPECT_THROW((void)read_bcc<double>("/dev/null"), NrrdError);  // not a regular file
}

// Files that other tools compressed (3D Slicer writes gzip by default): re-save our file with
// Teem in each compressed encoding and read it back.
TEST_F(BccNrrd, CompressedFilesRead) {
  const auto v = random_volume<double>({4, 3, 2}, 0.5, {1, -1, 0}, 10);
  write_lattice_nrrd(file("raw.nrrd"), v);
  const TeemNrrd t(file("raw.nrrd"));
  for (const NrrdEncoding* encoding : {nrrdEncodingGzip, nrrdEncodingBzip2}) {
    const fs::path path = file(std::string(encoding->name) + ".nrrd");
    NrrdIoState* io = nrrdIoStateNew();
    io->encoding = encoding;
    const int failed = nrrdSave(path.c_str(), t.nrrd, io);
    nrrdIoStateNix(io);
    ASSERT_EQ(failed, 0) << encoding->name;
    EXPECT_NE(read_bytes(path).find(std::string("encoding: ") + encoding->name), std::string::npos);
    expect_identical(read_bcc<double>(path), v);
  }
}

TEST_F(BccNrrd, CompressedDataBeyondTheLimitIsRefusedBeforeAllocation) {
  // gzip data cannot be checked against the file size; the limit bounds the allocation.
  const std::string h = replace(replace(base_header(), "sizes: 2 2 1 1", "sizes: 2 1000 1000 1000"),
                                "encoding: raw", "encoding: gzip");
  write_bytes(file("bomb.nrrd"), h + std::string(64, '\0'));
  try {
    (void)read_bcc<float>(file("bomb.nrrd"),
                          NrrdReadLimits{std::uint64_t{1} << 20, false, std::nullopt});
    ADD_FAILURE() << "no error";
  } catch (const NrrdError& e) {
    EXPECT_NE(std::string(e.what()).find("exceeds the limit"), std::string::npos) << e.what();
  }
  // Within the limit, short compressed data is Teem's to reject. (zlib passes data without a
  // gzip header through unchanged, so it must be short, not merely not gzip.)
  write_bytes(file("small.nrrd"),
              replace(base_header(), "encoding: raw", "encoding: gzip") + std::string(5, 'x'));
  EXPECT_THROW((void)read_bcc<float>(file("small.nrrd")), NrrdError);
  write_bytes(file("small.bz2.nrrd"),
              replace(base_header(), "encoding: raw", "encoding: bzip2") + std::string(5, 'x'));
  EXPECT_THROW((void)read_bcc<float>(file("small.bz2.nrrd")), NrrdError);
}

TEST_F(BccNrrd, WritingReplacesTheFileAndLeavesNoTemporaryFiles) {
  const auto first = random_volume<double>({2, 2, 2}, 0.5, {0, 0, 0}, 7);
  const auto second = random_volume<float>({3, 1, 2}, 0.25, {1, 1, 1}, 8);
  write_lattice_nrrd(file("v.nrrd"), first);
  write_lattice_nrrd(file("v.nrrd"), second);
  expect_identical(read_bcc<float>(file("v.nrrd")), second);
  EXPECT_EQ(listing(), std::vector<std::string>{"v.nrrd"});
}

TEST_F(BccNrrd, OutputDirectoryIsCheckedBeforeAnyWork) {
  EXPECT_NO_THROW(require_output_directory(file("v.nrrd")));
  EXPECT_NO_THROW(require_output_directory("relative-name.nrrd"));  // the current directory
  EXPECT_THROW(require_output_directory(file("missing") / "v.nrrd"), NrrdError);
  EXPECT_THROW(require_output_directory(file("v.nrrd") / ""),
               NrrdError);  // a directory, not a file
  std::ofstream(file("plain")) << "x";
  EXPECT_THROW(require_output_directory(file("plain") / "v.nrrd"), NrrdError);  // parent is a file
  EXPECT_EQ(listing(), std::vector<std::string>{"plain"});  // nothing written by the checks
}

TEST_F(BccNrrd, FailedWritesLeaveNothingBehind) {
  const auto v = random_volume<double>({2, 2, 2}, 0.5, {0, 0, 0}, 9);
  // The directory does not exist.
  EXPECT_THROW(write_lattice_nrrd(file("missing") / "v.nrrd", v), NrrdError);
  // The target is a directory: the rename fails, the temporary file goes.
  fs::create_directory(file("target"));
  try {
    write_lattice_nrrd(file("target"), v);
    ADD_FAILURE() << "no error";
  } catch (const NrrdError& e) {
    EXPECT_EQ(std::string(e.what()).find('\n'), std::string::npos);
    EXPECT_NE(std::string(e.what()).find("cannot write"), std::string::npos) << e.what();
  }
  EXPECT_EQ(listing(), std::vector<std::string>{"target"});
  EXPECT_TRUE(fs::is_empty(file("target")));
  // A path without a file name.
  EXPECT_THROW(write_lattice_nrrd(dir_ / "", v), NrrdError);
  // An existing file survives a failed write unchanged.
  write_lattice_nrrd(file("keep.nrrd"), v);
  const std::string before = read_bytes(file("keep.nrrd"));
  CartesianVolume<double> bad;
  bad.sizes = {2, 2, 2};
  bad.spacing = {1, 1, 1};
  EXPECT_THROW(write_cartesian_nrrd(file("keep.nrrd"), bad), std::invalid_argument);
  EXPECT_EQ(read_bytes(file("keep.nrrd")), before);
  EXPECT_EQ(listing(), (std::vector<std::string>{"keep.nrrd", "target"}));
}

// ---------------------------------------------------------------------------------------------
// Headers that lie, and what the data may hold.

// The message of the NrrdError that reading `path` throws ("" and a failure if none).
std::string read_error(const fs::path& path, const NrrdReadLimits& limits = {}) {
  try {
    (void)read_bcc<double>(path, limits);
  } catch (const NrrdError& e) {
    EXPECT_EQ(std::string(e.what()).find('\n'), std::string::npos) << e.what();
    return e.what();
  }
  ADD_FAILURE() << path << ": no error";
  return "";
}

TEST_F(BccNrrd, DataMustMatchTheHeaderExactly) {
  const std::string h = base_header();  // 2 x 2 x 1 x 1 floats: 16 bytes
  const std::string data = raw_floats(kValues);
  const std::vector<std::pair<std::string, std::string>> lies = {
      {"one byte more", h + data + "x"},
      {"float over double data", h + raw_floats(kValues) + raw_floats(kValues)},
      {"too few sizes", replace(h, "sizes: 2 2 1 1", "sizes: 2 1 1 1") + data},
      {"ascii: a number more",
       replace(h, "encoding: raw", "encoding: ascii") + "1.5 -2\n0.25 8 9\n"},
      {"hex: a digit more",
       replace(h, "encoding: raw", "encoding: hex") + std::string(32, '0') + "0\n"},
  };
  for (const auto& [name, bytes] : lies) {
    write_bytes(file("lie.nrrd"), bytes);
    EXPECT_NE(read_error(file("lie.nrrd")).find("announces"), std::string::npos) << name;
  }
  // Too little is refused as before, in every counted encoding.
  write_bytes(file("short.nrrd"),
              replace(h, "encoding: raw", "encoding: ascii") + "1.5 -2\n0.25\n");
  EXPECT_NE(read_error(file("short.nrrd")).find("truncated"), std::string::npos);
  // Positive controls: exact data in each encoding reads (hex digits with line breaks).
  write_bytes(file("ascii.nrrd"),
              replace(h, "encoding: raw", "encoding: ascii") + "1.5 -2\n0.25 8\n\n");
  EXPECT_NO_THROW((void)read_bcc<float>(file("ascii.nrrd")));
  std::string hex;
  for (unsigned char byte : data) hex += fmt_hex(byte);
  write_bytes(file("hex.nrrd"), replace(h, "encoding: raw", "encoding: hex") + hex.substr(0, 10) +
                                    "\n" + hex.substr(10) + "\n");
  const auto v = read_bcc<float>(file("hex.nrrd"));
  EXPECT_EQ(std::vector<float>(v.samples().begin(), v.samples().end()), kValues);
  // Compressed data is decompressed and counted: Teem re-saves the honest file in gzip and bzip2,
  // then the header is made to lie about the type (float over doubles) or the sizes.
  LatticeVolume<double> d(CosetLattice::bcc(), {2, 2, 2}, 0.5, {0, 0, 0});
  for (double& x : d.samples()) x = 0.75;
  write_lattice_nrrd(file("d.nrrd"), d);
  const TeemNrrd t(file("d.nrrd"));
  for (const NrrdEncoding* encoding : {nrrdEncodingGzip, nrrdEncodingBzip2}) {
    SCOPED_TRACE(encoding->name);
    NrrdIoState* io = nrrdIoStateNew();
    io->encoding = encoding;
    const fs::path compressed = file(std::string("c.") + encoding->name + ".nrrd");
    ASSERT_EQ(nrrdSave(compressed.c_str(), t.nrrd, io), 0);
    nrrdIoStateNix(io);
    const std::string bytes = read_bytes(compressed);
    EXPECT_NO_THROW((void)read_bcc<double>(compressed));  // the honest file reads
    write_bytes(file("lie.nrrd"), replace(bytes, "type: double", "type: float"));
    EXPECT_NE(read_error(file("lie.nrrd")).find("announces"), std::string::npos);
    write_bytes(file("lie.nrrd"), replace(bytes, "sizes: 2 2 2 2", "sizes: 2 2 2 1"));
    EXPECT_NE(read_error(file("lie.nrrd")).find("announces"), std::string::npos);
    write_bytes(file("lie.nrrd"), replace(bytes, "sizes: 2 2 2 2", "sizes: 2 2 2 3"));
    EXPECT_NE(read_error(file("lie.nrrd")).find("truncated"), std::string::npos);
  }
  // Skipped lines or bytes in attached data are not supported.
  write_bytes(file("skip.nrrd"),
              replace(h, "encoding: raw", "encoding: raw\nbyte skip: 4") + "abcd" + data);
  EXPECT_NE(read_error(file("skip.nrrd")).find("byte skip"), std::string::npos);
}

TEST_F(BccNrrd, TheDeclaredByteOrderIsHonouredAndAnEvidentLieRefused) {
  // Native data declared in the other byte order: 1.5f byte-swapped is about 5e-41.
  const std::string other = std::endian::native == std::endian::little ? "big" : "little";
  const std::string lie =
      replace(base_header(), std::string("endian: ") + kEndian, "endian: " + other);
  write_bytes(file("lie.nrrd"), lie + raw_floats(kValues));
  EXPECT_NE(read_error(file("lie.nrrd")).find("byte order"), std::string::npos);
  // The same header over data in that byte order reads (HandWrittenFilesRead also checks this).
  std::string swapped = raw_floats(kValues);
  for (std::size_t s = 0; s < swapped.size(); s += 4)
    std::reverse(swapped.begin() + static_cast<long>(s),
                 swapped.begin() + static_cast<long>(s + 4));
  write_bytes(file("honest.nrrd"), lie + swapped);
  EXPECT_EQ(read_bcc<float>(file("honest.nrrd")).value(3, 1, 1), 8.0f);
  // Doubles: 1.0 byte-swapped is about 3e-317.
  const auto ones = [] {
    LatticeVolume<double> v(CosetLattice::bcc(), {3, 2, 2}, 0.5, {0, 0, 0});
    for (double& x : v.samples()) x = 1.0;
    return v;
  }();
  write_lattice_nrrd(file("d.nrrd"), ones);
  std::string bytes = read_bytes(file("d.nrrd"));
  const std::string declared = std::string("endian: ") + kEndian;
  ASSERT_NE(bytes.find(declared), std::string::npos);
  write_bytes(file("dlie.nrrd"), replace(bytes, declared, "endian: " + other));
  EXPECT_NE(read_error(file("dlie.nrrd")).find("byte order"), std::string::npos);
  // Genuine data with tiny and huge values is not taken for a lie: their swaps are no better.
  LatticeVolume<double> extreme(CosetLattice::bcc(), {2, 1, 1}, 0.5, {0, 0, 0});
  extreme.samples()[0] = 1e-200;
  extreme.samples()[1] = 3e200;
  extreme.samples()[2] = 0;
  extreme.samples()[3] = -7e250;
  write_lattice_nrrd(file("extreme.nrrd"), extreme);
  expect_identical(read_bcc<double>(file("extreme.nrrd")), extreme);
}

TEST_F(BccNrrd, NonFiniteSamplesAreRefusedUnlessAllowed) {
  for (const float bad :
       {std::numeric_limits<float>::quiet_NaN(), std::numeric_limits<float>::infinity(),
        -std::numeric_limits<float>::infinity()}) {
    std::vector<float> values = kValues;
    values[3] = bad;
    write_bytes(file("bad.nrrd"), base_header() + raw_floats(values));
    const std::string message = read_error(file("bad.nrrd"));
    EXPECT_NE(message.find("sample 3 (coset 1, 1, 0, 0)"), std::string::npos) << message;
    EXPECT_NE(message.find("non-finite"), std::string::npos) << message;
    NrrdReadLimits allow;
    allow.allow_non_finite = true;
    const auto v = read_bcc<float>(file("bad.nrrd"), allow);
    EXPECT_EQ(std::isnan(v.samples()[3]), std::isnan(bad));
    EXPECT_EQ(v.samples()[0], 1.5f);
  }
}

// ---------------------------------------------------------------------------------------------
// Where writes go (support/output_file.h through write_bcc_nrrd).

TEST_F(BccNrrd, WritesGoThroughSymbolicLinks) {
  const auto v = random_volume<double>({2, 2, 2}, 0.5, {0, 0, 0}, 11);
  fs::create_directory(file("d"));
  fs::create_symlink("d/target.nrrd", file("link.nrrd"));  // dangling: the target is created
  write_lattice_nrrd(file("link.nrrd"), v);
  EXPECT_TRUE(fs::is_symlink(file("link.nrrd")));
  expect_identical(read_bcc<double>(file("d/target.nrrd")), v);
  fs::create_symlink("link.nrrd", file("link2.nrrd"));  // a link to a link
  const auto w = random_volume<double>({1, 2, 3}, 0.25, {0, 0, 0}, 12);
  write_lattice_nrrd(file("link2.nrrd"), w);
  EXPECT_TRUE(fs::is_symlink(file("link2.nrrd")));
  expect_identical(read_bcc<double>(file("d/target.nrrd")), w);
  EXPECT_EQ(listing(), (std::vector<std::string>{"d", "link.nrrd", "link2.nrrd"}));
  EXPECT_EQ(fs::directory_iterator(file("d"))->path().filename(), "target.nrrd");
  // A loop of links is an error.
  fs::create_symlink("loop-b", file("loop-a"));
  fs::create_symlink("loop-a", file("loop-b"));
  EXPECT_THROW(write_lattice_nrrd(file("loop-a"), v), NrrdError);
}

TEST_F(BccNrrd, SpecialFilesAreNeverReplaced) {
  const auto v = random_volume<double>({2, 2, 2}, 0.5, {0, 0, 0}, 13);
  ASSERT_EQ(::mkfifo(file("fifo").c_str(), 0600), 0);
  fs::create_symlink("/dev/null", file("null"));
  for (const char* name : {"fifo", "null"}) {
    try {
      write_lattice_nrrd(file(name), v);
      ADD_FAILURE() << name << ": no error";
    } catch (const NrrdError& e) {
      EXPECT_NE(std::string(e.what()).find("only regular files"), std::string::npos) << e.what();
    }
    EXPECT_THROW(require_output_directory(file(name)), NrrdError) << name;
  }
  EXPECT_TRUE(fs::is_fifo(file("fifo")));
  EXPECT_TRUE(fs::is_symlink(file("null")));
  EXPECT_TRUE(fs::is_character_file("/dev/null"));
  EXPECT_EQ(listing(), (std::vector<std::string>{"fifo", "null"}));
}

TEST_F(BccNrrd, AnOutputThatIsAnInputIsRefused) {
  const auto v = random_volume<double>({2, 2, 2}, 0.5, {0, 0, 0}, 14);
  write_lattice_nrrd(file("in.nrrd"), v);
  fs::create_symlink("in.nrrd", file("alias.nrrd"));
  fs::create_hard_link(file("in.nrrd"), file("hard.nrrd"));
  const fs::path inputs[] = {file("other-missing.nrrd"), file("in.nrrd")};
  for (const fs::path& out :
       {file("in.nrrd"), dir_ / "." / "in.nrrd", file("alias.nrrd"), file("hard.nrrd")})
    EXPECT_THROW(require_output_file(out, inputs), NrrdError) << out;
  EXPECT_NO_THROW(require_output_file(file("out.nrrd"), inputs));
  EXPECT_NO_THROW(require_output_file(file("in.nrrd"), {}));
}

TEST_F(BccNrrd, ReplacingAFileKeepsItsPermissions) {
  const auto v = random_volume<double>({2, 2, 2}, 0.5, {0, 0, 0}, 15);
  write_lattice_nrrd(file("v.nrrd"), v);
  fs::permissions(file("v.nrrd"),
                  fs::perms::owner_read | fs::perms::owner_write | fs::perms::others_read);
  write_lattice_nrrd(file("v.nrrd"), v);
  EXPECT_EQ(fs::status(file("v.nrrd")).permissions() & fs::perms::mask,
            fs::perms::owner_read | fs::perms::owner_write | fs::perms::others_read);
}

// ---------------------------------------------------------------------------------------------
// Faults a hostile trial found

// A BCC file whose cosets are stored odd first, and says so, is that volume; coset offsets that
// are not two cosets, rows that are not numbers and rows of another lattice are refused.
TEST_F(BccNrrd, CosetOffsetsAreHonouredOrRefused) {
  const std::vector<float> swapped = {-2, 1.5f, 8, 0.25f};  // kValues with the cosets exchanged
  write_bytes(file("swapped.nrrd"), replace(base_header(), "lattice:=bcc\n",
                                            "lattice:=bcc\ncoset_offsets:=(1,1,1) (0,0,0)\n") +
                                        raw_floats(swapped));
  write_bytes(file("usual.nrrd"), base_header() + raw_floats(kValues));
  const auto usual = read_bcc<float>(file("usual.nrrd"));
  const auto v = read_bcc<float>(file("swapped.nrrd"));
  EXPECT_EQ(v.lattice().offsets(), (std::vector<Offset>{{1, 1, 1}, {0, 0, 0}}));
  for (const LatticePoint& p :
       {LatticePoint{0, 0, 0}, LatticePoint{1, 1, 1}, LatticePoint{2, 0, 0}, LatticePoint{3, 1, 1}})
    EXPECT_EQ(v.value(p), usual.value(p)) << p[0] << " " << p[1] << " " << p[2];
  for (const char* keys : {"coset_offsets:=(0,0,0) (0,0,0)\n", "lattice_rows:=a,b,c\n",
                           "lattice_rows:=1,0,0; 0,1,0; 0,0,1\n", "coset_offsets:=(0,0,0)\n",
                           "coset_offsets:=(0,0,0) (1,1,0)\n"}) {
    write_bytes(file("bad.nrrd"),
                replace(base_header(), "lattice:=bcc\n", std::string("lattice:=bcc\n") + keys) +
                    raw_floats(kValues));
    EXPECT_THROW((void)read_bcc<float>(file("bad.nrrd")), NrrdError) << keys;
  }
}

// What Teem would say about these headers ("existance of all space vector coefficients must be
// consistent", "axis 1 size is zero!") or silently get wrong ("23.5" read as 23) is said in the
// project's words, and the file refused.
TEST_F(BccNrrd, TeemsWordsDoNotReachTheUser) {
  const struct {
    const char* from;
    const char* to;
    const char* said;
  } cases[] = {
      {"space origin: (1,2,3)", "space origin: (nan,2,3)", "not finite"},
      {"sizes: 2 2 1 1", "sizes: 2 -3 1 1", "positive integers"},
      {"sizes: 2 2 1 1", "sizes: 2 2.5 1 1", "positive integers"},
      {"sizes: 2 2 1 1", "sizes: 2 1.5 1 1", "positive integers"},
  };
  for (const auto& c : cases) {
    write_bytes(file("bad.nrrd"), replace(base_header(), c.from, c.to) + raw_floats(kValues));
    const std::string message = read_error(file("bad.nrrd"));
    EXPECT_NE(message.find(c.said), std::string::npos) << c.to << ": " << message;
    for (const char* teem : {"existance", "size is zero", "[nrrd]", "_nrrd"})
      EXPECT_EQ(message.find(teem), std::string::npos) << c.to << ": " << message;
  }
}

// A write that the file system stops (here a file size limit, as a full disk does) is one line
// in the project's words, and leaves nothing behind.
TEST_F(BccNrrd, AFailedWriteIsSaidInOurWords) {
  const LatticeVolume<double> v = random_volume<double>({16, 16, 16}, 0.5, {0, 0, 0}, 3);
  int pipe_fds[2];
  ASSERT_EQ(::pipe(pipe_fds), 0);
  const pid_t child = ::fork();
  ASSERT_GE(child, 0);
  if (child == 0) {  // 64 KiB of samples against a limit of 8 KiB
    ::signal(SIGXFSZ, SIG_IGN);
    const rlimit limit{8192, 8192};
    ::setrlimit(RLIMIT_FSIZE, &limit);
    std::string message = "no error";
    try {
      write_lattice_nrrd(file("big.nrrd"), v);
    } catch (const NrrdError& e) {
      message = e.what();
    }
    (void)!::write(pipe_fds[1], message.data(), message.size());
    ::_exit(0);
  }
  ::close(pipe_fds[1]);
  std::string message;
  char buffer[512];
  for (ssize_t got; (got = ::read(pipe_fds[0], buffer, sizeof buffer)) > 0;)
    message.append(buffer, static_cast<std::size_t>(got));
  ::close(pipe_fds[0]);
  int status = 0;
  ::waitpid(child, &status, 0);
  EXPECT_NE(message.find("cannot write"), std::string::npos) << message;
  EXPECT_NE(message.find(std::strerror(EFBIG)), std::string::npos) << message;
  EXPECT_EQ(message.find("fwrite"), std::string::npos) << message;
  EXPECT_EQ(message.find('\n'), std::string::npos) << message;
  EXPECT_FALSE(fs::exists(file("big.nrrd")));
  EXPECT_TRUE(fs::is_empty(dir_)) << "a temporary file was left behind";
}

}  // namespace
}  // namespace boxgen::runtime
