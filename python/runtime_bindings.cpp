// boxgen.Volume, Filter, read_volume, write_volume, sample, resample: the runtime's one API
// (docs/runtime.md) for Python, NumPy in and out. A Volume's samples are a NumPy view of the
// runtime's storage (no copy); evaluation and resampling run without the GIL, on the runtime's
// batch threads (BOXGEN_THREADS), and check their arguments with the messages boxrecon prints.
#include <pybind11/numpy.h>
#include <pybind11/stl.h>

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <cstdint>
#include <memory>
#include <optional>
#include <span>
#include <stdexcept>
#include <string>
#include <variant>
#include <vector>

#include "frontend/filter_choice.h"
#include "frontend/input_checks.h"
#include "frontend/sample_grid.h"
#include "generator/box_spline_properties.h"
#include "generator/spec.h"
#include "python/bindings.h"
#include "runtime/batch_threads.h"
#include "runtime/coefficients.h"
#include "runtime/interpolation.h"
#include "runtime/lattice_grid_choice.h"
#include "runtime/nifti_io.h"
#include "runtime/nrrd_checks.h"
#include "runtime/nrrd_io.h"
#include "runtime/prefilter.h"
#include "runtime/reconstruction.h"
#include "runtime/resample.h"
#include "runtime/sample_encoding.h"
#include "runtime/sampling.h"
#include "runtime/source_samples.h"
#include "runtime/test_functions.h"
#include "runtime/volume_output.h"

namespace py = pybind11;
namespace rt = boxgen::runtime;
namespace gen = boxgen::generator;

namespace boxgen::python {

namespace {

using Samples = rt::LatticeVolume<double>;

// A boxgen.Volume: samples on a lattice and, for an oblique Cartesian volume (a scanner's tilted
// slices), the map from its own frame to world (SourceSamples::frame, as boxrecon keeps it): the
// samples lie on the axes of that frame, world points map through its inverse and derivatives
// back through its linear part (rt::derivatives_to_world). Nothing for an axis-aligned volume.
// `anatomical`: the patient's frame of its world (SourceSamples::anatomical: "RAS", "LAS", "LPS";
// "" for none), which write_volume passes on as boxrecon's outputs do (NIfTI: mapped to RAS).
// `nifti_codes`: the qform and sform codes of the NIfTI file it was read from
// (SourceSamples::nifti_codes), which a NIfTI write_volume claims again.
struct Volume : Samples {
  std::optional<rt::Affine> frame;
  std::string anatomical;
  rt::NiftiCodes nifti_codes;
  explicit Volume(Samples&& samples, std::optional<rt::Affine> to_world = std::nullopt,
                  std::string world = {}, rt::NiftiCodes codes = {})
      : Samples(std::move(samples)),
        frame(to_world),
        anatomical(std::move(world)),
        nifti_codes(codes) {}
};
using VolumePtr = std::shared_ptr<Volume>;

// A box spline filter: the runtime's SplineFilter and the generator's SPEC and properties.
struct Filter {
  rt::SplineFilter filter;
  std::string spec_text, lattice_text;  // as given (for pickling)
  gen::BoxSplineSpec spec;
  gen::BoxSplineProperties properties;
};

std::string shape_text(const py::array& a) {
  std::string out = "(";
  for (py::ssize_t i = 0; i < a.ndim(); ++i) out += fmt::format("{}{}", i ? ", " : "", a.shape(i));
  return out + (a.ndim() == 1 ? ",)" : ")");
}

// `obj` as float64 in the layout `order` ("C" or "F"), by NumPy's own asarray: pybind11's
// ensure() clears a failed conversion's error, so a copy that could not be allocated surfaced as
// "ValueError: cannot create a pybind11::array_t from a nullptr"; NumPy raises MemoryError,
// naming the size.
py::array numpy_float64(const py::handle& obj, const char* order) {
  return py::module_::import("numpy").attr("asarray")(obj, py::arg("dtype") = "float64",
                                                      py::arg("order") = order);
}

// `what` as a float64 array: real numbers only (TypeError for strings, objects, complex, bool).
py::array_t<double> real_array(const py::handle& obj, const char* what) {
  py::array a;
  if (py::isinstance<py::array>(obj)) {
    a = py::reinterpret_borrow<py::array>(obj);
  } else {
    try {
      a = py::module_::import("numpy").attr("asarray")(obj);
    } catch (const py::error_already_set& e) {
      if (e.matches(PyExc_MemoryError)) throw;
      throw py::type_error(fmt::format("{} must be a NumPy array of real numbers", what));
    }
  }
  const char kind = a.dtype().kind();
  if (kind != 'f' && kind != 'i' && kind != 'u')
    throw py::type_error(fmt::format("{} must hold real numbers, got dtype {}", what,
                                     py::str(a.dtype()).cast<std::string>()));
  return py::array_t<double, py::array::c_style>::ensure(numpy_float64(a, "C"));
}

// An (n, 3) array of finite world coordinates, C-contiguous float64 (copied only if needed).
py::array_t<double> points_array(const py::handle& obj) {
  py::array_t<double> p = real_array(obj, "points");
  if (p.ndim() != 2 || p.shape(1) != 3)
    throw py::value_error(fmt::format(
        "points must be an (n, 3) array of world coordinates x y z, got shape {}", shape_text(p)));
  // One pass over the exponent bits (vectorised; no branch per coordinate), then the first
  // non-finite coordinate for the message.
  const double* x = p.data();
  const auto count = static_cast<std::size_t>(p.shape(0)) * 3;
  constexpr std::uint64_t kExponent = 0x7ff0000000000000ULL;
  std::uint64_t non_finite = 0;
  for (std::size_t i = 0; i < count; ++i)
    non_finite |=
        static_cast<std::uint64_t>((std::bit_cast<std::uint64_t>(x[i]) & kExponent) == kExponent);
  if (non_finite != 0)
    for (std::size_t i = 0; i < count; ++i)
      if (!std::isfinite(x[i]))
        throw py::value_error(
            fmt::format("points[{}]: the coordinate '{}' is not finite", i / 3, x[i]));
  return p;
}

std::array<double, 3> three(const py::handle& obj, const char* what) {
  const py::array_t<double> a = real_array(obj, what);
  if (a.ndim() != 1 || a.shape(0) != 3)
    throw py::value_error(
        fmt::format("{} must be three numbers x y z, got shape {}", what, shape_text(a)));
  return {a.at(0), a.at(1), a.at(2)};
}

rt::PrefilterChoice prefilter_choice(const std::optional<std::string>& name) {
  return rt::parse_prefilter(name.value_or("none"));
}

// prefilter= and boundary= of every function that takes them (as boxrecon's --prefilter and
// --boundary; None: "none" and mirror).
struct Prefiltering {
  rt::PrefilterChoice q;
  rt::Boundary b;
};
Prefiltering prefiltering(const std::optional<std::string>& prefilter,
                          const std::optional<std::string>& boundary) {
  return {prefilter_choice(prefilter),
          boundary ? rt::parse_boundary(*boundary) : rt::kDefaultBoundary};
}

// The coefficients the filter evaluates after prefilter and boundary p (runtime/coefficients.h):
// the volume itself (none, strict), or a new volume in `storage`. The lattice is checked first
// (one line naming both lattices).
const Samples& prepared(const Samples& volume, const Filter& f, const Prefiltering& p,
                        std::optional<Samples>& storage,
                        rt::InterpolationReport* report = nullptr) {
  f.filter.check_lattice(volume.lattice());
  if (p.q == rt::PrefilterChoice::None && p.b == rt::Boundary::Strict) return volume;
  storage.emplace(rt::spline_coefficients(volume, f.filter, p.q, p.b, report, report != nullptr));
  return *storage;
}

// Taps as NumPy arrays: (offsets (m, 3), weights (m,)).
py::tuple taps_arrays(const rt::PrefilterTaps& taps) {
  py::array_t<long> offsets(std::vector<py::ssize_t>{static_cast<py::ssize_t>(taps.size()), 3});
  py::array_t<double> weights(static_cast<py::ssize_t>(taps.size()));
  for (std::size_t i = 0; i < taps.size(); ++i) {
    for (int a = 0; a < 3; ++a)
      offsets.mutable_at(static_cast<py::ssize_t>(i), a) =
          taps[i].first[static_cast<std::size_t>(a)];
    weights.mutable_at(static_cast<py::ssize_t>(i)) = taps[i].second;
  }
  return py::make_tuple(offsets, weights);
}

// A float64 array over a vector it takes over (no copy), Fortran order when `fortran`.
py::array_t<double> adopt(std::vector<double>&& values, const std::vector<py::ssize_t>& shape,
                          bool fortran) {
  auto* owned = new std::vector<double>(std::move(values));
  py::capsule base(owned, [](void* p) { delete static_cast<std::vector<double>*>(p); });
  std::vector<py::ssize_t> strides(shape.size());
  py::ssize_t stride = sizeof(double);
  if (fortran) {
    for (std::size_t a = 0; a < shape.size(); ++a) strides[a] = stride, stride *= shape[a];
  } else {
    for (std::size_t a = shape.size(); a-- > 0;) strides[a] = stride, stride *= shape[a];
  }
  return py::array_t<double>(shape, strides, owned->data(), base);
}

py::array_t<double> grid_array(rt::CartesianVolume<double>&& grid) {
  const rt::Sizes n = grid.sizes;
  return adopt(std::move(grid.values), {n[0], n[1], n[2]}, true);  // x fastest: [i, j, k]
}

// The samples array (K, N0, N1, N2), any layout, as storage order (coset fastest).
std::vector<double> storage_of(const py::handle& samples, const rt::CosetLattice& lattice) {
  py::array_t<double> a = real_array(samples, "samples");
  const int k = lattice.coset_count();
  if (a.ndim() != 4 || a.shape(0) != k)
    throw py::value_error(fmt::format(
        "samples of shape {} do not fit the {} lattice: give a ({}, N0, N1, N2) array, its "
        "first axis the {} coset(s)",
        shape_text(a), lattice.name(), k, k));
  const auto fortran = py::array_t<double, py::array::f_style>::ensure(numpy_float64(a, "F"));
  return {fortran.data(), fortran.data() + fortran.size()};
}

rt::CosetLattice lattice_of(const std::string& text,
                            const std::optional<std::vector<std::array<int, 3>>>& offsets) {
  rt::CosetLattice lattice = rt::CosetLattice::parse(text);
  if (!offsets) return lattice;
  std::vector<rt::Offset> o;
  for (const auto& x : *offsets) o.push_back({x[0], x[1], x[2]});
  return lattice.with_offsets(o);
}

std::vector<std::array<int, 3>> offsets_of(const rt::CosetLattice& lattice) {
  std::vector<std::array<int, 3>> out;
  for (const auto& o : lattice.offsets())
    out.push_back({static_cast<int>(o[0]), static_cast<int>(o[1]), static_cast<int>(o[2])});
  return out;
}

// spacing=: one number h, or three (an anisotropic Cartesian volume, as scanners write).
rt::Vec3 spacing_of(const py::handle& spacing) {
  const py::array_t<double> a = real_array(spacing, "spacing");
  if (a.ndim() == 0) {
    const double h = *a.data();
    return {h, h, h};
  }
  return three(spacing, "spacing");
}

// A 4x4 (or 3x4) affine argument, as nibabel's img.affine: finite, last row (0, 0, 0, 1).
rt::Affine affine_arg(const py::handle& affine) {
  const py::array_t<double> a = real_array(affine, "affine");
  if (a.ndim() != 2 || (a.shape(0) != 4 && a.shape(0) != 3) || a.shape(1) != 4)
    throw py::value_error(
        fmt::format("affine must be a 4 x 4 (or 3 x 4) matrix, got shape {}", shape_text(a)));
  if (a.shape(0) == 4 && (a.at(3, 0) != 0 || a.at(3, 1) != 0 || a.at(3, 2) != 0 || a.at(3, 3) != 1))
    throw py::value_error("affine's last row must be (0, 0, 0, 1)");
  rt::Affine out;
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 4; ++c) {
      if (!std::isfinite(a.at(r, c)))
        throw py::value_error(fmt::format("affine[{}, {}] is not finite", r, c));
      const auto ru = static_cast<std::size_t>(r), cu = static_cast<std::size_t>(c);
      (c < 3 ? out.linear[ru][cu] : out.translation[ru]) = a.at(r, c);
    }
  return out;
}

// affine=: the 4x4 (or 3x4) map from lattice coordinates to world, as nibabel's img.affine. A
// diagonal one gives the spacings and origin; a negative step reverses that axis of the
// Cartesian samples (as the NIfTI reader does), keeping every value's world position. An oblique
// (or axis-permuting) one, Cartesian only, is kept as the NIfTI reader keeps a tilted file's:
// the voxel grid in its own frame and `frame` (rt::split_oblique).
void from_affine(const py::handle& affine, const rt::CosetLattice& lattice, const rt::Sizes& sizes,
                 std::vector<double>& storage, rt::Vec3& steps, rt::Vec3& origin,
                 std::optional<rt::Affine>& frame) {
  const rt::Affine a = affine_arg(affine);
  for (std::size_t r = 0; r < 3; ++r)
    for (std::size_t c = 0; c < 3; ++c) {
      if (c == r || a.linear[r][c] == 0) continue;
      if (lattice != rt::CosetLattice::cartesian())
        throw py::value_error(fmt::format(
            "affine[{}, {}] = {}: the affine is oblique (or permutes the axes), which only a "
            "Cartesian volume can be, not a {} lattice's",
            r, c, a.linear[r][c], lattice.name()));
      rt::Affine to_world;
      if (const std::string why = rt::split_oblique(a, steps, to_world); !why.empty())
        throw py::value_error("affine " + why);
      origin = {0, 0, 0};
      frame = to_world;
      return;
    }
  for (std::size_t r = 0; r < 3; ++r) {
    steps[r] = a.linear[r][r];
    origin[r] = a.translation[r];
  }
  const bool reversed = steps[0] < 0 || steps[1] < 0 || steps[2] < 0;
  if (reversed && lattice.coset_count() != 1)
    throw py::value_error(fmt::format(
        "affine has a negative step: only a Cartesian volume's axes can be reversed, not a {} "
        "lattice's",
        lattice.name()));
  if (reversed) rt::orient_axes_positive(std::span<double>(storage), sizes, steps, origin);
}

VolumePtr make_volume(const py::handle& samples, const std::string& lattice_text,
                      const py::handle& spacing, const py::handle& origin,
                      const std::optional<std::vector<std::array<int, 3>>>& offsets,
                      const py::handle& affine) {
  const rt::CosetLattice lattice = lattice_of(lattice_text, offsets);
  std::vector<double> storage = storage_of(samples, lattice);
  const py::array a = py::module_::import("numpy").attr("asarray")(samples);  // no copy of an array
  const rt::Sizes sizes{static_cast<int>(a.shape(1)), static_cast<int>(a.shape(2)),
                        static_cast<int>(a.shape(3))};
  rt::Vec3 steps{}, corner{};
  std::optional<rt::Affine> frame;
  if (affine.is_none()) {
    steps = spacing_of(spacing);
    corner = three(origin, "origin");
  } else {
    if (!spacing.is_none() || !origin.is_none())
      throw py::value_error("give affine= or spacing= and origin=, not both");
    from_affine(affine, lattice, sizes, storage, steps, corner, frame);
  }
  return std::make_shared<Volume>(Samples(lattice, sizes, steps, corner, std::move(storage)),
                                  frame);
}

// Volume(anatomical=): None, or the letters of a patient's frame boxrecon writes.
std::string anatomical_arg(const std::optional<std::string>& letters) {
  if (!letters) return {};
  if (*letters != "RAS" && *letters != "LAS" && *letters != "LPS")
    throw py::value_error(fmt::format("anatomical must be 'RAS', 'LAS', 'LPS' or None, got '{}'",
                                      rt::nrrd_checks::printable(*letters, 16)));
  return *letters;
}

// Volume(nifti_codes=): None, or (qform_code, sform_code) as NIfTI numbers them (0..5; nibabel's
// header['qform_code'], header['sform_code']).
rt::NiftiCodes nifti_codes_arg(const std::optional<std::array<int, 2>>& codes) {
  if (!codes) return {};
  const auto [q, s] = *codes;
  if (q < 0 || q > 5 || s < 0 || s > 5)
    throw py::value_error(fmt::format(
        "nifti_codes must be (qform_code, sform_code), each 0..5 as NIfTI numbers them, got ({}, "
        "{})",
        q, s));
  return {q, s};
}

py::tuple nifti_codes_tuple(const rt::NiftiCodes& c) { return py::make_tuple(c.qform, c.sform); }

py::tuple spacings_of(const Volume& v) {
  const rt::Vec3& h = v.axis_spacing();
  return py::make_tuple(h[0], h[1], h[2]);
}

// An affine as a 4x4 NumPy array (last row 0 0 0 1).
py::array_t<double> affine_array(const rt::Affine& a) {
  py::array_t<double> out({4, 4});
  for (int r = 0; r < 4; ++r)
    for (int c = 0; c < 4; ++c) {
      const auto ru = static_cast<std::size_t>(r), cu = static_cast<std::size_t>(c);
      out.mutable_at(r, c) =
          r == 3 ? (c == 3 ? 1.0 : 0.0) : (c < 3 ? a.linear[ru][cu] : a.translation[ru]);
    }
  return out;
}

// The map from lattice coordinates to world: diag(spacings) and the origin, after an oblique
// volume's frame (for a Cartesian volume the voxel-to-world affine of nibabel and NIfTI's sform).
rt::Affine affine_of(const Volume& v) {
  const rt::Affine own = rt::Affine::diagonal(v.axis_spacing(), v.origin());
  return v.frame ? v.frame->after(own) : own;
}

bool isotropic(const Volume& v) {
  const rt::Vec3& h = v.axis_spacing();
  return h[0] == h[1] && h[1] == h[2];
}

// The world position of every sample, (K N0 N1 N2, 3) in storage order (the positions
// sample_lattice evaluates a function at).
py::array_t<double> positions(const Volume& v) {
  std::vector<double> out;
  out.reserve(v.sample_count() * 3);
  const rt::Sizes& n = v.sizes();
  for (int z = 0; z < n[2]; ++z)
    for (int y = 0; y < n[1]; ++y)
      for (int x = 0; x < n[0]; ++x)
        for (int c = 0; c < v.coset_count(); ++c)
          for (double p : v.frame ? v.frame->apply(v.sample_position(c, x, y, z))
                                  : v.sample_position(c, x, y, z))
            out.push_back(p);
  return adopt(std::move(out), {static_cast<py::ssize_t>(v.sample_count()), 3}, false);
}

// A Python callable sampled once at every sample position (storage order), vectorised.
VolumePtr sample_callable(const py::function& f, const rt::LatticeGrid& grid) {
  auto volume = std::make_shared<Volume>(Samples(grid.lattice, grid.sizes, grid.h, grid.origin));
  const auto m = static_cast<py::ssize_t>(volume->sample_count());
  const py::array_t<double> values = real_array(f(positions(*volume)), "the function's result");
  if (values.ndim() != 1 || values.shape(0) != m)
    throw py::value_error(fmt::format(
        "the function returned shape {} for {} points: it must return one value per point, "
        "shape ({},)",
        shape_text(values), m, m));
  const double* v = values.data();
  auto out = volume->samples();
  for (py::ssize_t i = 0; i < m; ++i) {
    if (!std::isfinite(v[i]))
      throw py::value_error(
          fmt::format("the function's value {} at sample {} is not finite", v[i], i));
    out[static_cast<std::size_t>(i)] = v[i];
  }
  return volume;
}

// Work released from the GIL runs in blocks of about this many points; between blocks the GIL
// is taken back for Python's signal handlers, so Ctrl-C interrupts a long call within a block's
// time.
constexpr std::size_t kPointsBetweenSignalChecks = std::size_t{1} << 16;

// Called with the GIL released: runs Python's pending signal handlers; true when one raised
// (KeyboardInterrupt), whose error stays set for the caller to throw once it holds the GIL.
bool signal_pending() {
  const py::gil_scoped_acquire acquire;
  return PyErr_CheckSignals() != 0;
}

// A registry filter, or any SPEC through the loader (compiled and cached on first use, exactly
// as boxrecon --filter SPEC --lattice L gets it), with the generator's properties of its SPEC.
// With `volume` (and no lattice) a direction list is on the volume's lattice, as boxrecon's
// --filter SPEC --volume FILE (frontend::lattice_for_volume).
Filter make_filter(const std::string& spec_text, const std::optional<std::string>& lattice,
                   const Volume* volume) {
  const std::string lattice_text =
      volume ? frontend::lattice_for_volume(spec_text, lattice.value_or(""), volume->lattice(),
                                            "the volume", "lattice")
             : lattice.value_or("");
  std::optional<rt::SplineFilter> filter;
  {
    py::gil_scoped_release release;  // a first use derives and compiles: seconds
    filter = frontend::filter_from(spec_text, lattice_text);
  }
  gen::BoxSplineSpec spec = gen::parse_spec(spec_text, lattice_text);
  gen::BoxSplineProperties properties = gen::box_spline_properties(spec);
  return {*filter, spec_text, lattice_text, std::move(spec), std::move(properties)};
}

py::object evaluate(const Filter& f, const Volume& volume, const py::handle& points_obj,
                    const std::optional<std::string>& prefilter, bool gradient, bool hessian,
                    const std::optional<std::string>& boundary) {
  const Prefiltering q = prefiltering(prefilter, boundary);
  const py::array_t<double> points = points_array(points_obj);
  const auto n = static_cast<std::size_t>(points.shape(0));
  const auto count = static_cast<py::ssize_t>(n);
  py::array_t<double> values(count);
  const bool derivatives = gradient || hessian;
  py::array_t<double> gradients(std::vector<py::ssize_t>{derivatives ? count : 0, 3});
  py::array_t<double> hessians(std::vector<py::ssize_t>{hessian ? count : 0, 6});
  const std::span<const rt::Vec3> p(reinterpret_cast<const rt::Vec3*>(points.data()), n);
  // An oblique volume: world points in its frame, derivatives back in world.
  const std::optional<rt::Affine> to_volume = rt::grid_to_volume(volume.frame, std::nullopt);
  std::vector<rt::Vec3> in_frame;
  const std::span<double> v(values.mutable_data(), n);
  const std::span<rt::Vec3> g(reinterpret_cast<rt::Vec3*>(gradients.mutable_data()),
                              derivatives ? n : 0);
  const std::span<rt::Hessian> h(reinterpret_cast<rt::Hessian*>(hessians.mutable_data()),
                                 hessian ? n : 0);
  {
    py::gil_scoped_release release;
    std::optional<Samples> storage;
    const rt::Reconstructor<double> spline(prepared(volume, f, q, storage), f.filter);
    // In blocks, so that Ctrl-C is seen between them.
    for (std::size_t first = 0; first < n; first += kPointsBetweenSignalChecks) {
      const std::size_t m = std::min(kPointsBetweenSignalChecks, n - first);
      const auto gs = derivatives ? g.subspan(first, m) : g;
      const auto hs = hessian ? h.subspan(first, m) : h;
      const std::span<const rt::Vec3> world = p.subspan(first, m);
      if (to_volume) {
        in_frame.resize(m);
        for (std::size_t i = 0; i < m; ++i) in_frame[i] = to_volume->apply(world[i]);
      }
      spline.evaluate(to_volume ? std::span<const rt::Vec3>(in_frame) : world, v.subspan(first, m),
                      gs, hs);
      spline.require_finite(world, v.subspan(first, m), gs, hs);
      if (to_volume) rt::derivatives_to_world(*to_volume, gs, hs);
      if (first + m < n && signal_pending()) break;
    }
  }
  if (PyErr_Occurred() != nullptr) throw py::error_already_set();
  if (hessian) return py::make_tuple(values, gradients, hessians);
  if (gradient) return py::make_tuple(values, gradients);
  return values;
}

rt::Sizes shape_of(const std::variant<int, std::array<int, 3>>& shape) {
  if (const auto* n = std::get_if<int>(&shape)) return {*n, *n, *n};
  const auto& s = std::get<std::array<int, 3>>(shape);
  return {s[0], s[1], s[2]};
}

// Where the output grid lies: lo..hi, or its voxel-to-world affine, or an image's grid.
struct GridArgs {
  py::handle lo, hi, affine, like;
  std::optional<std::variant<int, std::array<int, 3>>> shape;
};

// The grid of an image file (NIfTI or NRRD, oblique included): its sizes and its voxel-to-world
// affine (its frame after diag(spacings) and its origin), as nibabel's img.affine. Its samples are
// read for the geometry only (non-finite ones do not matter).
struct ImageGrid {
  rt::Sizes sizes;
  rt::Affine affine;
};
ImageGrid image_grid(const std::string& path) {
  rt::NrrdReadLimits limits;
  limits.allow_non_finite = true;
  limits.allow_oblique = true;
  rt::SourceSamples source;
  const Samples image = [&] {
    py::gil_scoped_release release;
    return rt::read_volume_file<double>(path, limits, &source);
  }();
  if (image.coset_count() != 1)
    throw py::value_error(fmt::format(
        "like '{}' is a {} volume: its grid is the output's with lattice='{}' (a Volume back)",
        rt::nrrd_checks::printable(path), image.lattice().name(), image.lattice().name()));
  const rt::Affine own = rt::Affine::diagonal(image.axis_spacing(), image.origin());
  return {image.sizes(), source.frame ? source.frame->after(own) : own};
}

// The grid of lo..hi with `shape` points (default 64 per axis), lo and hi defaulting to the
// filter's default_box; or `shape` points whose world positions are affine (i, j, k, 1), oblique
// or not; or the grid and affine of the image file `like` (NIfTI or NRRD, oblique included).
// World points map into an oblique volume's frame (`frame`; CartesianGrid::to_volume); its
// default box lies in that frame, so such a volume needs the grid given.
rt::CartesianGrid grid_of(const Samples& volume, const std::optional<rt::Affine>& frame,
                          const Filter& f, const GridArgs& g) {
  if (g.lo.is_none() != g.hi.is_none()) throw py::value_error("give both lo and hi, or neither");
  const int given = static_cast<int>(!g.lo.is_none()) + static_cast<int>(!g.affine.is_none()) +
                    static_cast<int>(!g.like.is_none());
  if (given > 1) throw py::value_error("give one of lo and hi, affine or like");
  const rt::Sizes shape = shape_of(g.shape.value_or(64));
  if (!g.like.is_none()) {
    if (g.shape) throw py::value_error("like gives the grid's shape: give like or shape, not both");
    const ImageGrid image = image_grid(py::str(g.like));
    rt::CartesianGrid grid = rt::grid_over({{0, 0, 0}, {1, 1, 1}}, image.sizes);  // checks them
    grid.spacing = {1, 1, 1};
    grid.origin = {0, 0, 0};
    grid.to_volume = rt::grid_to_volume(frame, image.affine);  // as affine= with it: one path
    return grid;
  }
  if (!g.affine.is_none()) {
    rt::CartesianGrid grid = rt::grid_over({{0, 0, 0}, {1, 1, 1}}, shape);  // checks the shape
    grid.spacing = {1, 1, 1};
    grid.origin = {0, 0, 0};
    grid.to_volume = rt::grid_to_volume(frame, affine_arg(g.affine));
    return grid;
  }
  if (g.lo.is_none() && frame)
    throw py::value_error(
        "the volume is oblique: give the output grid (lo and hi in world coordinates, affine= or "
        "like=); its default box lies in its own frame (Filter.default_box, Volume.frame)");
  const rt::Box box = g.lo.is_none() ? rt::default_box(volume, f.filter)
                                     : rt::Box{three(g.lo, "lo"), three(g.hi, "hi")};
  rt::CartesianGrid grid = rt::grid_over(box, shape);
  grid.to_volume = rt::grid_to_volume(frame, std::nullopt);
  return grid;
}

py::array_t<double> resample(const VolumePtr& volume, const Filter& f,
                             const std::optional<std::string>& prefilter, const GridArgs& where,
                             const std::optional<std::array<std::array<int, 3>, 2>>& block,
                             const std::optional<std::string>& boundary) {
  const Prefiltering q = prefiltering(prefilter, boundary);
  std::optional<Samples> storage;
  const Samples* v = nullptr;
  {
    py::gil_scoped_release release;
    v = &prepared(*volume, f, q, storage);
  }
  const rt::CartesianGrid grid = grid_of(*v, volume->frame, f, where);
  const rt::GridBlock b =
      block ? rt::GridBlock{(*block)[0], (*block)[1]} : rt::GridBlock{{0, 0, 0}, grid.sizes};
  rt::CartesianVolume<double> out;
  {
    py::gil_scoped_release release;
    // By slabs of z (contiguous in the output, x fastest), so that Ctrl-C is seen between
    // them; each value is the whole block's, bit for bit (GridBlock).
    const int plane = std::max(1, (b.end[0] - b.begin[0]) * (b.end[1] - b.begin[1]));
    const int slab = std::max(1, static_cast<int>(kPointsBetweenSignalChecks) / plane);
    if (b.end[2] <= b.begin[2]) out = rt::resample(*v, f.filter, grid, b);  // its refusal
    for (int z = b.begin[2]; z < b.end[2]; z += slab) {
      const rt::GridBlock part{{b.begin[0], b.begin[1], z},
                               {b.end[0], b.end[1], std::min(b.end[2], z + slab)}};
      rt::CartesianVolume<double> piece = rt::resample(*v, f.filter, grid, part);
      if (z == b.begin[2]) {
        out = std::move(piece);
        out.sizes[2] = b.end[2] - b.begin[2];
        out.values.reserve(static_cast<std::size_t>(plane) *
                           static_cast<std::size_t>(out.sizes[2]));
      } else {
        out.values.insert(out.values.end(), piece.values.begin(), piece.values.end());
      }
      if (part.end[2] < b.end[2] && signal_pending()) break;
    }
  }
  if (PyErr_Occurred() != nullptr) throw py::error_already_set();
  return grid_array(std::move(out));
}

// resample(lattice=L) onto a non-Cartesian lattice, as `boxrecon resample --lattice L`: the grid
// of like= (a volume file of that lattice), or of L at spacing= h or at about shape^3 samples
// (shape one integer, default 64) over lo..hi (default: the filter's default_box), centred in it.
// A Volume, holding what the CLI writes as NRRD.
VolumePtr resample_onto_lattice(const VolumePtr& volume, const Filter& f,
                                const std::optional<std::string>& prefilter,
                                const std::optional<std::string>& boundary,
                                const rt::CosetLattice& lattice, const GridArgs& g,
                                const py::handle& spacing) {
  const std::string& name = lattice.name();
  if (volume->frame)
    throw py::value_error(fmt::format(
        "the volume is oblique: it resamples onto Cartesian grids only (a {} volume is stored "
        "axis-aligned in the world); resample it onto an axis-aligned grid first (lo and hi)",
        name));
  if (!g.affine.is_none())
    throw py::value_error(fmt::format(
        "affine= gives a Cartesian grid: onto the {} lattice give lo and hi with spacing or "
        "shape, or like=",
        name));
  if (g.lo.is_none() != g.hi.is_none()) throw py::value_error("give both lo and hi, or neither");
  if (g.shape && std::holds_alternative<std::array<int, 3>>(*g.shape))
    throw py::value_error(fmt::format(
        "shape=(nx, ny, nz) counts Cartesian grid points: onto the {} lattice give spacing= (its "
        "h) or shape=N (about N^3 samples)",
        name));
  if (g.shape && !spacing.is_none()) throw py::value_error("give spacing or shape, not both");
  std::optional<rt::LatticeGrid> grid;
  if (!g.like.is_none()) {
    if (!g.lo.is_none() || g.shape || !spacing.is_none())
      throw py::value_error("like gives the grid: give like, or lo, hi, shape and spacing");
    const std::string path = py::str(g.like);
    rt::NrrdReadLimits limits;
    limits.allow_non_finite = true;
    limits.allow_oblique = true;
    const Samples image = [&] {
      py::gil_scoped_release release;
      return rt::read_volume_file<double>(path, limits);
    }();
    if (!(image.lattice() == lattice))
      throw py::value_error(
          fmt::format("lattice {} differs from the lattice of like '{}' ({}): give one of them",
                      name, rt::nrrd_checks::printable(path, 80), image.lattice().name()));
    grid = rt::LatticeGrid{lattice, image.sizes(), image.axis_spacing()[0], image.origin()};
  }
  const Prefiltering q = prefiltering(prefilter, boundary);
  std::optional<Samples> storage;
  const Samples* v = nullptr;
  {
    py::gil_scoped_release release;
    v = &prepared(*volume, f, q, storage);
  }
  if (!grid) {
    const rt::Box box = g.lo.is_none() ? rt::default_box(*v, f.filter)
                                       : rt::Box{three(g.lo, "lo"), three(g.hi, "hi")};
    const int count = g.shape ? std::get<int>(*g.shape) : 64;
    if (count < 2 || count > rt::kMaxGridSize)
      throw py::value_error(
          fmt::format("shape must be between 2 and {}, got {}", rt::kMaxGridSize, count));
    std::optional<double> h;
    if (!spacing.is_none()) {
      const py::array_t<double> a = real_array(spacing, "spacing");
      if (a.ndim() != 0)
        throw py::value_error(
            fmt::format("the {} lattice has one spacing h: give one number, got shape {}", name,
                        shape_text(a)));
      h = *a.data();
    }
    grid = rt::lattice_grid_for(lattice, box, h, count);  // checks h, the box and the count
  }
  const rt::Sizes& n = grid->sizes;
  frontend::check_memory(static_cast<std::uint64_t>(lattice.coset_count()) *
                             static_cast<std::uint64_t>(n[0]) * static_cast<std::uint64_t>(n[1]) *
                             static_cast<std::uint64_t>(n[2]),
                         sizeof(double),
                         fmt::format("the output grid of {} x {} x {} x {} {} samples",
                                     lattice.coset_count(), n[0], n[1], n[2], name),
                         "values");
  py::gil_scoped_release release;
  return std::make_shared<Volume>(rt::resample_to_lattice(*v, f.filter, *grid), std::nullopt,
                                  volume->anatomical, volume->nifti_codes);
}

py::tuple box_tuple(const rt::Box& b) {
  return py::make_tuple(py::make_tuple(b.min[0], b.min[1], b.min[2]),
                        py::make_tuple(b.max[0], b.max[1], b.max[2]));
}

py::int_ big_int(const gen::Integer& x) {
  return py::int_(py::str(gen::to_string(gen::Rational(x))));
}

void bind_volume(py::module_& m) {
  py::class_<Volume, VolumePtr>(m, "Volume",
                                "Samples on a lattice (docs/python.md): `samples` is a (K, N0, "
                                "N1, N2) view of the storage, sample (c, i, j, k) at origin + "
                                "spacing * (d (i, j, k) + offset_c); spacing one number or three "
                                "(Cartesian), or an `affine` instead (oblique: Cartesian only).")
      .def(py::init([](const py::handle& samples, const std::string& lattice,
                       const py::handle& spacing, const py::handle& origin,
                       const std::optional<std::vector<std::array<int, 3>>>& offsets,
                       const py::handle& affine, const std::optional<std::string>& anatomical,
                       const std::optional<std::array<int, 2>>& nifti_codes) {
             VolumePtr v =
                 affine.is_none()
                     ? make_volume(samples, lattice, spacing.is_none() ? py::float_(1.0) : spacing,
                                   origin.is_none() ? py::make_tuple(0, 0, 0) : origin, offsets,
                                   affine)
                     : make_volume(samples, lattice, spacing, origin, offsets, affine);
             v->anatomical = anatomical_arg(anatomical);
             v->nifti_codes = nifti_codes_arg(nifti_codes);
             return v;
           }),
           py::arg("samples"), py::arg("lattice") = "bcc", py::arg("spacing") = py::none(),
           py::arg("origin") = py::none(), py::arg("coset_offsets") = py::none(),
           py::arg("affine") = py::none(), py::arg("anatomical") = py::none(),
           py::arg("nifti_codes") = py::none())
      .def_property_readonly(
          "samples",
          [](const py::object& self) {
            auto& v = self.cast<Volume&>();
            const auto k = static_cast<py::ssize_t>(v.coset_count());
            const rt::Sizes& n = v.sizes();
            const py::ssize_t s = sizeof(double);
            return py::array_t<double>({k, py::ssize_t{n[0]}, py::ssize_t{n[1]}, py::ssize_t{n[2]}},
                                       {s, s * k, s * k * n[0], s * k * n[0] * n[1]},
                                       v.samples().data(), self);
          },
          "The samples as a writable NumPy array (K, N0, N1, N2) without a copy")
      .def_property_readonly("lattice", [](const Volume& v) { return v.lattice().name(); })
      .def_property_readonly("lattice_rows",
                             [](const Volume& v) { return v.lattice().rows_text(); })
      .def_property_readonly("coset_offsets",
                             [](const Volume& v) { return offsets_of(v.lattice()); })
      .def_property_readonly("period", [](const Volume& v) { return v.period(); })
      .def_property_readonly(
          "spacing",
          [](const Volume& v) {
            if (!isotropic(v))
              throw py::value_error(
                  fmt::format("the volume is anisotropic (spacings {}, {}, {}): it has no "
                              "one spacing; use spacings",
                              v.axis_spacing()[0], v.axis_spacing()[1], v.axis_spacing()[2]));
            return v.spacing();
          })
      .def_property_readonly("spacings", &spacings_of, "The spacing along x, y and z")
      .def_property_readonly(
          "affine", [](const Volume& v) { return affine_array(affine_of(v)); },
          "4 x 4: lattice coordinates to world (diag(spacings), origin, after an oblique volume's "
          "frame); for a Cartesian volume the voxel-to-world affine, as nibabel's")
      .def_property_readonly(
          "frame",
          [](const Volume& v) {
            return v.frame ? py::object(affine_array(*v.frame)) : py::object(py::none());
          },
          "None for an axis-aligned volume; for an oblique one the 4 x 4 map from its own frame "
          "(where its samples lie on the axes: positions origin + spacings * (i, j, k), and "
          "default_box and evaluable_region lie) to world")
      .def_property_readonly(
          "anatomical",
          [](const Volume& v) {
            return v.anatomical.empty() ? py::object(py::none()) : py::object(py::str(v.anatomical));
          },
          "The patient's frame of the world: 'RAS' (+x right, +y anterior, +z superior: NIfTI, "
          "a NRRD in right-anterior-superior), 'LAS', 'LPS' (DICOM's, a NRRD in "
          "left-posterior-superior), or None for a world tied to no patient")
      .def_property_readonly(
          "nifti_codes", [](const Volume& v) { return nifti_codes_tuple(v.nifti_codes); },
          "(qform_code, sform_code) of the NIfTI file the volume was read from (1 scanner, 2 "
          "aligned, 3 Talairach, 4 MNI, 5 template; (0, 0) otherwise), claimed again by a NIfTI "
          "write_volume")
      .def_property_readonly("origin",
                             [](const Volume& v) {
                               const rt::Vec3 o = affine_of(v).translation;
                               return py::make_tuple(o[0], o[1], o[2]);
                             })
      .def_property_readonly("sizes", [](const Volume& v) { return v.sizes(); })
      .def("positions", &positions,
           "World positions of the samples, (K N0 N1 N2, 3) in storage order (coset fastest)")
      .def("__repr__",
           [](const Volume& v) {
             const rt::Vec3& h = v.axis_spacing();
             const std::string spacing =
                 isotropic(v) ? fmt::format("spacing {}", h[0])
                              : fmt::format("spacings ({}, {}, {})", h[0], h[1], h[2]);
             const rt::Vec3 o = affine_of(v).translation;
             return fmt::format(
                 "boxgen.Volume({} lattice, {} x {} x {} x {} samples, {}, origin ({}, {}, "
                 "{}){})",
                 v.lattice().name(), v.coset_count(), v.sizes()[0], v.sizes()[1], v.sizes()[2],
                 spacing, o[0], o[1], o[2], v.frame ? ", oblique (see affine)" : "");
           })
      .def(py::pickle(
          [](const py::object& self) {
            const auto& v = self.cast<const Volume&>();
            const std::string lattice =
                v.lattice().name() == "custom" ? v.lattice().rows_text() : v.lattice().name();
            const rt::Vec3& o = v.origin();  // in its own frame: the frame travels apart
            return py::make_tuple(self.attr("samples").attr("copy")(), lattice, spacings_of(v),
                                  py::make_tuple(o[0], o[1], o[2]), offsets_of(v.lattice()),
                                  self.attr("frame"), v.anatomical,
                                  nifti_codes_tuple(v.nifti_codes));
          },
          [](const py::tuple& t) {
            VolumePtr v = make_volume(t[0], t[1].cast<std::string>(), t[2], t[3],
                                      t[4].cast<std::vector<std::array<int, 3>>>(), py::none());
            if (t.size() > 5 && !t[5].is_none()) v->frame = affine_arg(t[5]);
            if (t.size() > 6) v->anatomical = t[6].cast<std::string>();
            if (t.size() > 7) v->nifti_codes = nifti_codes_arg(t[7].cast<std::array<int, 2>>());
            return v;
          }));

  m.def(
      "read_volume",
      [](const std::string& path, bool allow_nonfinite, const std::optional<std::string>& lattice) {
        rt::NrrdReadLimits limits;
        limits.allow_non_finite = allow_nonfinite;
        limits.allow_oblique = true;  // kept as boxrecon keeps it: Volume.frame
        if (lattice) limits.lattice = rt::CosetLattice::parse(*lattice);
        std::shared_ptr<Volume> v;
        {
          py::gil_scoped_release release;
          rt::SourceSamples source;
          v = std::make_shared<Volume>(rt::read_volume_file<double>(path, limits, &source),
                                       source.frame, source.anatomical, source.nifti_codes);
        }
        // The lattice asked for is what the caller gets, or an error: the
        // same points (the file's coset offsets may differ in order or representative).
        const rt::CosetLattice& got = v->lattice();
        const bool same_points =
            !limits.lattice ||
            (got.determinant() == limits.lattice->determinant() &&
             std::all_of(got.offsets().begin(), got.offsets().end(), [&](const auto& o) {
               return limits.lattice->contains(o[0], o[1], o[2]);
             }));
        if (!same_points)
          throw py::value_error(fmt::format("'{}' holds a {} volume, not the {} lattice asked for",
                                            rt::nrrd_checks::printable(path), got.label(),
                                            limits.lattice->label()));
        return v;
      },
      py::arg("path"), py::arg("allow_nonfinite") = false, py::arg("lattice") = py::none(),
      "A volume file as a Volume of doubles: a lattice NRRD (docs/runtime.md#nrrd-layout) or a "
      "NIfTI-1/2 image (.nii, .nii.gz, a .hdr/.img pair; an oblique one keeps its affine: "
      "Volume.frame), with every check of boxrecon's readers; "
      "`lattice`: the one the caller needs (a NRRD that does not say its lattice is then refused "
      "in its terms)");
  m.def(
      "write_volume",
      [](const std::string& path, const Volume& v, const std::optional<std::string>& type) {
        const std::optional<rt::SampleType> t =
            type ? std::optional(rt::parse_sample_type(*type)) : std::nullopt;
        rt::VolumeWrite written;
        {
          py::gil_scoped_release release;
          // An oblique volume's frame is composed into the file's affine.
          written = rt::write_volume_file(path, static_cast<const Samples&>(v), t, v.anatomical,
                                          v.frame, v.nifti_codes);
        }
        if (written.clamped > 0 &&
            PyErr_WarnEx(PyExc_RuntimeWarning,
                         fmt::format("{} value(s) beyond the range of {} were clamped to it",
                                     written.clamped, rt::sample_type_name(written.type))
                             .c_str(),
                         1) < 0)
          throw py::error_already_set();  // warnings as errors
      },
      py::arg("path"), py::arg("volume"), py::arg("type") = py::none(),
      "Writes the volume in the format of its name, atomically: NRRD (.nrrd, any lattice) or "
      "NIfTI-1 (.nii, .nii.gz, Cartesian only); `type`: the sample type (int8 ... float64; "
      "default the NRRD's float64, NIfTI's float32); integers rounded, values beyond the range "
      "clamped (a RuntimeWarning says how many)");
  m.def(
      "sample",
      [](const py::object& function, int n, const std::optional<std::string>& lattice,
         const std::optional<std::string>& filter, std::optional<double> h) {
        const rt::LatticeGrid grid =
            frontend::sample_grid(n, h, lattice.value_or(""), filter.value_or(""), sizeof(double));
        if (py::isinstance<py::str>(function)) {
          const rt::TestFunction& fn = rt::find_test_function(function.cast<std::string>());
          py::gil_scoped_release release;
          return std::make_shared<Volume>(rt::sample_lattice<double>(fn.value, grid));
        }
        if (!py::isinstance<py::function>(function))
          throw py::type_error(
              fmt::format("function must be a name ({}) or a callable on an (m, 3) array of points",
                          rt::test_function_names()));
        return sample_callable(function.cast<py::function>(), grid);
      },
      py::arg("function"), py::arg("n"), py::arg("lattice") = py::none(),
      py::arg("filter") = py::none(), py::arg("h") = py::none(),
      "`boxrecon sample`: a test function (ml, cubic, sphere, gaussian) or a Python callable "
      "(called once with every sample position, an (m, 3) array, returning m values) on N^3 x K "
      "lattice points over [-1,1]^3 with boxrecon's margin");
}

void bind_filter(py::module_& m) {
  py::class_<Filter>(m, "Filter", "A box-spline filter with its evaluator (docs/python.md)")
      .def(py::init(&make_filter), py::arg("spec"), py::arg("lattice") = py::none(),
           py::arg("volume") = py::none())
      .def_property_readonly("name", [](const Filter& f) { return f.filter.name(); })
      .def_property_readonly("spec", [](const Filter& f) { return f.spec.directions_text(); })
      .def_property_readonly("lattice", [](const Filter& f) { return f.filter.lattice().name(); })
      .def_property_readonly("lattice_rows",
                             [](const Filter& f) { return f.filter.lattice().rows_text(); })
      .def_property_readonly("dimension", [](const Filter& f) { return f.spec.dimension(); })
      .def_property_readonly("directions", [](const Filter& f) { return f.spec.count(); })
      .def_property_readonly("degree", [](const Filter& f) { return f.properties.degree; })
      .def_property_readonly("approximation_order",
                             [](const Filter& f) { return f.filter.approximation_order(); })
      .def_property_readonly(
          "continuity", [](const Filter& f) { return f.properties.continuity; }, "k of C^k")
      .def_property_readonly("support_volume",
                             [](const Filter& f) { return big_int(f.properties.support_volume); })
      .def_property_readonly("stencil_size",
                             [](const Filter& f) { return big_int(f.properties.stencil_size); })
      .def_property_readonly("linearly_independent",
                             [](const Filter& f) { return f.properties.linearly_independent; })
      .def_property_readonly("reach",
                             [](const Filter& f) {
                               const rt::StencilReach r = f.filter.reach();
                               py::dict d;
                               d["lo"] = r.lo;
                               d["hi"] = r.hi;
                               d["centre"] = r.centre;
                               return d;
                             })
      .def_property_readonly(
          "prefilters",
          [](const Filter& f) {
            py::dict out;
            for (const auto& [name, q] : {std::pair{"q1", rt::PrefilterChoice::Q1},
                                          std::pair{"q2", rt::PrefilterChoice::Q2},
                                          std::pair{"q1opt", rt::PrefilterChoice::Q1Opt},
                                          std::pair{"q2opt", rt::PrefilterChoice::Q2Opt}}) {
              out[name] = taps_arrays(f.filter.prefilter(q));
            }
            return out;
          },
          "{'q1': (offsets (m, 3), weights (m,)), 'q2': ..., 'q1opt': ..., 'q2opt': ...}: the "
          "generated quasi-interpolation prefilters")
      .def(
          "required_margin",
          [](const Filter& f, const std::optional<std::string>& q) {
            return f.filter.required_margin(prefilter_choice(q));
          },
          py::arg("prefilter") = py::none())
      .def("evaluate", &evaluate, py::arg("volume"), py::arg("points"),
           py::arg("prefilter") = py::none(), py::arg("gradient") = false,
           py::arg("hessian") = false, py::arg("boundary") = py::none(),
           "The spline at (n, 3) world points: values (n,), or (values, gradients (n, 3)[, "
           "Hessians (n, 6) xx xy xz yy yz zz]); bit for bit `boxrecon eval`. prefilter: none "
           "(default) | q1 | q2 | q1opt | q2opt | qfir:K | interp | interp:LAMBDA; boundary: "
           "mirror (default) | clamp | "
           "strict")
      .def(
          "prefilter_volume",
          [](const Filter& f, const Volume& volume, const std::string& q,
             const std::optional<std::string>& boundary) {
            std::optional<Samples> storage;
            py::gil_scoped_release release;
            (void)prepared(volume, f, prefiltering(q, boundary), storage);
            if (!storage) return std::make_shared<Volume>(volume);  // none, strict: a copy
            return std::make_shared<Volume>(std::move(*storage), volume.frame, volume.anatomical,
                                            volume.nifti_codes);
          },
          py::arg("volume"), py::arg("prefilter"), py::arg("boundary") = py::none(),
          "The coefficients after prefilter (none | q1 | q2 | q1opt | q2opt | qfir:K | "
          "interp[:LAMBDA]) and boundary (mirror (default) | clamp | strict): a new Volume, "
          "evaluated with prefilter none and boundary strict")
      .def(
          "interpolation",
          [](const Filter& f, const Volume& volume, const std::string& q,
             const std::optional<std::string>& boundary) {
            const Prefiltering p = prefiltering(q, boundary);
            if (p.q.is_fir())
              throw py::value_error(fmt::format("prefilter {} is not interp", p.q.text()));
            rt::InterpolationReport r;
            {
              std::optional<Samples> storage;
              py::gil_scoped_release release;
              (void)prepared(volume, f, p, storage, &r);
            }
            py::dict d;
            d["lambda"] = r.lambda;
            d["residual_max"] = r.residual_max;
            d["residual_rms"] = r.residual_rms;
            d["symbol_min"] = r.symbol.min;
            d["symbol_max"] = r.symbol.max;
            d["padding"] = r.padding;
            d["transform"] = r.transform;
            return d;
          },
          py::arg("volume"), py::arg("prefilter") = "interp", py::arg("boundary") = py::none(),
          "interp's report on this volume: lambda (0: exact), the residual at the samples (max "
          "and RMS, of max |sample|), min and max |A| of the symbol, the padding and transform "
          "size per axis")
      .def(
          "lattice_values",
          [](const Filter& f) { return taps_arrays(rt::lattice_values(f.filter)); },
          "(offsets (m, 3), values (m,)): the filter M at the lattice points where it is not "
          "zero, from its evaluator in double")
      .def("evaluable_region",
           [](const Filter& f, const Volume& v) {
             return box_tuple(rt::evaluable_region(v, f.filter));
           })
      .def("default_box",
           [](const Filter& f, const Volume& v) { return box_tuple(rt::default_box(v, f.filter)); })
      .def("__repr__",
           [](const Filter& f) {
             return fmt::format("boxgen.Filter('{}' on the {} lattice: degree {}, C^{}, order {})",
                                f.filter.name(), f.filter.lattice().name(), f.properties.degree,
                                f.properties.continuity, f.filter.approximation_order());
           })
      .def(py::pickle(
          [](const Filter& f) {
            return py::make_tuple(f.spec_text, f.lattice_text.empty()
                                                   ? py::object(py::none())
                                                   : py::object(py::str(f.lattice_text)));
          },
          [](const py::tuple& t) {
            return make_filter(t[0].cast<std::string>(), t[1].cast<std::optional<std::string>>(),
                               nullptr);
          }));
}

}  // namespace

void bind_runtime(py::module_& m) {
  bind_volume(m);
  bind_filter(m);
  m.def(
      "resample",
      [](const VolumePtr& volume, const Filter& f, const std::optional<std::string>& prefilter,
         const py::object& lo, const py::object& hi,
         const std::optional<std::variant<int, std::array<int, 3>>>& shape,
         const std::optional<std::string>& boundary, const py::object& affine,
         const py::object& like, const std::optional<std::string>& lattice,
         const py::object& spacing) -> py::object {
        const GridArgs where{lo, hi, affine, like, shape};
        const rt::CosetLattice onto =
            lattice ? rt::CosetLattice::parse(*lattice) : rt::CosetLattice::cartesian();
        if (!(onto == rt::CosetLattice::cartesian()))
          return py::cast(
              resample_onto_lattice(volume, f, prefilter, boundary, onto, where, spacing));
        if (!spacing.is_none())
          throw py::value_error(
              "spacing= is the h of a lattice= output (bcc, fcc, ...); a Cartesian grid is lo, hi "
              "and shape, affine= or like=");
        return resample(volume, f, prefilter, where, std::nullopt, boundary);
      },
      py::arg("volume"), py::arg("filter"), py::arg("prefilter") = py::none(),
      py::arg("lo") = py::none(), py::arg("hi") = py::none(), py::arg("shape") = py::none(),
      py::arg("boundary") = py::none(), py::kw_only(), py::arg("affine") = py::none(),
      py::arg("like") = py::none(), py::arg("lattice") = py::none(),
      py::arg("spacing") = py::none(),
      "The spline on the grid lo + (i, j, k) (hi - lo) / (shape - 1) (shape default 64; lo, hi "
      "default to filter.default_box of the coefficients after prefilter and boundary), or at "
      "the world points affine @ (i, j, k, 1) (any 4x4 voxel-to-world affine, oblique included), "
      "or on the grid of the image file like= (its shape and affine, as nibabel's): an array of "
      "the grid's shape. lattice= a non-Cartesian lattice (bcc, fcc, rows of G): a Volume on "
      "that lattice's grid over lo..hi at spacing= h or about shape^3 samples, or on the grid of "
      "the volume file like=, as `boxrecon resample --lattice`");
  m.def(
      "_resample_block",
      [](const VolumePtr& volume, const Filter& f, const std::optional<std::string>& prefilter,
         const py::object& lo, const py::object& hi,
         const std::variant<int, std::array<int, 3>>& shape,
         const std::array<std::array<int, 3>, 2>& block, const std::optional<std::string>& boundary,
         const py::object& affine) {
        return resample(volume, f, prefilter, GridArgs{lo, hi, affine, py::none(), shape}, block,
                        boundary);
      },
      py::arg("volume"), py::arg("filter"), py::arg("prefilter"), py::arg("lo"), py::arg("hi"),
      py::arg("shape"), py::arg("block"), py::arg("boundary") = py::none(),
      py::arg("affine") = py::none(),
      "resample() at the grid points begin <= (i, j, k) < end of block = (begin, end) only");
  m.def(
      "_image_grid",
      [](const std::string& path) {
        const ImageGrid g = image_grid(path);
        return py::make_tuple(py::make_tuple(g.sizes[0], g.sizes[1], g.sizes[2]),
                              affine_array(g.affine));
      },
      py::arg("path"),
      "(shape, affine) of the image file's grid (NIfTI or NRRD, oblique included), as like= "
      "takes it");
  m.def(
      "filters",
      [] {
        std::vector<std::string> names;
        for (int i = 0; i < rt::SplineFilter::count(); ++i)
          names.push_back(rt::SplineFilter::at(i).name());
        return names;
      },
      "The registry's filters");
  m.def(
      "test_functions",
      [] {
        std::vector<std::string> names;
        for (const auto& f : rt::test_functions()) names.emplace_back(f.name);
        return names;
      },
      "The test functions of sample()");
  m.def("threads", &rt::batch_threads,
        "Threads of the batch paths: set_threads(n), else BOXGEN_THREADS, else all cores");
  m.def("set_threads", &rt::set_batch_threads, py::arg("n"),
        "Caps the batch paths at n threads (0: back to BOXGEN_THREADS / all cores)");
}

}  // namespace boxgen::python
