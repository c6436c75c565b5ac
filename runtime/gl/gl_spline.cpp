#include "runtime/gl/gl_spline.h"

#define GL_GLEXT_PROTOTYPES
#include <GL/glcorearb.h>
#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <climits>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <type_traits>
#include <utility>

#include "runtime/gl/glsl_tables.h"
#include "runtime/gl/registry_glsl.h"

namespace boxgen::runtime::gl {

namespace {

constexpr int kLocalSize = 128;    // invocations per work group
constexpr int kMaxGroups = 65535;  // the dispatch size every GL 4.3 device takes
// Far outside the volume (lattice units), points are refused before the evaluator converts
// floor(x) to an int (as emitted_spline.h's kFar); their error comes from the CPU path.
constexpr double kFar = 64;
// TableStorage::buffer's block (bindings 0, 1: the volume; 2-4: the kernels).
constexpr int kTablesBinding = 5;

// The shader's opening: the precision, the volume's storage buffers and the evaluator's fetch
// (lattice point -> coset and cell of d Z^3 -> the storage order of lattice_volume.h), then the
// evaluator's text. A fetch outside the stored samples reads 0 and marks the invocation.
template <class T>
std::string prelude(const LatticeVolume<T>& volume, const std::string& name,
                    const std::string& evaluator) {
  constexpr bool dbl = std::is_same_v<T, double>;
  return fmt::format(R"(#version 430
#define BOXGEN_TABLES_BINDING {6}
#define REAL {0}
#define VEC3 {1}vec3
#define MAT3 {1}mat3
layout(local_size_x = {2}) in;
layout(std430, binding = 0) readonly buffer Samples {{ REAL samples[]; }};
layout(std430, binding = 1) readonly buffer Cosets {{ int coset_of_residue[]; }};
uniform ivec3 sizes;
const int kPeriod = {3};
const int kCosets = {4};
bool outside_volume = false;
int boxgen_floor_div(int a, int b) {{ return a >= 0 ? a / b : -((b - 1 - a) / b); }}
// The position of lattice point j in the samples, or -1 where it is not stored.
int boxgen_sample_index(ivec3 j) {{
  ivec3 q = ivec3(boxgen_floor_div(j.x, kPeriod), boxgen_floor_div(j.y, kPeriod),
                  boxgen_floor_div(j.z, kPeriod));
  ivec3 r = j - kPeriod * q;
  int c = coset_of_residue[r.x + kPeriod * (r.y + kPeriod * r.z)];
  if (c < 0 || any(lessThan(q, ivec3(0))) || any(greaterThanEqual(q, sizes))) return -1;
  return c + kCosets * (q.x + sizes.x * (q.y + sizes.y * q.z));
}}
REAL {5}_fetch(ivec3 j) {{
  int k = boxgen_sample_index(j);
  if (k < 0) {{
    outside_volume = true;
    return REAL(0);
  }}
  return samples[k];
}}
)",
                     dbl ? "double" : "float", dbl ? "d" : "", kLocalSize, volume.period(),
                     volume.coset_count(), name, kTablesBinding) +
         evaluator;
}

// The kernels' buffers (binding 2: the points or ray directions, then the results and a status per
// invocation), their range of invocations, and the store of a value, gradient and Hessian (the
// upper triangle xx xy xz yy yz zz) at results[at].
std::string kernel_io(const char* input) {
  return fmt::format(R"(
layout(std430, binding = 2) readonly buffer Input {{ REAL {}[]; }};
layout(std430, binding = 3) writeonly buffer Results {{ REAL results[]; }};
layout(std430, binding = 4) writeonly buffer Status {{ int status[]; }};
uniform int base;
uniform int count;
// Components by name, never by a run-time index: NVIDIA's compiler keeps only single precision
// where a double vector is indexed at run time (docs/gpu.md).
void boxgen_store_gradient(int at, REAL v, VEC3 g) {{
  results[at] = v;
  results[at + 1] = g.x;
  results[at + 2] = g.y;
  results[at + 3] = g.z;
}}
void boxgen_store(int at, REAL v, VEC3 g, MAT3 h) {{
  boxgen_store_gradient(at, v, g);
  results[at + 4] = h[0][0];
  results[at + 5] = h[1][0];
  results[at + 6] = h[2][0];
  results[at + 7] = h[1][1];
  results[at + 8] = h[2][1];
  results[at + 9] = h[2][2];
}}
)",
                     input);
}

// The batch kernel of one order (0, 1, 2: value, + gradient, + Hessian; kFetchFloor: the same
// number of samples read around the point and summed). Points in lattice coordinates.
std::string batch_kernel(const std::string& name, int order) {
  std::string body;
  if (order == 0) {
    body = fmt::format("  results[p] = {}_value(x);\n", name);
  } else if (order == 1) {
    body = fmt::format(R"(  VEC3 g;
  REAL v = {}_value_gradient(x, g);
  boxgen_store_gradient(4 * p, v, g);
)",
                       name);
  } else if (order == 2) {
    body = fmt::format(R"(  VEC3 g;
  MAT3 h;
  REAL v = {}_value_gradient_hessian(x, g, h);
  boxgen_store(10 * p, v, g, h);
)",
                       name);
  } else {  // the floor: a compact box of stored samples next to the point, all cosets
    body = fmt::format(R"(  ivec3 q = ivec3(floor(x / REAL(kPeriod)));
  int side = int(ceil(pow(float({0}_kStencilSize) / float(kCosets), 1.0 / 3.0)));
  REAL sum = REAL(0);
  for (int s = 0; s < {0}_kStencilSize; ++s) {{
    int b = s / kCosets;
    ivec3 k = clamp(q + ivec3(b % side, (b / side) % side, b / (side * side)), ivec3(0), sizes - 1);
    sum += samples[s % kCosets + kCosets * (k.x + sizes.x * (k.y + sizes.y * k.z))];
  }}
  results[p] = sum;
)",
                       name);
  }
  return kernel_io("points") + fmt::format(R"(
void main() {{
  int p = base + int(gl_GlobalInvocationID.x);
  if (p >= count) return;
  VEC3 x = VEC3(points[3 * p], points[3 * p + 1], points[3 * p + 2]);
{}  status[p] = outside_volume ? 1 : 0;
}}
)",
                                           body);
}

// The renderer of render.h on the GPU, one invocation per pixel: the camera's ray through it
// (Camera::ray), the caster's march and the hit's normal, cut face and principal curvatures
// (RayCaster::cast: clip to the box, march by the step, bisect the first crossing), the colours
// (render.cpp's shade_pixels). A transcription of render.cpp's code, kept equal to it
// by the render agreement test (docs/design.md §16). Each pixel's word: its RGB bytes (red low),
// and in the top byte the status: 4 for a fetch outside the volume.
std::string frame_kernel(const std::string& name) {
  return fmt::format(R"(
layout(std430, binding = 3) writeonly buffer Pixels {{ uint pixels[]; }};
uniform int base;
uniform int count;
uniform int width, height, cutaway, curvature;
uniform VEC3 eye, forward, right, up, light, box_min, box_max, mid, origin, spacing;
uniform REAL tan_half, size, step, iso, eps, value_lo, value_hi, curvature_scale;
bool in_region(VEC3 p) {{
  return cutaway == 0 || !(p.z > mid.z && (p.x > mid.x || p.y > mid.y));
}}
bool inside(VEC3 p) {{
  return in_region(p) && {0}_value((p - origin) / spacing) >= iso;
}}
// One axis of the slab test; axes by name, not by a run-time index: NVIDIA's compiler keeps only
// single precision where a double vector is indexed at run time (docs/gpu.md).
bool clip_axis(REAL o, REAL d, REAL lo, REAL hi, inout REAL t0, inout REAL t1) {{
  if (abs(d) < REAL(1e-30)) return o >= lo && o <= hi;
  REAL a = (lo - o) / d, b = (hi - o) / d;
  t0 = max(t0, min(a, b));
  t1 = min(t1, max(a, b));
  return true;
}}
bool clip_to_box(VEC3 o, VEC3 d, out REAL t0, out REAL t1) {{
  t0 = REAL(0);
  t1 = REAL(1e30);
  return clip_axis(o.x, d.x, box_min.x, box_max.x, t0, t1) &&
         clip_axis(o.y, d.y, box_min.y, box_max.y, t0, t1) &&
         clip_axis(o.z, d.z, box_min.z, box_max.z, t0, t1) && t1 > t0;
}}
// RayCaster::face_normal: the cut or box face nearest to p, against d.
REAL face_gap(REAL p, REAL m, REAL lo, REAL hi) {{
  return min(abs(p - m), min(abs(p - lo), abs(p - hi)));
}}
VEC3 face_normal(VEC3 p, VEC3 d) {{
  REAL gx = face_gap(p.x, mid.x, box_min.x, box_max.x);
  REAL gy = face_gap(p.y, mid.y, box_min.y, box_max.y);
  REAL gz = face_gap(p.z, mid.z, box_min.z, box_max.z);
  if (gx <= gy && gx <= gz) return VEC3(d.x > REAL(0) ? -1 : 1, 0, 0);
  if (gy <= gz) return VEC3(0, d.y > REAL(0) ? -1 : 1, 0);
  return VEC3(0, 0, d.z > REAL(0) ? -1 : 1);
}}
// render.cpp's principal_curvatures: the eigenvalues of -P H P / |g| from its trace and
// Frobenius norm (P the projection onto the tangent plane).
void principal_curvatures(VEC3 g, MAT3 h, out REAL k1, out REAL k2) {{
  REAL glen = length(g);
  VEC3 n = -g / glen;
  MAT3 p = MAT3(1) - outerProduct(n, n);
  MAT3 c = -(p * h * p) / glen;
  REAL trace = c[0][0] + c[1][1] + c[2][2];
  REAL frob2 = dot(c[0], c[0]) + dot(c[1], c[1]) + dot(c[2], c[2]);
  REAL root = sqrt(max(REAL(0), REAL(2) * frob2 - trace * trace));
  k1 = REAL(0.5) * (trace + root);
  k2 = REAL(0.5) * (trace - root);
}}
// render.cpp's value_colour and curvature_colour.
VEC3 value_colour(REAL t) {{
  const VEC3 stops[5] = VEC3[](VEC3(0.267, 0.005, 0.329), VEC3(0.230, 0.322, 0.546),
                               VEC3(0.128, 0.567, 0.551), VEC3(0.369, 0.789, 0.383),
                               VEC3(0.993, 0.906, 0.144));
  t = clamp(isnan(t) || isinf(t) ? REAL(0) : t, REAL(0), REAL(1)) * REAL(4);
  int i = min(3, int(t));
  REAL f = t - REAL(i);
  VEC3 a = stops[0], b = stops[1];
  if (i == 1) {{ a = stops[1]; b = stops[2]; }}
  if (i == 2) {{ a = stops[2]; b = stops[3]; }}
  if (i == 3) {{ a = stops[3]; b = stops[4]; }}
  return (REAL(1) - f) * a + f * b;
}}
VEC3 curvature_colour(REAL k1, REAL k2) {{
  // GLSL's tanh is single precision only.
  REAL u = REAL(tanh(float(k1 * curvature_scale))), v = REAL(tanh(float(k2 * curvature_scale)));
  REAL mean = REAL(0.5) * (u + v), spread = clamp(REAL(0.5) * (u - v), REAL(0), REAL(1));
  VEC3 c = VEC3(0.80, 0.80, 0.80);
  VEC3 target = mean > REAL(0) ? VEC3(1.0, 0.55, 0.15) : VEC3(0.2, 0.4, 1.0);
  c += abs(mean) * (target - c);
  REAL w = spread * (REAL(1) - abs(mean));
  return c + w * (VEC3(0.25, 0.8, 0.3) - c);
}}
REAL pow40(REAL x) {{  // x^40 by squaring (GLSL's pow is single precision only)
  REAL x5 = x * x * x * x * x;
  REAL x10 = x5 * x5;
  REAL x20 = x10 * x10;
  return x20 * x20;
}}
uint channel(REAL c) {{  // std::lround(255 * clamp(c, 0, 1))
  return uint(floor(REAL(255) * clamp(c, REAL(0), REAL(1)) + REAL(0.5)));
}}
// One call of inside() and one of the evaluator in the whole kernel: the driver inlines every
// call, and each copy of the evaluator costs compile time (llvmpipe: seconds).
void main() {{
  int p = base + int(gl_GlobalInvocationID.x);
  if (p >= count) return;
  int px = p % width, py = p / width;
  REAL sx = (REAL(2) * (REAL(px) + REAL(0.5)) / REAL(width) - REAL(1)) * tan_half * REAL(width) /
            REAL(height);
  REAL sy = (REAL(1) - REAL(2) * (REAL(py) + REAL(0.5)) / REAL(height)) * tan_half;
  VEC3 d = normalize(forward + right * sx + up * sy);
  REAL t0, t1;
  int flags = 0;
  REAL t = REAL(0);
  if (clip_to_box(eye, d, t0, t1)) {{
    t0 += eps * size;
    t1 -= eps * size;
    // phase 0: the entry point; 1: marching by the step (k steps); 2: bisecting [lo, hi].
    int phase = 0, k = 0;
    REAL probe = t0, prev = t0, lo = t0, hi = t0;
    for (int guard = 0; guard < (1 << 18); ++guard) {{
      bool solid = inside(eye + d * probe);
      if (phase == 0 && solid) {{
        flags = 3;
        t = t0;
        break;
      }}
      if (phase == 1 && solid) {{
        lo = prev;
        hi = probe;
        phase = 2;
      }} else if (phase == 2) {{
        if (solid) hi = probe; else lo = probe;
      }} else {{  // outside: one more step
        if (phase == 1 && probe >= t1) break;
        phase = 1;
        prev = probe;
        ++k;
        probe = min(t0 + REAL(k) * step, t1);
        continue;
      }}
      REAL m = REAL(0.5) * (lo + hi);
      if (!(hi - lo > eps * size) || m <= lo || m >= hi) {{  // float: the bracket stops shrinking
        t = hi;
        // Through a cut face when the point just before is outside the region (as the CPU's
        // cast tests, with a gap float resolves).
        flags = in_region(eye + d * (t - REAL(2) * eps * size)) ? 1 : 3;
        break;
      }}
      probe = m;
    }}
  }}
  REAL ry = REAL(py) / REAL(height);
  VEC3 colour = VEC3(REAL(0.93) - REAL(0.12) * ry, REAL(0.94) - REAL(0.1) * ry, 0.96);
  if (flags != 0) {{
    VEC3 point = eye + d * t;
    VEC3 g;
    MAT3 h;
    REAL value = {0}_value_gradient_hessian((point - origin) / spacing, g, h);
    // Lattice-frame derivatives to world units (as to_world on the CPU).
    g /= spacing;
    h = matrixCompMult(h, outerProduct(VEC3(1) / spacing, VEC3(1) / spacing));
    bool on_cut = (flags & 2) != 0;
    VEC3 normal;
    REAL k1 = REAL(0), k2 = REAL(0);
    if (!on_cut && dot(g, g) > REAL(0)) {{
      normal = normalize(-g);
      if (curvature != 0) principal_curvatures(g, h, k1, k2);
    }} else {{
      on_cut = true;
      normal = face_normal(point, d);
    }}
    if (dot(normal, d) > REAL(0)) normal = -normal;
    VEC3 base_colour = on_cut ? value_colour((value - value_lo) / (value_hi - value_lo))
                              : VEC3(0.82, 0.80, 0.76);
    if (!on_cut && curvature != 0) base_colour = curvature_colour(k1, k2);
    REAL diffuse = max(REAL(0), dot(normal, light));
    VEC3 halfway = normalize(light - d);
    REAL specular = on_cut ? REAL(0) : REAL(0.25) * pow40(max(REAL(0), dot(normal, halfway)));
    colour = min(VEC3(1), base_colour * (REAL(0.28) + REAL(0.72) * diffuse) + specular);
  }}
  pixels[p] = channel(colour.x) | (channel(colour.y) << 8) | (channel(colour.z) << 16) |
              (outside_volume ? 4u << 24 : 0u);
}}
)",
                     name);
}

// A storage buffer of `bytes` (at least 4) holding `data` (or nothing), bound at `binding`.
unsigned storage_buffer(unsigned id, unsigned binding, const void* data, std::size_t bytes) {
  if (id == 0) glGenBuffers(1, &id);
  glBindBuffer(GL_SHADER_STORAGE_BUFFER, id);
  glBufferData(GL_SHADER_STORAGE_BUFFER, static_cast<GLsizeiptr>(std::max<std::size_t>(bytes, 4)),
               data, GL_DYNAMIC_COPY);
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, binding, id);
  return id;
}

template <class V>
void read_buffer(unsigned id, std::vector<V>& out) {
  glBindBuffer(GL_SHADER_STORAGE_BUFFER, id);
  glGetBufferSubData(GL_SHADER_STORAGE_BUFFER, 0, static_cast<GLsizeiptr>(out.size() * sizeof(V)),
                     out.data());
}

void uniform_real(unsigned program, const char* name, double v, bool dbl) {
  const GLint at = glGetUniformLocation(program, name);
  if (dbl)
    glUniform1d(at, v);
  else
    glUniform1f(at, static_cast<float>(v));
}
void uniform_vec3(unsigned program, const char* name, const Vec3& v, bool dbl) {
  const GLint at = glGetUniformLocation(program, name);
  if (dbl)
    glUniform3d(at, v[0], v[1], v[2]);
  else
    glUniform3f(at, static_cast<float>(v[0]), static_cast<float>(v[1]), static_cast<float>(v[2]));
}

// Lattice-frame derivatives d (gradient, then the Hessian's upper triangle) in world units, as
// emitted_spline.h's to_world_derivatives: divided by the spacing of each axis.
template <class T>
void to_world(const T* d, const Vec3& h, Vec3& gradient, Hessian* hessian) {
  for (int a = 0; a < 3; ++a) gradient[a] = static_cast<double>(d[a]) / h[a];
  if (!hessian) return;
  constexpr int kRow[6] = {0, 0, 0, 1, 1, 2}, kColumn[6] = {0, 1, 2, 1, 2, 2};
  for (int i = 0; i < 6; ++i)
    (*hessian)[i] = static_cast<double>(d[3 + i]) / (h[kRow[i]] * h[kColumn[i]]);
}

std::string mib(double bytes) { return fmt::format("{:.1f} MiB", bytes / (1 << 20)); }

}  // namespace

GlslEvaluator registry_glsl(const std::string& name, bool double_precision) {
  std::string names;
  for (int i = 0; i < kRegistryGlslCount; ++i) {
    const RegistryGlsl& r = kRegistryGlsl[i];
    if (name == r.name)
      return {name, double_precision ? r.double_text : r.float_text,
              double_precision ? r.double_buffered : r.float_buffered,
              std::vector<int>(r.block, r.block + r.block_size)};
    names += fmt::format("{}{}", i ? ", " : "", r.name);
  }
  throw GlError(fmt::format(
      "this build embeds the GLSL of the registry's filters ({}), not of {}: a SPEC's comes with "
      "its filter (filter_glsl), a file of `boxgen emit --target glsl` from read_glsl",
      names, name));
}

GlslEvaluator filter_glsl(const SplineFilter& filter, bool double_precision) {
  if (filter.registry_index() >= 0) return registry_glsl(filter.name(), double_precision);
  if (auto own = filter.source().glsl(double_precision)) return std::move(*own);
  throw GlError(fmt::format(
      "filter {} carries no GLSL evaluator: give the NAME.glsl of `boxgen emit --target glsl` "
      "(read_glsl)",
      filter.name()));
}

GlslEvaluator read_glsl(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw GlError(fmt::format("cannot read the GLSL evaluator {}", path));
  std::stringstream s;
  s << in.rdbuf();
  return {std::filesystem::path(path).stem().string(), s.str()};
}

template <class T>
GlSpline<T>::GlSpline(const LatticeVolume<T>& volume, const SplineFilter& filter,
                      GlslEvaluator glsl, TableStorage tables)
    : volume_(&volume), cpu_(volume, filter), glsl_(std::move(glsl)), programs_(5, 0) {
  const DeviceInfo& info = device();
  const double bytes = static_cast<double>(volume.sample_count()) * sizeof(T);
  if (volume.sample_count() > static_cast<std::size_t>(INT_MAX) ||
      bytes > static_cast<double>(storage_limit()))
    throw GlError(fmt::format(
        "the volume ({} samples, {}) exceeds the largest storage buffer of {} ({}): use --device "
        "cpu or a smaller volume",
        volume.sample_count(), mib(bytes), info.renderer,
        mib(static_cast<double>(std::min<std::int64_t>(storage_limit(), INT_MAX)))));
  const int d = volume.period();
  std::vector<int> residues;  // x fastest: the shader's r.x + d (r.y + d r.z)
  for (int z = 0; z < d; ++z)
    for (int y = 0; y < d; ++y)
      for (int x = 0; x < d; ++x) residues.push_back(volume.lattice().coset_of(x, y, z));
  samples_ = storage_buffer(0, 0, volume.samples().data(), volume.sample_count() * sizeof(T));
  lattice_table_ = storage_buffer(0, 1, residues.data(), residues.size() * sizeof(int));
  shader_text_ = glsl_.text;
  if (tables == TableStorage::buffer && !glsl_.buffered.empty()) {
    shader_text_ = glsl_.buffered;
    tables_ =
        storage_buffer(0, kTablesBinding, glsl_.block.data(), glsl_.block.size() * sizeof(int));
  }
  check_gl("the volume's upload");
}

template <class T>
GlSpline<T>::~GlSpline() {
  for (unsigned p : programs_)
    if (p) glDeleteProgram(p);
  const unsigned buffers[] = {samples_, lattice_table_, tables_, points_, results_, status_};
  for (unsigned b : buffers)
    if (b) glDeleteBuffers(1, &b);
}

template <class T>
std::string GlSpline<T>::kernel_source(int kind) const {
  if (kind != kFetchFloor && (kind < 0 || kind > kFrame))
    throw std::invalid_argument(fmt::format("kernel_source: no kernel {}", kind));
  return prelude(*volume_, glsl_.name, shader_text_) +
         (kind == kFrame ? frame_kernel(glsl_.name) : batch_kernel(glsl_.name, kind));
}

template <class T>
unsigned GlSpline<T>::program(int kind) const {
  unsigned& p = programs_[kind == kFetchFloor ? 0 : static_cast<std::size_t>(kind) + 1];
  if (p == 0) {
    constexpr const char* kKernels[] = {"fetch floor", "value", "gradient", "Hessian", "frame"};
    p = compile_compute(kernel_source(kind),
                        fmt::format("the GLSL evaluator {} ({}, {} kernel{})", glsl_.name,
                                    sizeof(T) == 8 ? "double" : "float", kKernels[kind + 1],
                                    tables_ ? "" : ", const tables"));
  }
  glUseProgram(p);
  const Sizes& n = volume_->sizes();
  glUniform3i(glGetUniformLocation(p, "sizes"), n[0], n[1], n[2]);
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 0, samples_);
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 1, lattice_table_);
  if (tables_) glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kTablesBinding, tables_);
  return p;
}

// Runs the bound program over `count` invocations in dispatches of at most kMaxGroups groups and
// waits for them.
template <class T>
void GlSpline<T>::dispatch(unsigned p, std::size_t count) const {
  glUniform1i(glGetUniformLocation(p, "count"), static_cast<GLint>(count));
  const std::size_t per = static_cast<std::size_t>(kMaxGroups) * kLocalSize;
  for (std::size_t base = 0; base < count; base += per) {
    glUniform1i(glGetUniformLocation(p, "base"), static_cast<GLint>(base));
    const std::size_t n = std::min(per, count - base);
    glDispatchCompute(static_cast<GLuint>((n + kLocalSize - 1) / kLocalSize), 1, 1);
  }
  glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT | GL_SHADER_STORAGE_BARRIER_BIT);
  glFinish();
  check_gl("a compute dispatch");
}

template <class T>
void GlSpline<T>::upload(std::span<const Vec3> points) const {
  const std::size_t n = points.size();
  if (n > static_cast<std::size_t>(INT_MAX) / 10 ||
      static_cast<double>(n) * 10 * sizeof(T) > static_cast<double>(storage_limit()))
    throw GlError(fmt::format("{} points do not fit the device's storage buffers", n));
  std::vector<T> lattice(3 * n);
  for (std::size_t i = 0; i < n; ++i) {
    const Vec3 x = volume_->to_lattice(points[i]);
    for (int a = 0; a < 3; ++a)  // far or non-finite points: the CPU path names their error
      lattice[3 * i + a] = std::isfinite(x[a]) && std::abs(x[a]) < (1 << 24)
                               ? static_cast<T>(x[a])
                               : static_cast<T>(-2 * kFar);
  }
  points_ = storage_buffer(points_, 2, lattice.data(), lattice.size() * sizeof(T));
  results_ = storage_buffer(results_, 3, nullptr, 10 * n * sizeof(T));
  status_ = storage_buffer(status_, 4, nullptr, n * sizeof(int));
  uploaded_ = n;
  check_gl("the points' upload");
}

template <class T>
void GlSpline<T>::run(int order) const {
  const unsigned p = program(order);
  const unsigned buffers[] = {points_, results_, status_};
  for (unsigned b = 0; b < 3; ++b) glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 2 + b, buffers[b]);
  dispatch(p, uploaded_);
}

template <class T>
void GlSpline<T>::throw_point_error(std::span<const Vec3> points, std::size_t index) const {
  try {
    Vec3 g;
    Hessian h;
    (void)cpu_.value(points[index], &g, &h);
  } catch (const std::exception& e) {  // as the CPU batch reports it (emitted_spline.h)
    throw std::out_of_range(fmt::format("point {}: {}", index + 1, e.what()));
  }
  const Vec3& p = points[index];
  throw std::out_of_range(fmt::format(
      "point {}: world point ({}, {}, {}) needs a sample outside the volume (on the GPU's "
      "rounding of its coordinates)",
      index + 1, p[0], p[1], p[2]));
}

template <class T>
void GlSpline<T>::evaluate(std::span<const Vec3> points, std::span<T> values,
                           std::span<Vec3> gradients, std::span<Hessian> hessians) const {
  if (values.size() != points.size() || (!gradients.empty() && gradients.size() != points.size()) ||
      (!hessians.empty() &&
       (hessians.size() != points.size() || gradients.size() != points.size())))
    throw std::invalid_argument("evaluate: output sizes differ from the number of points");
  const int order = !hessians.empty() ? 2 : !gradients.empty() ? 1 : 0;
  const std::size_t stride = order == 2 ? 10 : order == 1 ? 4 : 1;
  // Batches that fit the device's storage blocks (results: 10 reals per point at most).
  const std::size_t chunk = std::max<std::size_t>(
      1, std::min<std::size_t>(std::size_t{1} << 22,
                               static_cast<std::size_t>(storage_limit()) / (10 * sizeof(T))));
  std::vector<T> results;
  std::vector<int> status;
  for (std::size_t first = 0; first < points.size(); first += chunk) {
    const std::size_t n = std::min(chunk, points.size() - first);
    const std::span<const Vec3> part = points.subspan(first, n);
    upload(part);
    run(order);
    results.resize(stride * n);
    status.resize(n);
    read_buffer(results_, results);
    read_buffer(status_, status);
    check_gl("reading the results");
    for (std::size_t i = 0; i < n; ++i) {
      const Vec3 x = volume_->to_lattice(part[i]);
      const bool far = std::any_of(x.begin(), x.end(), [](double c) {
        return !std::isfinite(c) || std::abs(c) >= (1 << 24);
      });
      if (status[i] != 0 || far) throw_point_error(points, first + i);
      const T* r = &results[stride * i];
      values[first + i] = r[0];
      if (order >= 1)
        to_world(r + 1, volume_->axis_spacing(), gradients[first + i],
                 order == 2 ? &hessians[first + i] : nullptr);
    }
  }
}

template <class T>
RgbBuffer GlSpline<T>::render(const FrameOptions& o, FrameTimes* times) const {
  using Clock = std::chrono::steady_clock;
  constexpr bool dbl = std::is_same_v<T, double>;
  const std::size_t n = static_cast<std::size_t>(o.width) * static_cast<std::size_t>(o.height);
  if (o.width < 1 || o.height < 1 || n > static_cast<std::size_t>(INT_MAX) ||
      static_cast<double>(n) * sizeof(unsigned) > static_cast<double>(storage_limit()))
    throw GlError(fmt::format("a {} x {} picture does not fit the device's storage buffers",
                              o.width, o.height));
  const unsigned p = program(kFrame);  // compiled on first use: not part of the frame's time
  const Clock::time_point start = Clock::now();
  results_ = storage_buffer(results_, 3, nullptr, n * sizeof(unsigned));
  Vec3 mid, diagonal;
  for (int a = 0; a < 3; ++a) {
    mid[a] = 0.5 * (o.box.min[a] + o.box.max[a]);
    diagonal[a] = o.box.max[a] - o.box.min[a];
  }
  glUniform1i(glGetUniformLocation(p, "width"), o.width);
  glUniform1i(glGetUniformLocation(p, "height"), o.height);
  glUniform1i(glGetUniformLocation(p, "cutaway"), o.cutaway ? 1 : 0);
  glUniform1i(glGetUniformLocation(p, "curvature"), o.curvature ? 1 : 0);
  const std::pair<const char*, const Vec3*> vectors[] = {{"eye", &o.camera.eye},
                                                         {"forward", &o.camera.forward},
                                                         {"right", &o.camera.right},
                                                         {"up", &o.camera.up},
                                                         {"light", &o.light},
                                                         {"box_min", &o.box.min},
                                                         {"box_max", &o.box.max},
                                                         {"mid", &mid},
                                                         {"origin", &volume_->origin()},
                                                         {"spacing", &volume_->axis_spacing()}};
  for (const auto& [name, v] : vectors) uniform_vec3(p, name, *v, dbl);
  // The CPU caster's tolerance (1e-9 of the diagonal) where double resolves it; float stops at
  // 1e-6, about its resolution of t.
  const std::pair<const char*, double> reals[] = {
      {"tan_half", o.camera.tan_half},
      {"size", std::sqrt(diagonal[0] * diagonal[0] + diagonal[1] * diagonal[1] +
                         diagonal[2] * diagonal[2])},
      {"step", o.step},
      {"iso", o.iso},
      {"eps", dbl ? 1e-9 : 1e-6},
      {"value_lo", o.value_lo},
      {"value_hi", o.value_hi},
      {"curvature_scale", o.curvature_scale}};
  for (const auto& [name, v] : reals) uniform_real(p, name, v, dbl);
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 3, results_);
  const Clock::time_point dispatched = Clock::now();
  dispatch(p, n);
  const Clock::time_point done = Clock::now();
  std::vector<unsigned> words(n);
  read_buffer(results_, words);
  check_gl("reading the picture");
  RgbBuffer image{o.width, o.height, std::vector<std::uint8_t>(3 * n)};
  for (std::size_t i = 0; i < n; ++i) {
    if (words[i] >> 24 & 4)
      throw std::out_of_range(
          "a ray of the render reads samples outside the volume: choose a box inside it");
    for (int c = 0; c < 3; ++c)
      image.pixels[3 * i + static_cast<std::size_t>(c)] =
          static_cast<std::uint8_t>(words[i] >> (8 * c) & 0xff);
  }
  if (times) {
    const auto seconds = [](Clock::duration d) { return std::chrono::duration<double>(d).count(); };
    times->gpu = seconds(done - dispatched);
    times->cpu += seconds(dispatched - start) + seconds(Clock::now() - done);
  }
  return image;
}

template class GlSpline<float>;
template class GlSpline<double>;

}  // namespace boxgen::runtime::gl
