// Faults a hostile trial found in boxrecon's reading and results: a BCC
// file's coset order is honoured or refused, never guessed, and a result that is not finite is an
// error naming its cause, with nothing printed or written. Each case is a file written here by
// hand. BOXRECON_UNDER_TEST runs them against another boxrecon (an older build fails them).
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "boxrecon_scratch_test.h"
#include "cli_support.h"

namespace boxgen::test {
namespace {

namespace fs = std::filesystem;

// The header of a BCC volume of 2 x n^3 little-endian doubles, h = 1/2 (coset cells of 1),
// origin 0, and `extra` key/value lines.
std::string bcc_header(std::size_t n, const std::string& extra = "") {
  return "NRRD0004\ntype: double\ndimension: 4\nsizes: 2 " + std::to_string(n) + " " +
         std::to_string(n) + " " + std::to_string(n) +
         "\nspace dimension: 3\nspace directions: none (1,0,0) (0,1,0) (0,0,1)\n"
         "space origin: (0,0,0)\nkinds: list domain domain domain\nendian: little\n"
         "encoding: raw\nlattice:=bcc\n" +
         extra + "\n";
}

std::string doubles(const std::vector<double>& values) {
  std::string bytes(values.size() * sizeof(double), '\0');
  std::memcpy(bytes.data(), values.data(), bytes.size());
  return bytes;
}

class BoxreconFaults : public BoxreconScratchTest {
 protected:
  BoxreconFaults() : BoxreconScratchTest("boxrecon-faults") {}
  // A refused command: exit 1, one line on stderr naming `mention`, nothing on stdout.
  void refused(const std::vector<std::string>& args, const std::string& mention) {
    const ProcessResult r = boxrecon(args);
    const std::string what = describe(args, r);
    ASSERT_TRUE(r.exited) << what;
    EXPECT_EQ(r.exit_code, 1) << what;
    EXPECT_EQ(r.out, "") << what;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << what;
    EXPECT_EQ(r.err.rfind("boxrecon: error: ", 0), 0u) << what;
    EXPECT_NE(r.err.find(mention), std::string::npos) << "expected '" << mention << "'\n" << what;
  }
};

// A file that stores the odd coset first and says so (coset_offsets:=(1,1,1) (0,0,0)) is the
// same volume as the usual one: eval gives the same values, digit for digit.
TEST_F(BoxreconFaults, BccCosetOrderIsHonoured) {
  constexpr std::size_t n = 8;
  std::vector<double> usual(2 * n * n * n), swapped(usual.size());
  for (std::size_t s = 0; s < usual.size(); ++s)
    usual[s] = std::sin(0.37 * static_cast<double>(s)) + 0.01 * static_cast<double>(s % 7);
  for (std::size_t s = 0; s < usual.size(); ++s) swapped[s] = usual[s ^ 1];  // coset 0 <-> 1
  write_bytes(file("usual.nrrd"), bcc_header(n) + doubles(usual));
  write_bytes(file("swapped.nrrd"),
              bcc_header(n, "coset_offsets:=(1,1,1) (0,0,0)\n") + doubles(swapped));
  write_bytes(file("p.txt"), "3.75 3.6 4.05\n3.45 4.15 3.85\n4 4 4\n");
  for (const char* filter : {"m7", "m8", "m12"}) {
    SCOPED_TRACE(filter);
    const std::string expected = ok({"eval", "--filter", filter, "--volume", file("usual.nrrd"),
                                     "--points", file("p.txt"), "--gradient"});
    EXPECT_EQ(ok({"eval", "--filter", filter, "--volume", file("swapped.nrrd"), "--points",
                  file("p.txt"), "--gradient"}),
              expected);
  }
}

// Coset offsets that are not two cosets, rows that are not numbers and rows of another lattice
// are refused, never guessed.
TEST_F(BoxreconFaults, BccHeadersThatContradictThemselvesAreRefused) {
  constexpr std::size_t n = 4;
  const std::string data = doubles(std::vector<double>(2 * n * n * n, 0.5));
  write_bytes(file("p.txt"), "1.75 1.75 1.75\n");
  const struct {
    const char* name;
    const char* extra;
    const char* mention;
  } cases[] = {
      {"same", "coset_offsets:=(0,0,0) (0,0,0)\n", "same coset"},
      {"rows", "lattice_rows:=a,b,c\n", "lattice_rows"},
      {"cartesian", "lattice_rows:=1,0,0; 0,1,0; 0,0,1\n", "do not generate the bcc lattice"},
  };
  for (const auto& c : cases) {
    SCOPED_TRACE(c.name);
    write_bytes(file(std::string(c.name) + ".nrrd"), bcc_header(n, c.extra) + data);
    refused({"eval", "--filter", "m7", "--volume", file(std::string(c.name) + ".nrrd"), "--points",
             file("p.txt")},
            c.mention);
  }
}

// Finite samples near the largest double overflow the spline's sums: eval prints nothing and
// resample writes nothing; the message names the cause.
TEST_F(BoxreconFaults, NonFiniteResultsFromFiniteSamplesAreErrors) {
  constexpr std::size_t n = 6;
  std::vector<double> huge;
  for (std::size_t k = 0; k < n; ++k)
    for (std::size_t j = 0; j < n; ++j)
      for (std::size_t i = 0; i < n; ++i)
        for (std::size_t c = 0; c < 2; ++c)
          huge.push_back((i + j + k + c) % 2 == 0 ? 1e308 : -1e308);
  write_bytes(file("huge.nrrd"), bcc_header(n) + doubles(huge));
  write_bytes(file("p.txt"), "2.75 2.75 2.75\n");
  refused({"eval", "--filter", "m7", "--volume", file("huge.nrrd"), "--points", file("p.txt")},
          "too large for the spline's sums");
  refused({"resample", "--filter", "m7", "--volume", file("huge.nrrd"), "-o", file("grid.nrrd"),
           "--n", "4"},
          "not finite");
  EXPECT_FALSE(fs::exists(file("grid.nrrd")));
  // Allowed non-finite samples give non-finite values: the message says so.
  std::vector<double> with_nan(huge.size(), 0.25);
  with_nan[2 * (3 + n * (3 + n * 3))] = std::nan("");
  write_bytes(file("nan.nrrd"), bcc_header(n) + doubles(with_nan));
  refused({"eval", "--filter", "m7", "--volume", file("nan.nrrd"), "--points", file("p.txt"),
           "--allow-nonfinite"},
          "non-finite samples");
}

}  // namespace
}  // namespace boxgen::test
