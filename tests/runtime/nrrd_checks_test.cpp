// The NRRD reader's own checks (runtime/nrrd_checks.h), one by one on bytes written here: the
// header text, the stored data's length in every encoding (gzip and bzip2 data compressed here
// with zlib and libbz2), the declared byte order, non-finite samples and float's range. Oracles:
// the counts the bytes were made with; byte-swapped values computed here.
#include "runtime/nrrd_checks.h"

#include <bzlib.h>
#include <gtest/gtest.h>
#include <zlib.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <limits>
#include <memory>
#include <string>
#include <vector>

namespace boxgen::runtime::nrrd_checks {
namespace {

struct FileCloser {
  void operator()(std::FILE* f) const { std::fclose(f); }
};
using File = std::unique_ptr<std::FILE, FileCloser>;

// `bytes` in a temporary file (removed when closed).
File file_of(const std::string& bytes) {
  File f(std::tmpfile());
  EXPECT_TRUE(f);
  std::fwrite(bytes.data(), 1, bytes.size(), f.get());
  std::rewind(f.get());
  return f;
}

std::string header_check(const std::string& bytes) {
  const File f = file_of(bytes);
  return check_header_text(f.get(), bytes.size());
}

const std::string kHeader =
    "NRRD0004\ntype: float\ndimension: 4\nsizes: 2 2 1 1\nspace dimension: 3\n"
    "space directions: none (1,0,0) (0,1,0) (0,0,1)\nspace origin: (0,0,0)\nencoding: raw\n"
    "lattice:=bcc\n\n";

std::string with(const std::string& from, const std::string& to) {
  std::string h = kHeader;
  return h.replace(h.find(from), from.size(), to);
}

TEST(NrrdChecks, HeaderTextAcceptsAPlainHeader) { EXPECT_EQ(header_check(kHeader), ""); }

TEST(NrrdChecks, HeaderTextRefusesOtherFormatsAndDetachedData) {
  EXPECT_NE(header_check("P5\n2 2\n255\n").find("not a NRRD file"), std::string::npos);
  EXPECT_NE(header_check("").find("not a NRRD file"), std::string::npos);
  for (const char* field : {"data file: x.raw\n", "DATA  File: /dev/stdin\n", "datafile: y\n"})
    EXPECT_NE(header_check(with("encoding: raw\n", std::string("encoding: raw\n") + field))
                  .find("detached"),
              std::string::npos)
        << field;
  std::string long_header = "NRRD0004\n";
  while (long_header.size() <= kMaxHeaderBytes) long_header += "# comment\n";
  EXPECT_NE(header_check(long_header + "x").find("header is longer"), std::string::npos);
}

// Teem reads "23.5" as 23 and "-3" as a size it calls zero: both are refused here, in words.
TEST(NrrdChecks, SizesMustBePositiveIntegers) {
  for (const char* sizes : {"sizes: 2 23.5 23 23", "sizes: 2 -3 2 2", "sizes: 2 0 1 1",
                            "sizes: 2 1e3 1 1", "sizes: 2 0x10 1 1"}) {
    const std::string why = header_check(with("sizes: 2 2 1 1", sizes));
    EXPECT_NE(why.find("not all positive integers"), std::string::npos) << sizes << ": " << why;
    EXPECT_EQ(why.find('\n'), std::string::npos);
  }
  EXPECT_EQ(header_check(with("sizes: 2 2 1 1", "sizes:   2 10 007 1")), "");
}

TEST(NrrdChecks, SpaceFieldsMustBeFinite) {
  EXPECT_NE(header_check(with("space origin: (0,0,0)", "space origin: (nan,0,0)"))
                .find("space origin '(nan,0,0)' has a number that is not finite"),
            std::string::npos);
  EXPECT_NE(header_check(with("(0,1,0)", "(0,INF,0)")).find("space directions"), std::string::npos);
  // Key/value pairs are the writer's business, not Teem's fields.
  EXPECT_EQ(header_check(with("lattice:=bcc", "note:=sizes: nan")), "");
}

// Raw: the bytes after the header; ascii: whitespace-separated numbers; hex: digits.
TEST(NrrdChecks, DataLengthCountsRawAsciiAndHex) {
  const std::string head = "header\n\n";
  const long start = static_cast<long>(head.size());
  const auto length = [&](const std::string& data, Encoding e, std::uint64_t bytes,
                          std::uint64_t samples) {
    const std::string all = head + data;
    const File f = file_of(all);
    return check_data_length(f.get(), start, e, all.size(), bytes, samples);
  };
  EXPECT_EQ(length(std::string(16, 'x'), Encoding::Raw, 16, 4), "");
  EXPECT_NE(length(std::string(15, 'x'), Encoding::Raw, 16, 4).find("truncated"),
            std::string::npos);
  EXPECT_NE(length(std::string(17, 'x'), Encoding::Raw, 16, 4).find("17 bytes of raw data"),
            std::string::npos);
  EXPECT_EQ(length("1 2.5\n-3 4e1\n", Encoding::Ascii, 16, 4), "");
  EXPECT_NE(length("1 2.5\n-3\n", Encoding::Ascii, 16, 4).find("only 3 follow"), std::string::npos);
  EXPECT_EQ(length(std::string(32, 'a') + "\n", Encoding::Hex, 16, 4), "");
  EXPECT_NE(length(std::string(30, 'a'), Encoding::Hex, 16, 4).find("30"), std::string::npos);
  EXPECT_NE(length(std::string(31, 'a') + "g", Encoding::Hex, 16, 4).find("not a hex digit"),
            std::string::npos);
  EXPECT_EQ(length("anything", Encoding::Other, 16, 4), "");
}

std::string gzip(const std::string& data) {
  z_stream z{};
  EXPECT_EQ(deflateInit2(&z, 9, Z_DEFLATED, 15 + 16, 8, Z_DEFAULT_STRATEGY), Z_OK);
  std::string out(data.size() + 1024, '\0');
  z.next_in = reinterpret_cast<Bytef*>(const_cast<char*>(data.data()));
  z.avail_in = static_cast<uInt>(data.size());
  z.next_out = reinterpret_cast<Bytef*>(out.data());
  z.avail_out = static_cast<uInt>(out.size());
  EXPECT_EQ(deflate(&z, Z_FINISH), Z_STREAM_END);
  out.resize(z.total_out);
  deflateEnd(&z);
  return out;
}

std::string bzip2(const std::string& data) {
  std::string out(data.size() + 1024, '\0');
  auto size = static_cast<unsigned>(out.size());
  EXPECT_EQ(BZ2_bzBuffToBuffCompress(out.data(), &size, const_cast<char*>(data.data()),
                                     static_cast<unsigned>(data.size()), 9, 0, 0),
            BZ_OK);
  out.resize(size);
  return out;
}

// Compressed data count once decompressed: exact, short, long, corrupt, and members in a row.
TEST(NrrdChecks, DataLengthDecompressesGzipAndBzip2) {
  const std::string data(4000, 'q');
  for (const Encoding e : {Encoding::Gzip, Encoding::Bzip2}) {
    SCOPED_TRACE(e == Encoding::Gzip ? "gzip" : "bzip2");
    const auto pack = [&](const std::string& d) {
      return e == Encoding::Gzip ? gzip(d) : bzip2(d);
    };
    const auto length = [&](const std::string& stored) {
      const File f = file_of(stored);
      return check_data_length(f.get(), 0, e, stored.size(), data.size(), 1000);
    };
    EXPECT_EQ(length(pack(data)), "");
    EXPECT_NE(length(pack(data.substr(1))).find("truncated"), std::string::npos);
    EXPECT_NE(length(pack(data + "x")).find("more than"), std::string::npos);
    EXPECT_EQ(length(pack(data.substr(0, 1000)) + pack(data.substr(1000))), "");
    std::string corrupt = pack(data);
    for (std::size_t i = 12; i < corrupt.size(); i += 7)
      corrupt[i] = static_cast<char>(~corrupt[i]);
    EXPECT_NE(length(corrupt).find("corrupt"), std::string::npos) << length(corrupt);
  }
  // gzip data without the gzip magic is stored as it is (Teem reads it so).
  const File f = file_of(data);
  EXPECT_EQ(check_data_length(f.get(), 0, Encoding::Gzip, data.size(), data.size(), 1000), "");
}

template <class T>
T swapped(T x) {
  unsigned char b[sizeof(T)];
  std::memcpy(b, &x, sizeof(T));
  std::reverse(b, b + sizeof(T));
  std::memcpy(&x, b, sizeof(T));
  return x;
}

// Plausible samples pass in either order; samples read in the wrong order are refused naming the
// declared order.
TEST(NrrdChecks, ByteOrderThatTheDataContradictIsRefused) {
  const std::vector<double> values = {1.0, -2.5, 0.0, 3e5, 0.125, 7.0};
  std::vector<double> wrong;
  for (double v : values) wrong.push_back(swapped(v));
  EXPECT_EQ(check_byte_order<double>(values, "little"), "");
  const std::string why = check_byte_order<double>(wrong, "big");
  EXPECT_NE(why.find("'endian: big'"), std::string::npos) << why;
  EXPECT_NE(why.find("5 of its 5 non-zero"), std::string::npos) << why;
  const std::vector<float> floats = {1.0f, 2.0f, -0.5f};
  std::vector<float> wrong_floats;
  for (float v : floats) wrong_floats.push_back(swapped(v));
  EXPECT_EQ(check_byte_order<float>(floats, "little"), "");
  EXPECT_NE(check_byte_order<float>(wrong_floats, "little").find("1e+-20"), std::string::npos);
  // One odd sample among plausible ones is data, not a byte-order lie.
  std::vector<double> mostly = values;
  mostly[1] = 1e200;
  EXPECT_EQ(check_byte_order<double>(mostly, "little"), "");
}

TEST(NrrdChecks, NonFiniteSamplesAreNamedByTheirPlace) {
  std::vector<float> samples(std::size_t{2} * 3 * 2 * 2, 1.0f);
  EXPECT_EQ(check_finite<float>(samples, 2, {3, 2, 2}), "");
  samples[std::size_t{2} * (1 + 3 * (1 + 2 * 1)) + 1] = -std::numeric_limits<float>::infinity();
  const std::string why = check_finite<float>(samples, 2, {3, 2, 2});
  EXPECT_NE(why.find("sample 21 (coset 1, 1, 1, 1) is -inf"), std::string::npos) << why;
}

TEST(NrrdChecks, DoublesBeyondFloatAreRefusedForFloat) {
  EXPECT_EQ(check_float_range(std::vector<double>{1e38, -3.0, std::nan("")}), "");
  EXPECT_NE(check_float_range(std::vector<double>{0.0, -1e39}).find("sample 1 = -1e+39"),
            std::string::npos);
}

}  // namespace
}  // namespace boxgen::runtime::nrrd_checks
