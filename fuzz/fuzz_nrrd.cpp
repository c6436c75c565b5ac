// libFuzzer target for the volume reader (runtime/nrrd_io.h: the Teem wrapper and the checks of
// runtime/nrrd_checks.h it runs before and after Teem). Teem reads from files (its in-memory
// reader takes NUL-terminated text only), so each input is written to one temporary file per
// process and read back as float and as double, as a BCC filter reads it (the BCC header keys,
// coset offsets and lattice rows, are in the seeds and the dictionary) and on any lattice. Every
// input must either give a consistent volume or raise a NrrdError with a one-line message; a crash,
// a sanitizer report, any other exception or an inconsistent volume is a bug.
#include <unistd.h>

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <filesystem>
#include <fstream>
#include <string>
#include <string_view>

#include "runtime/nrrd_io.h"

namespace {

using namespace boxgen::runtime;

void require(bool condition, const char* what) {
  if (condition) return;
  std::fprintf(stderr, "fuzz_nrrd: invariant violated: %s\n", what);
  std::abort();
}

// One file per process, removed after each input (libFuzzer may end with _Exit, skipping atexit).
const std::filesystem::path& input_path() {
  static const std::filesystem::path path =
      std::filesystem::temp_directory_path() /
      ("boxgen-fuzz-nrrd-" + std::to_string(::getpid()) + ".nrrd");
  return path;
}

// Keep what a small input can make us allocate far below libFuzzer's memory limit.
const NrrdReadLimits kLimits{std::uint64_t{1} << 24, false, std::nullopt};

// Any lattice, or (on_bcc) as a BCC filter reads it: then the volume holds BCC's points, in the
// coset order the file gave.
template <class T>
void read_lattice_or_nrrd_error(const std::filesystem::path& path, bool on_bcc) {
  try {
    NrrdReadLimits limits = kLimits;
    if (on_bcc) limits.lattice = CosetLattice::bcc();
    const LatticeVolume<T> v = read_lattice_nrrd<T>(path, limits);
    if (on_bcc && v.lattice().name() == "bcc")
      require(v.coset_count() == 2 && v.period() == 2, "a BCC volume has two cosets of 2 Z^3");
    const Sizes& n = v.sizes();
    require(n[0] >= 1 && n[1] >= 1 && n[2] >= 1, "sizes at least 1");
    require(v.sample_count() == static_cast<std::size_t>(v.coset_count()) * n[0] * n[1] * n[2],
            "sample count K N0 N1 N2");
    require(std::isfinite(v.spacing()) && v.spacing() > 0, "h finite and positive");
    for (double o : v.origin()) require(std::isfinite(o), "origin finite");
    // Every coset's first and last samples through the lattice accessor.
    for (int c = 0; c < v.coset_count(); ++c) {
      require(v.value(v.lattice_point(c, 0, 0, 0)) == v.at(c, 0, 0, 0), "first sample of a coset");
      require(v.contains(v.lattice_point(c, n[0] - 1, n[1] - 1, n[2] - 1)),
              "last sample of a coset");
    }
  } catch (const NrrdError& e) {
    const std::string_view message = e.what();
    require(!message.empty(), "NrrdError message is empty");
    require(message.find_first_of("\r\n") == std::string_view::npos,
            "NrrdError message spans several lines");
  } catch (const std::exception& e) {
    std::fprintf(stderr, "fuzz_nrrd: unexpected exception: %s\n", e.what());
    std::abort();
  }
}

}  // namespace

// Teem 1.12 leaks on some of its error paths: support/lsan_suppressions.cpp, linked in, names
// them, or every such input would count as a crash.

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::filesystem::path& path = input_path();
  {
    std::ofstream out(path, std::ios::binary | std::ios::trunc);
    out.write(reinterpret_cast<const char*>(data), static_cast<std::streamsize>(size));
    require(static_cast<bool>(out.flush()), "the input could be written to the temporary file");
  }
  read_lattice_or_nrrd_error<float>(path, true);
  read_lattice_or_nrrd_error<double>(path, true);
  read_lattice_or_nrrd_error<double>(path, false);
  std::error_code ignored;
  std::filesystem::remove(path, ignored);
  return 0;
}
