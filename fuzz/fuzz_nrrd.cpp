// libFuzzer target for the BCC volume reader (runtime/nrrd_io.h). Teem reads from files (its
// in-memory reader takes NUL-terminated text only), so each input is written to one temporary file
// per process and read back as float and as double. Every input must either give a consistent
// volume or raise a NrrdError with a one-line message; a crash, a sanitizer report, any other
// exception or an inconsistent volume is a bug.
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

template <class T>
void read_or_nrrd_error(const std::filesystem::path& path) {
  try {
    const LatticeVolume<T> v = read_lattice_nrrd<T>(path, kLimits);
    const Sizes& n = v.sizes();
    require(n[0] >= 1 && n[1] >= 1 && n[2] >= 1, "sizes at least 1");
    require(v.sample_count() == 2 * static_cast<std::size_t>(n[0]) * n[1] * n[2],
            "sample count 2 N0 N1 N2");
    require(std::isfinite(v.spacing()) && v.spacing() > 0, "h finite and positive");
    for (double o : v.origin()) require(std::isfinite(o), "origin finite");
    // Touch the first and last samples through the lattice accessor.
    (void)v.value(0, 0, 0);
    (void)v.value(2 * n[0] - 1, 2 * n[1] - 1, 2 * n[2] - 1);
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

// The same through the reader of any lattice (lattice_volume.h).
template <class T>
void read_lattice_or_nrrd_error(const std::filesystem::path& path) {
  try {
    const LatticeVolume<T> v = read_lattice_nrrd<T>(path, kLimits);
    const Sizes& n = v.sizes();
    require(n[0] >= 1 && n[1] >= 1 && n[2] >= 1, "sizes at least 1");
    require(v.sample_count() == static_cast<std::size_t>(v.coset_count()) * n[0] * n[1] * n[2],
            "sample count K N0 N1 N2");
    require(std::isfinite(v.spacing()) && v.spacing() > 0, "h finite and positive");
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
  read_or_nrrd_error<float>(path);
  read_or_nrrd_error<double>(path);
  read_lattice_or_nrrd_error<double>(path);
  std::error_code ignored;
  std::filesystem::remove(path, ignored);
  return 0;
}
