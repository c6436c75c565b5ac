// What the volume readers (nrrd_io.h, nifti_io.h) share: what a file stored before its samples
// became float or double (for scaling output: slices, PSNR, iso values), and the one way a grid
// stored with negative axis steps (scanners' radiological x, NIfTI's qfac = -1) becomes a volume
// with positive ones, every world point keeping its sample.
#pragma once
#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <utility>

#include "runtime/affine.h"
#include "runtime/lattice_volume.h"

namespace boxgen::runtime {

// The codes of a NIfTI file's qform and sform (NIfTI's NIFTI_XFORM_*: 1 scanner, 2 aligned
// anatomical, 3 Talairach, 4 MNI-152, 5 template; 0 unknown): what the world of the file is, kept
// so that a NIfTI written from it claims the same (write_nifti). Both 0 for other files.
struct NiftiCodes {
  int qform = 0, sform = 0;
  bool any() const { return qform > 0 || sform > 0; }
  bool operator==(const NiftiCodes&) const = default;
};

// The file's sample type ("int8", "uint8", "int16", "uint16", "int32", "uint32", "float",
// "double") and the range of its values as read (after a NIfTI scale slope and intercept).
struct SourceSamples {
  std::string type;
  double min = 0, max = 0;
  // An oblique (or axis-permuting) NIfTI volume read with NrrdReadLimits::allow_oblique: the
  // volume is its voxel grid in its own frame (spacings = the voxel sizes, origin 0, axes as
  // stored) and `frame` maps that frame to the file's world (a rotation, or any linear map with
  // unit columns, and a translation). Nothing for an axis-aligned volume, whose frame is the world.
  std::optional<Affine> frame;
  // The anatomical direction each world axis points to, as three letters ("RAS": +x right, +y
  // anterior, +z superior; NIfTI with a qform or sform, a NRRD's space "right-anterior-superior";
  // "LPS" for a NRRD in DICOM's space): empty when the file's world is not tied to a patient.
  std::string anatomical;
  // A NIfTI file's own qform and sform codes (both 0 for NRRD).
  NiftiCodes nifti_codes;
};

// Calls f(S{}) with S the C++ type of a sample type named as SourceSamples::type names it; false
// (f not called) for any other name. The one dispatch of the readers' conversions.
template <class F>
bool visit_sample_type(std::string_view name, F&& f) {
  if (name == "int8") return f(std::int8_t{}), true;
  if (name == "uint8") return f(std::uint8_t{}), true;
  if (name == "int16") return f(std::int16_t{}), true;
  if (name == "uint16") return f(std::uint16_t{}), true;
  if (name == "int32") return f(std::int32_t{}), true;
  if (name == "uint32") return f(std::uint32_t{}), true;
  if (name == "float") return f(float{}), true;
  if (name == "double") return f(double{}), true;
  return false;
}

template <class T>
SourceSamples describe_samples(std::span<const T> samples, std::string type) {
  SourceSamples s;
  s.type = std::move(type);
  if (samples.empty()) return s;
  const auto [lo, hi] = std::minmax_element(samples.begin(), samples.end());
  s.min = static_cast<double>(*lo);
  s.max = static_cast<double>(*hi);
  return s;
}

// A grid of sizes n (x fastest) whose sample (i, j, k) sits at origin + (i s0, j s1, k s2):
// every axis with a negative step is reversed in storage, its step negated and its origin moved
// to the old last sample, so that the world position of every value is unchanged (no change of
// handedness: the world frame stays the file's).
template <class T>
void orient_axes_positive(std::span<T> samples, const Sizes& n, Vec3& steps, Vec3& origin) {
  const std::size_t stride[3] = {1, static_cast<std::size_t>(n[0]),
                                 static_cast<std::size_t>(n[0]) * static_cast<std::size_t>(n[1])};
  const std::size_t total = stride[2] * static_cast<std::size_t>(n[2]);
  for (int a = 0; a < 3; ++a) {
    if (steps[a] >= 0) continue;
    origin[a] += steps[a] * (n[a] - 1);
    steps[a] = -steps[a];
    const std::size_t len = static_cast<std::size_t>(n[a]), s = stride[a];
    // Each line along axis a starts at an index whose coordinate a is 0.
    for (std::size_t start = 0; start < total; ++start) {
      if ((start / s) % len != 0) continue;
      for (std::size_t i = 0, j = len - 1; i < j; ++i, --j)
        std::swap(samples[start + i * s], samples[start + j * s]);
    }
  }
}

}  // namespace boxgen::runtime
