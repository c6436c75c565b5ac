// boxrecon's file handling as a user meets it: -o never replaces a link, a special file or the
// input; arguments that used to fall back to a default or wrap around are refused; a NRRD whose
// header lies is refused; points files as people write them are read. Each case gives one line
// on stderr and exit code 1, and leaves every file as it was.
#include <sys/stat.h>
#include <sys/sysmacros.h>
#include <teem/nrrd.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "cli_support.h"
#include "tests/support/scratch_directory.h"

namespace boxgen::test {
namespace {

namespace fs = std::filesystem;

class BoxreconFiles : public ScratchDirectoryTest {
 protected:
  BoxreconFiles() : ScratchDirectoryTest("boxrecon-files") {}
  std::string file(const std::string& name) const { return (dir_ / name).string(); }

  void ok(const std::vector<std::string>& args, const std::string& stdin_file = "") {
    const ProcessResult r = boxrecon(args, {.stdout_file = "", .stdin_file = stdin_file});
    EXPECT_TRUE(r.exited && r.exit_code == 0) << describe(args, r);
    EXPECT_EQ(r.err, "") << describe(args, r);
    last_out_ = r.out;
  }
  // A refused command: exit 1, one line on stderr naming one of `mentions`, nothing on stdout.
  void refused(const std::vector<std::string>& args, const std::vector<std::string>& mentions) {
    const ProcessResult r = boxrecon(args);
    const std::string what = describe(args, r);
    ASSERT_TRUE(r.exited) << what;
    EXPECT_EQ(r.exit_code, 1) << what;
    EXPECT_EQ(r.out, "") << what;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << what;
    EXPECT_EQ(r.err.rfind("boxrecon: error: ", 0), 0u) << what;
    EXPECT_TRUE(std::any_of(
        mentions.begin(), mentions.end(),
        [&](const std::string& m) { return lower(r.err).find(lower(m)) != std::string::npos; }))
        << "expected one of " << ::testing::PrintToString(mentions) << "\n"
        << what;
  }
  // A valid volume of the cubic at N = 5, and its bytes.
  std::string make_volume(const std::string& name) {
    ok({"sample", "--function", "cubic", "--n", "5", "-o", file(name)});
    return read_bytes(file(name));
  }
  std::vector<std::string> eval_args(const std::string& volume, const std::string& points) {
    return {"eval",
            "--filter",
            "m7",
            "--volume",
            file(volume),
            "--points",
            points == "-" ? "-" : file(points)};
  }
  std::string last_out_;
};

bool is_nrrd(const fs::path& path) { return read_bytes(path).starts_with("NRRD000"); }

// ---------------------------------------------------------------------------------------------
// -o

TEST_F(BoxreconFiles, OutputThroughASymbolicLinkWritesItsTarget) {
  fs::create_directory(file("data"));
  write_bytes(file("data/old.nrrd"), "old contents");
  fs::create_symlink("data/old.nrrd", file("link.nrrd"));  // relative, as users make them
  ok({"sample", "--function", "cubic", "--n", "4", "-o", file("link.nrrd")});
  EXPECT_TRUE(fs::is_symlink(file("link.nrrd"))) << "the link was replaced by a file";
  EXPECT_TRUE(is_nrrd(file("data/old.nrrd"))) << "the link's target was not written";
  // A dangling link creates its target; resample writes through links too.
  fs::create_symlink("data/new.nrrd", file("dangling.nrrd"));
  ok({"resample", "--filter", "m7", "--volume", file("link.nrrd"), "-o", file("dangling.nrrd"),
      "--n", "3"});
  EXPECT_TRUE(fs::is_symlink(file("dangling.nrrd")));
  EXPECT_TRUE(is_nrrd(file("data/new.nrrd")));
  // Nothing else appeared (no temporary file left next to the link or its target).
  std::vector<std::string> names;
  for (const auto& e : fs::recursive_directory_iterator(dir_))
    names.push_back(e.path().lexically_relative(dir_).string());
  std::sort(names.begin(), names.end());
  EXPECT_EQ(names, (std::vector<std::string>{"dangling.nrrd", "data", "data/new.nrrd",
                                             "data/old.nrrd", "link.nrrd"}));
}

TEST_F(BoxreconFiles, OutputOntoAFifoIsRefusedAndTheFifoStays) {
  ASSERT_EQ(::mkfifo(file("fifo").c_str(), 0600), 0);
  refused({"sample", "--function", "cubic", "--n", "4", "-o", file("fifo")}, {"fifo"});
  struct stat info {};
  ASSERT_EQ(::lstat(file("fifo").c_str(), &info), 0);
  EXPECT_TRUE(S_ISFIFO(info.st_mode)) << "the FIFO was replaced";
}

TEST_F(BoxreconFiles, OutputOntoADeviceIsRefusedAndTheDeviceStays) {
  // Through a link in the scratch directory (never -o /dev/... directly: a broken build run as
  // root would replace the machine's device node).
  fs::create_symlink("/dev/null", file("null-link"));
  refused({"sample", "--function", "cubic", "--n", "4", "-o", file("null-link")}, {"device"});
  EXPECT_TRUE(fs::is_symlink(file("null-link")));
  EXPECT_TRUE(fs::is_character_file("/dev/null"));
  // A device node of its own (as root only): the same device as /dev/full.
  if (::mknod(file("full").c_str(), S_IFCHR | 0600, makedev(1, 7)) == 0) {
    refused({"sample", "--function", "cubic", "--n", "4", "-o", file("full")}, {"device"});
    struct stat info {};
    ASSERT_EQ(::lstat(file("full").c_str(), &info), 0);
    EXPECT_TRUE(S_ISCHR(info.st_mode)) << "the device node was replaced";
  }
  // A directory is not replaced either.
  fs::create_directory(file("dir"));
  refused({"sample", "--function", "cubic", "--n", "4", "-o", file("dir")},
          {"directory", "not a file name"});
  EXPECT_TRUE(fs::is_directory(file("dir")));
}

TEST_F(BoxreconFiles, OutputThatIsTheInputIsRefusedBeforeAnyWork) {
  const std::string volume = make_volume("v.nrrd");
  fs::create_directory(file("sub"));
  fs::create_symlink("v.nrrd", file("alias.nrrd"));
  fs::create_hard_link(file("v.nrrd"), file("hard.nrrd"));
  for (const std::string& out :
       {file("v.nrrd"), file("sub/../v.nrrd"), file("alias.nrrd"), file("hard.nrrd")}) {
    SCOPED_TRACE(out);
    refused({"resample", "--filter", "m7", "--volume", file("v.nrrd"), "-o", out, "--n", "3"},
            {"input"});
    EXPECT_EQ(read_bytes(file("v.nrrd")), volume) << "the input was overwritten";
  }
  // Reading through the link and writing the file itself is the same file as well.
  refused({"resample", "--filter", "m7", "--volume", file("alias.nrrd"), "-o", file("v.nrrd"),
           "--n", "3"},
          {"input"});
  EXPECT_EQ(read_bytes(file("v.nrrd")), volume);
  EXPECT_TRUE(fs::is_symlink(file("alias.nrrd")));
}

TEST_F(BoxreconFiles, ReplacingAFileKeepsItsPermissions) {
  write_bytes(file("v.nrrd"), "old");
  fs::permissions(file("v.nrrd"),
                  fs::perms::owner_read | fs::perms::owner_write | fs::perms::group_read);
  ok({"sample", "--function", "cubic", "--n", "4", "-o", file("v.nrrd")});
  EXPECT_TRUE(is_nrrd(file("v.nrrd")));
  EXPECT_EQ(fs::status(file("v.nrrd")).permissions() & fs::perms::mask,
            fs::perms::owner_read | fs::perms::owner_write | fs::perms::group_read);
}

// ---------------------------------------------------------------------------------------------
// Argument values

TEST_F(BoxreconFiles, SpacingMustBeFiniteAndPositive) {
  for (const char* h : {"0", "nan", "-0.1", "inf", "-0"}) {
    SCOPED_TRACE(h);
    refused({"sample", "--function", "cubic", "--n", "4", "--h", h, "-o", file("v.nrrd")}, {"--h"});
    EXPECT_FALSE(fs::exists(file("v.nrrd")));
  }
  // A valid --h is used: h = 0.25 puts the first odd sample at origin + 0.25.
  ok({"sample", "--function", "cubic", "--n", "4", "--h", "0.25", "-o", file("v.nrrd")});
  EXPECT_NE(read_bytes(file("v.nrrd")).find("(0.5,0,0)"), std::string::npos)
      << "space directions 2h = 0.5";
}

TEST_F(BoxreconFiles, SeedOutOfRangeIsAnError) {
  for (const char* seed :
       {"-1", "18446744073709551616", "99999999999999999999999", "1.5", "0x10", ""}) {
    SCOPED_TRACE(seed);
    refused({"error", "--function", "cubic", "--n", "5", "--filter", "m7", "--points", "10",
             "--seed", seed},
            {"--seed"});
  }
  ok({"error", "--function", "cubic", "--n", "5", "--filter", "m7", "--points", "10", "--seed",
      "18446744073709551615"});
  ok({"error", "--function", "cubic", "--n", "5", "--filter", "m7", "--points", "10", "--seed",
      "0"});
}

TEST_F(BoxreconFiles, AVolumeBeyondMemoryIsAnInputErrorBeforeAllocation) {
  // --n 1024 with the sampling margin of 3: 2 x 1030^3 doubles, about 16.3 GiB.
  const double needed = 2.0 * 1030 * 1030 * 1030 * 8;
  const double budget = static_cast<double>(::sysconf(_SC_PHYS_PAGES)) *
                        static_cast<double>(::sysconf(_SC_PAGE_SIZE)) / 2;
  if (needed <= budget) GTEST_SKIP() << "this machine has memory for --n 1024";
  refused({"sample", "--function", "cubic", "--n", "1024", "-o", file("v.nrrd")}, {"16.3 GiB"});
  // error samples with M7's own margin of 2: 2 x 1028^3 doubles, about 16.2 GiB.
  refused({"error", "--function", "cubic", "--n", "1024", "--filter", "m7"}, {"16.2 GiB"});
  EXPECT_FALSE(fs::exists(file("v.nrrd")));
}

// ---------------------------------------------------------------------------------------------
// Volumes whose header lies: the header of a 2 x 3^3 double volume (h = 0.5, origin 0) written
// by hand over data of another length, type or byte order.

std::string header(const std::string& type, const std::string& sizes,
                   const std::string& endian = "little") {
  return "NRRD0004\ntype: " + type + "\ndimension: 4\nspace dimension: 3\nsizes: " + sizes +
         "\nspace directions: none (1,0,0) (0,1,0) (0,0,1)\nspace origin: (0,0,0)\nendian: " +
         endian + "\nencoding: raw\nlattice:=bcc\n\n";
}

std::string doubles(std::size_t count, double value) {
  const std::vector<double> v(count, value);
  return std::string(reinterpret_cast<const char*>(v.data()), count * sizeof(double));
}

TEST_F(BoxreconFiles, AVolumeWhoseHeaderLiesIsRefused) {
  static_assert(std::endian::native == std::endian::little,
                "the data below are written little-endian");
  write_bytes(file("p.txt"), "1 1 1\n");
  // Positive control: the honest file reads.
  write_bytes(file("honest.nrrd"), header("double", "2 3 3 3") + doubles(54, 1.0));
  ok(eval_args("honest.nrrd", "p.txt"));
  // type float over double data: twice the bytes the header announces.
  write_bytes(file("float.nrrd"), header("float", "2 3 3 3") + doubles(54, 1.0));
  refused(eval_args("float.nrrd", "p.txt"), {"announces"});
  // too few sizes for the data.
  write_bytes(file("sizes.nrrd"), header("double", "2 3 3 2") + doubles(54, 1.0));
  refused(eval_args("sizes.nrrd", "p.txt"), {"announces"});
  // too much data by a single byte.
  write_bytes(file("extra.nrrd"), header("double", "2 3 3 3") + doubles(54, 1.0) + "x");
  refused(eval_args("extra.nrrd", "p.txt"), {"announces"});
  // endian: big over little-endian data.
  write_bytes(file("endian.nrrd"), header("double", "2 3 3 3", "big") + doubles(54, 1.0));
  refused(eval_args("endian.nrrd", "p.txt"), {"byte order"});
  // type float over gzip-compressed double data (Teem re-saves the honest file compressed).
  Nrrd* nrrd = nrrdNew();
  ASSERT_EQ(nrrdLoad(nrrd, file("honest.nrrd").c_str(), nullptr), 0);
  NrrdIoState* io = nrrdIoStateNew();
  io->encoding = nrrdEncodingGzip;
  ASSERT_EQ(nrrdSave(file("honest.gz.nrrd").c_str(), nrrd, io), 0);
  nrrdIoStateNix(io);
  nrrdNuke(nrrd);
  ok(eval_args("honest.gz.nrrd", "p.txt"));
  std::string gz = read_bytes(file("honest.gz.nrrd"));
  ASSERT_NE(gz.find("type: double"), std::string::npos);
  write_bytes(file("float.gz.nrrd"), gz.replace(gz.find("type: double"), 12, "type: float"));
  refused(eval_args("float.gz.nrrd", "p.txt"), {"announces"});
  // A real big-endian file is read in its declared byte order.
  std::string big = doubles(54, 1.0);
  for (std::size_t s = 0; s < big.size(); s += 8)
    std::reverse(big.begin() + static_cast<long>(s), big.begin() + static_cast<long>(s + 8));
  write_bytes(file("big.nrrd"), header("double", "2 3 3 3", "big") + big);
  ok(eval_args("big.nrrd", "p.txt"));
  EXPECT_EQ(last_out_, "1\n");  // partition of unity over samples 1
}

TEST_F(BoxreconFiles, NonFiniteSamplesAreRefusedUnlessAllowed) {
  std::string data = doubles(std::size_t{2} * 8 * 8 * 8, 1.0);
  const double nan = std::nan("");
  std::memcpy(data.data() + std::ptrdiff_t{8} * 3, &nan,
              8);  // sample 3: coset 1 of cell (1, 0, 0), far from the centre
  write_bytes(file("nan.nrrd"), header("double", "2 8 8 8") + data);
  write_bytes(file("p.txt"), "4 4 4\n");
  refused(eval_args("nan.nrrd", "p.txt"), {"not finite", "nan"});
  refused({"resample", "--filter", "m7", "--volume", file("nan.nrrd"), "-o", file("out.nrrd"),
           "--n", "3"},
          {"nan"});
  EXPECT_FALSE(fs::exists(file("out.nrrd")));
  auto args = eval_args("nan.nrrd", "p.txt");
  args.push_back("--allow-nonfinite");
  ok(args);
  EXPECT_EQ(last_out_, "1\n");  // the NaN is outside the stencil of the centre
}

// ---------------------------------------------------------------------------------------------
// Points files

TEST_F(BoxreconFiles, PointsOfADirectoryAreAnError) {
  make_volume("v.nrrd");
  fs::create_directory(file("pts"));
  refused(eval_args("v.nrrd", "pts"), {"directory"});
}

TEST_F(BoxreconFiles, PointsFilesAsPeopleWriteThem) {
  make_volume("v.nrrd");
  write_bytes(file("plain.txt"), "0 0 0\n0.5 -0.25 0.125\n-0.5 0.5 0\n");
  ok(eval_args("v.nrrd", "plain.txt"));
  const std::string expected = last_out_;
  ASSERT_EQ(std::count(expected.begin(), expected.end(), '\n'), 3);
  const std::vector<std::pair<const char*, std::string>> variants = {
      {"blank lines", "\n0 0 0\n\n   \n0.5 -0.25 0.125\n\t\n-0.5 0.5 0\n\n"},
      {"comments", "# x y z\n0 0 0  # the centre\n#0.1 0.1 0.1\n0.5 -0.25 0.125\n-0.5 0.5 0 #\n"},
      {"CRLF", "0 0 0\r\n0.5 -0.25 0.125\r\n-0.5 0.5 0\r\n"},
      {"BOM",
       "\xEF\xBB\xBF"
       "0 0 0\n0.5 -0.25 0.125\n-0.5 0.5 0"},
      {"tabs and plus signs", "0\t0\t0\n+0.5 -0.25 +0.125\n-5e-1 5E-1 0\n"},
  };
  for (const auto& [name, text] : variants) {
    SCOPED_TRACE(name);
    write_bytes(file("variant.txt"), text);
    ok(eval_args("v.nrrd", "variant.txt"));
    EXPECT_EQ(last_out_, expected);
  }
  // "-" reads standard input.
  write_bytes(file("stdin.txt"), "# from stdin\r\n0 0 0\r\n0.5 -0.25 0.125\r\n-0.5 0.5 0\r\n");
  ok(eval_args("v.nrrd", "-"), file("stdin.txt"));
  EXPECT_EQ(last_out_, expected);
  // A bad line still names its line number, counted with the blank and comment lines.
  write_bytes(file("bad.txt"), "# header\n\n0 0 0\n0 zero 0\n");
  refused(eval_args("v.nrrd", "bad.txt"), {"bad.txt:4"});
}

// ---------------------------------------------------------------------------------------------
// sample --lattice

// The header field `name` of a NRRD file ("" if absent), and its data as doubles.
std::string field(const std::string& text, const std::string& name) {
  const std::size_t at = text.find("\n" + name);
  if (at == std::string::npos) return "";
  const std::size_t start = at + 1 + name.size(), end = text.find('\n', start);
  return text.substr(start, end - start);
}

std::vector<double> data_of(const std::string& text) {
  const std::size_t start = text.find("\n\n") + 2;
  std::vector<double> values((text.size() - start) / 8);
  std::memcpy(values.data(), text.data() + start, values.size() * 8);
  return values;
}

TEST_F(BoxreconFiles, SampleOnEveryLattice) {
  // --lattice bcc is the default, byte for byte.
  ok({"sample", "--function", "cubic", "--n", "4", "-o", file("default.nrrd")});
  ok({"sample", "--function", "cubic", "--n", "4", "--lattice", "bcc", "-o", file("bcc.nrrd")});
  EXPECT_EQ(read_bytes(file("bcc.nrrd")), read_bytes(file("default.nrrd")));
  // N = 4 and margin 3: 10 samples per coset and axis, cells of 2/3, origin -1 - 3 (2/3) = -3.
  struct Case {
    const char* lattice;
    int k;
    int d;
    std::vector<std::array<int, 3>> offsets;  // as the issue specifies them
    const char* key;
  };
  const std::vector<Case> cases = {
      {"fcc", 4, 2, {{0, 0, 0}, {1, 1, 0}, {1, 0, 1}, {0, 1, 1}}, "fcc"},
      {"cartesian", 1, 1, {{0, 0, 0}}, "cartesian"},
      {"1,0,0; 0,1,0; 0,0,2", 4, 2, {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {1, 1, 0}}, "custom"},
  };
  for (const Case& c : cases) {
    SCOPED_TRACE(c.lattice);
    ok({"sample", "--function", "cubic", "--n", "4", "--lattice", c.lattice, "-o", file("v.nrrd")});
    const std::string text = read_bytes(file("v.nrrd"));
    EXPECT_EQ(field(text, "lattice:="), c.key);
    const std::size_t k = c.offsets.size();
    EXPECT_EQ(field(text, "sizes: "),
              (k == 1 ? std::string() : std::to_string(k) + " ") + "10 10 10");
    const double h = 2.0 / 3 / c.d;
    const std::vector<double> values = data_of(text);
    ASSERT_EQ(values.size(), k * 1000);
    // A few samples (c, i, j, k) against the cubic at o + h (d (i,j,k) + off_c).
    for (std::size_t s : {std::size_t{0}, k * 123 + k - 1, values.size() - 1, values.size() / 2}) {
      const std::size_t coset = s % k, cell = s / k;
      const std::array<int, 3>& off = c.offsets[coset];
      const std::size_t i = cell % 10, j = (cell / 10) % 10, l = cell / 100;  // the cell's indices
      const double x = -3 + h * (c.d * static_cast<double>(i) + off[0]);
      const double y = -3 + h * (c.d * static_cast<double>(j) + off[1]);
      const double z = -3 + h * (c.d * static_cast<double>(l) + off[2]);
      EXPECT_NEAR(values[s], cubic({x, y, z}), 1e-12 * (1 + std::abs(cubic({x, y, z})))) << s;
    }
  }
  // A BCC filter on the FCC volume is one error naming both lattices.
  ok({"sample", "--function", "cubic", "--n", "4", "--lattice", "fcc", "-o", file("fcc.nrrd")});
  write_bytes(file("p.txt"), "0 0 0\n");
  refused({"eval", "--filter", "m7", "--volume", file("fcc.nrrd"), "--points", file("p.txt")},
          {"filter m7 is for the bcc lattice, but the volume is on the fcc lattice"});
  // z = 0 mod 2 is the custom lattice above: its rows and offsets are in the file.
  EXPECT_EQ(field(read_bytes(file("v.nrrd")), "lattice_rows:="), "1,0,0; 0,1,0; 0,0,2");
  EXPECT_EQ(field(read_bytes(file("v.nrrd")), "coset_offsets:="),
            "(0,0,0) (1,0,0) (0,1,0) (1,1,0)");
  for (const char* bad : {"hexagonal", "1,0,0; 0,1,0; 1,1,0", "1,0,0; 0,1,0"}) {
    SCOPED_TRACE(bad);
    refused({"sample", "--function", "cubic", "--n", "4", "--lattice", bad, "-o", file("bad.nrrd")},
            {"lattice"});
    EXPECT_FALSE(fs::exists(file("bad.nrrd")));
  }
}

// ---------------------------------------------------------------------------------------------
// boxgen emit writes through the same module (support/output_file.h).

TEST_F(BoxreconFiles, EmitWritesThroughLinksAndRefusesSpecialFiles) {
  const std::string spec = "1,0; 0,1; 1,1";  // a small planar box spline: derived in milliseconds
  fs::create_directory(file("out"));
  fs::create_directory(file("real"));
  fs::create_symlink("../real/zp.hpp", file("out/zp.hpp"));
  ProcessResult r = boxgen({"emit", spec, "--name", "zp", "--out", file("out")});
  EXPECT_TRUE(r.exited && r.exit_code == 0) << describe({"emit"}, r);
  EXPECT_TRUE(fs::is_symlink(file("out/zp.hpp")));
  EXPECT_NE(read_bytes(file("real/zp.hpp")).find("zp"), std::string::npos);
  EXPECT_TRUE(fs::is_regular_file(file("out/zp_prefilters.hpp")));
  // A FIFO in place of one of the files: refused before anything is written, the FIFO stays.
  fs::remove(file("out/zp_prefilters.hpp"));
  ASSERT_EQ(::mkfifo(file("out/zp_prefilters.hpp").c_str(), 0600), 0);
  const std::string before = read_bytes(file("real/zp.hpp"));
  r = boxgen({"emit", spec, "--name", "zp", "--out", file("out")});
  EXPECT_TRUE(r.exited && r.exit_code == 1) << describe({"emit"}, r);
  EXPECT_NE(r.err.find("FIFO"), std::string::npos) << r.err;
  EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
  struct stat info {};
  ASSERT_EQ(::lstat(file("out/zp_prefilters.hpp").c_str(), &info), 0);
  EXPECT_TRUE(S_ISFIFO(info.st_mode));
  EXPECT_EQ(read_bytes(file("real/zp.hpp")), before);
}

}  // namespace
}  // namespace boxgen::test
