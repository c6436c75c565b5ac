#include "loader/filter_loader.h"

#include <dlfcn.h>
#include <unistd.h>

#include <algorithm>
#include <array>

#include <fmt/format.h>
#include <atomic>
#include <chrono>
#include <cstdio>
#include <fstream>
#include <sstream>

#include "boxgen/version.h"
#include "frontend/optimised_prefilter.h"
#include "generator/codegen/emitter.h"
#include "generator/derivation.h"
#include "generator/error.h"
#include "generator/int_linalg.h"
#include "generator/spec.h"
#include "loader/filter_cache.h"
#include "loader/filter_compiler.h"
#include "runtime/batch_threads.h"
#include "runtime/nrrd_checks.h"
#include "support/output_file.h"

namespace boxgen::loader {

namespace fs = std::filesystem;
namespace rt = boxgen::runtime;
namespace gen = boxgen::generator;

namespace {

// Progress of a first use on stderr: on a terminal one line rewritten in place, else a line per
// stage; nothing unless asked for.
class Progress {
 public:
  explicit Progress(bool on) : on_(on), tty_(isatty(STDERR_FILENO) != 0) {}
  ~Progress() { finish(); }
  Progress(const Progress&) = delete;
  Progress& operator=(const Progress&) = delete;
  void stage(const std::string& what) {
    if (!on_) return;
    const double t =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
    std::fprintf(stderr, tty_ ? "\r\033[Kboxgen: %s (%.1f s)" : "boxgen: %s (%.1f s)\n",
                 what.c_str(), t);
    std::fflush(stderr);
    printed_ = true;
  }
  void finish() {
    if (on_ && printed_ && tty_) std::fputs("\r\033[K", stderr);
    printed_ = false;
  }

 private:
  bool on_, tty_, printed_ = false;
  std::chrono::steady_clock::time_point start_ = std::chrono::steady_clock::now();
};

std::string rows_text(const gen::Lattice& lattice) {
  std::string out;
  for (const auto& row : lattice.generator_rows()) {
    if (!out.empty()) out += "; ";
    for (std::size_t i = 0; i < row.size(); ++i) out += (i ? "," : "") + std::to_string(row[i]);
  }
  return out;
}

// The registry's filter of that name, if any.
std::optional<rt::SplineFilter> registry_filter(const std::string& name) {
  for (int i = 0; i < rt::SplineFilter::count(); ++i)
    if (rt::SplineFilter::at(i).name() == name) return rt::SplineFilter::at(i);
  return std::nullopt;
}

// The shared object's two sources, compiled at the same time (the double precision half of the
// evaluation paths and SIMD kernels is the second: each half is about half the compile): the
// emitted evaluator in both, and in the first the prefilters, the float half and the two exported
// functions. boxgen_filter_stamp() says which loader, boxgen and entry it was built for;
// boxgen_filter_create() returns the filter as a FilterSource of the runtime's engine, whose
// batch paths follow the host's thread cap (the object has its own copy of the runtime's
// functions, so the cap is asked from the host before each batch).
std::array<std::string, 2> glue_sources(const std::string& name, const gen::Emission& emission,
                                        const std::string& stamp) {
  const std::string head = fmt::format(
      R"(// A run-time filter of boxgen (loader/filter_loader.cpp): do not edit, it is rebuilt.
// The engine first, so that the build's precompiled header can stand for it.
#include <runtime/compiled_filter.h>

{evaluator}

namespace rt = boxgen::runtime;
namespace g = boxgen::generated::{name};

// The double precision half (the second source) fills these.
void boxgen_filter_double_kernels(rt::simd::Kernels& kernels);
)",
      fmt::arg("evaluator", emission.files.at(0).pasted), fmt::arg("name", name));
  const auto table = [](const std::optional<gen::Prefilter>& q, const char* id) {
    return q ? fmt::format("rt::prefilter_from(g::{})", id) : std::string("rt::PrefilterTaps{}");
  };
  std::string first =
      head + fmt::format(
                 R"(
extern template std::shared_ptr<const rt::EvaluationPath<double>> rt::emitted_path<g::Traits, double, false>(
    const rt::LatticeVolume<double>&, int, const rt::simd::Kernels*);

{prefilters}

namespace {{
using HostThreads = int (*)();

// The SIMD kernels of this filter for the instruction set it is compiled for (-march=native);
// none for a scaled pair, which the kernels do not handle (the scalar path serves it).
template <class Tr>
const rt::simd::Kernels* own_kernels() {{
  if constexpr (Tr::kScale == 1) {{
    static const rt::simd::Kernels kernels = [] {{
      rt::simd::Kernels k{{}};
      rt::simd::HWY_NAMESPACE::set_kernels_for<Tr, float>(k);
      boxgen_filter_double_kernels(k);
      return k;
    }}();
    return &kernels;
  }} else {{
    return nullptr;
  }}
}}

template <class T>
class Path final : public rt::EvaluationPath<T> {{
 public:
  Path(std::shared_ptr<const rt::EvaluationPath<T>> inner, HostThreads threads)
      : inner_(std::move(inner)), threads_(threads) {{}}
  T at(const rt::Vec3& p, rt::Vec3* g, rt::Hessian* h) const override {{ return inner_->at(p, g, h); }}
  void batch(std::span<const rt::Vec3> p, std::span<T> v, std::span<rt::Vec3> g,
             std::span<rt::Hessian> h) const override {{
    rt::set_batch_threads(threads_());
    inner_->batch(p, v, g, h);
  }}
 private:
  std::shared_ptr<const rt::EvaluationPath<T>> inner_;
  HostThreads threads_;
}};

class Source final : public rt::FilterSource {{
 public:
  Source(std::string name, HostThreads threads)
      : filter_({{{q1}, {q2}, {q1opt}, {q2opt}}}, g::kApproximationOrder, -1,
                own_kernels<g::Traits>()),
        name_(std::move(name)), threads_(threads) {{}}
  std::string name() const override {{ return name_; }}
  rt::CosetLattice lattice() const override {{ return filter_.lattice(); }}
  rt::StencilReach reach() const override {{ return filter_.reach(); }}
  rt::PrefilterTaps prefilter(rt::PrefilterChoice q) const override {{ return filter_.prefilter(q); }}
  int approximation_order() const override {{ return filter_.approximation_order(); }}
  std::shared_ptr<const rt::EvaluationPath<float>> path(const rt::LatticeVolume<float>& v) const override {{
    return std::make_shared<Path<float>>(filter_.path(v), threads_);
  }}
  std::shared_ptr<const rt::EvaluationPath<double>> path(const rt::LatticeVolume<double>& v) const override {{
    return std::make_shared<Path<double>>(filter_.path(v), threads_);
  }}
 private:
  rt::EmittedFilter<g::Traits, false> filter_;
  std::string name_;
  HostThreads threads_;
}};
}}  // namespace

extern "C" __attribute__((visibility("default"))) const char* boxgen_filter_stamp() {{
  return "{stamp}";
}}
extern "C" __attribute__((visibility("default"))) rt::FilterSource* boxgen_filter_create(
    const char* name, HostThreads threads) {{
  return new Source(name, threads);
}}
)",
                 fmt::arg("prefilters", emission.files.at(1).pasted),
                 fmt::arg("q1", table(emission.q1, "q1")), fmt::arg("q2", table(emission.q2, "q2")),
                 fmt::arg("q1opt", table(emission.q1opt, "q1opt")),
                 fmt::arg("q2opt", table(emission.q2opt, "q2opt")), fmt::arg("stamp", stamp));
  std::string second = head + R"(
template std::shared_ptr<const rt::EvaluationPath<double>> rt::emitted_path<g::Traits, double, false>(
    const rt::LatticeVolume<double>&, int, const rt::simd::Kernels*);

namespace {
template <class Tr>
void double_kernels(rt::simd::Kernels& kernels) {
  if constexpr (Tr::kScale == 1) rt::simd::HWY_NAMESPACE::set_kernels_for<Tr, double>(kernels);
}
}  // namespace

void boxgen_filter_double_kernels(rt::simd::Kernels& kernels) { double_kernels<g::Traits>(kernels); }
)";
  return {std::move(first), std::move(second)};
}

using StampFn = const char* (*)();
using CreateFn = rt::FilterSource* (*)(const char*, int (*)());

// The entry's GLSL evaluators (float, double; tables `const` or in a storage block) for the GL
// device (runtime/gl), written beside the shared object: NAME.glsl, NAME_double.glsl,
// NAME_buffered.glsl and NAME_buffered_double.glsl with NAME = spec_KEY.
fs::path glsl_file(const CacheEntry& entry, bool double_precision, bool buffered) {
  return entry.file(buffered ? (double_precision ? "_buffered_double.glsl" : "_buffered.glsl")
                             : (double_precision ? "_double.glsl" : ".glsl"));
}
std::string EntryInfo::*glsl_hash(bool double_precision, bool buffered) {
  return buffered ? (double_precision ? &EntryInfo::glsl_buffered_double_hash
                                      : &EntryInfo::glsl_buffered_hash)
                  : (double_precision ? &EntryInfo::glsl_double_hash : &EntryInfo::glsl_hash);
}

// Why an entry whose object is intact is not complete: emitting its GLSL again repairs it.
constexpr const char* kGlslChanged = "its GLSL evaluator is not the one written";

// A complete entry: its description, and its GLSL evaluators (float, double) as read and checked
// against it.
struct CompleteEntry {
  EntryInfo info;
  std::array<rt::GlslEvaluator, 2> glsl;
};

// The entry when it is complete and this loader's: the .json parses, its stamp is `stamp`, and
// the GLSL files hold what it records (the .so is checked as it is loaded, through the
// descriptor it is loaded from).
std::optional<CompleteEntry> complete_entry(const CacheEntry& entry, const std::string& stamp,
                                            std::string& why) {
  auto info = read_entry(entry);
  if (!info) return why = "no complete entry", std::nullopt;
  if (info->stamp != stamp) return why = "built for another boxgen", std::nullopt;
  CompleteEntry out{*info, {}};
  for (const bool dbl : {false, true}) {
    rt::GlslEvaluator& glsl = out.glsl.at(dbl ? 1 : 0);
    glsl.name = "spec_" + entry.key;
    glsl.block = info->glsl_block;  // the same numbers in both precisions
    for (const bool buffered : {false, true}) {
      auto text = read_entry_file(glsl_file(entry, dbl, buffered));
      if (!text || hash_text(*text) != (*info).*glsl_hash(dbl, buffered))
        return why = kGlslChanged, std::nullopt;
      (buffered ? glsl.buffered : glsl.text) = std::move(*text);
    }
  }
  return out;
}

// The entry's description when its .json is this loader's and its .so is the one it describes.
std::optional<EntryInfo> intact_object(const CacheEntry& entry, const std::string& stamp) {
  auto info = read_entry(entry);
  if (!info || info->stamp != stamp) return std::nullopt;
  const int fd = open_entry_file(entry.file(".so"));
  if (fd < 0) return std::nullopt;
  std::uintmax_t size = 0;
  const auto hash = hash_descriptor(fd, size);
  ::close(fd);
  if (!hash || *hash != info->so_hash || size != info->so_size) return std::nullopt;
  return info;
}

// A compiled filter as the host sees it: the object's FilterSource, and the GLSL evaluators read
// and checked with it (the GL device's, FilterSource::glsl).
class CachedSource final : public rt::FilterSource {
 public:
  CachedSource(std::unique_ptr<const rt::FilterSource> compiled,
               std::array<rt::GlslEvaluator, 2> glsl)
      : compiled_(std::move(compiled)), glsl_(std::move(glsl)) {}
  std::string name() const override { return compiled_->name(); }
  rt::CosetLattice lattice() const override { return compiled_->lattice(); }
  rt::StencilReach reach() const override { return compiled_->reach(); }
  rt::PrefilterTaps prefilter(rt::PrefilterChoice q) const override {
    return compiled_->prefilter(q);
  }
  int approximation_order() const override { return compiled_->approximation_order(); }
  std::shared_ptr<const rt::EvaluationPath<float>> path(
      const rt::LatticeVolume<float>& volume) const override {
    return compiled_->path(volume);
  }
  std::shared_ptr<const rt::EvaluationPath<double>> path(
      const rt::LatticeVolume<double>& volume) const override {
    return compiled_->path(volume);
  }
  std::optional<rt::GlslEvaluator> glsl(bool double_precision) const override {
    return glsl_.at(double_precision ? 1 : 0);
  }

 private:
  std::unique_ptr<const rt::FilterSource> compiled_;
  std::array<rt::GlslEvaluator, 2> glsl_;
};

// The entry's filter, or nothing (with the reason) when it is missing, incomplete, corrupt or
// built for another loader, boxgen or key. The object is opened without following a link,
// hashed and compared with the .json through that descriptor, and loaded from the same
// descriptor (/proc/self/fd/N), so what runs is what was checked. The descriptor stays open for
// the life of the process, as the library stays loaded (the paths it makes may outlive the
// filter): its name is then never reused for another object, which glibc would otherwise hand
// back for the same name without reading the file.
std::shared_ptr<const rt::FilterSource> open_entry(const CacheEntry& entry,
                                                   const std::string& stamp,
                                                   const std::string& name, std::string& why) {
  auto complete = complete_entry(entry, stamp, why);
  if (!complete) return nullptr;
  const EntryInfo& info = complete->info;
  const int fd = open_entry_file(entry.file(".so"));
  std::uintmax_t size = 0;
  const auto hash = fd < 0 ? std::nullopt : hash_descriptor(fd, size);
  if (!hash || size != info.so_size || *hash != info.so_hash) {
    if (fd >= 0) ::close(fd);
    return why = "its shared object is not the one built", nullptr;
  }
  void* handle = ::dlopen(fmt::format("/proc/self/fd/{}", fd).c_str(), RTLD_NOW | RTLD_LOCAL);
  if (!handle) {
    ::close(fd);  // nothing was loaded under its name
    const char* error = ::dlerror();
    return why = error ? error : "dlopen failed", nullptr;
  }
  const auto stamp_fn = reinterpret_cast<StampFn>(::dlsym(handle, "boxgen_filter_stamp"));
  const auto create = reinterpret_cast<CreateFn>(::dlsym(handle, "boxgen_filter_create"));
  if (!stamp_fn || !create || stamp != stamp_fn()) {
    ::dlclose(handle);
    return why = "its stamp is not this boxgen's", nullptr;
  }
  return std::make_shared<CachedSource>(
      std::unique_ptr<const rt::FilterSource>(create(name.c_str(), &rt::batch_threads)),
      std::move(complete->glsl));
}

// Emits the GLSL evaluators into the entry and records their hashes in `info`.
void write_glsl(const CacheEntry& entry, const gen::Derivation& derivation, EntryInfo& info) {
  for (const bool dbl : {false, true}) {
    gen::EmissionRequest request;
    request.name = "spec_" + entry.key;
    request.command =
        fmt::format("the run-time filter \"{}\" --lattice \"{}\"", info.spec, info.rows);
    request.target = gen::EmissionTarget::Glsl;
    request.double_precision = dbl;
    const gen::Emission glsl = gen::emit(derivation, request);
    for (const bool buffered : {false, true}) {
      const std::string& text = buffered ? glsl.glsl_buffered : glsl.files.at(0).text;
      write_entry_file(glsl_file(entry, dbl, buffered), text);
      info.*glsl_hash(dbl, buffered) = hash_text(text);
    }
    info.glsl_block = glsl.glsl_block;  // the same numbers in both precisions
  }
}

void build_entry(const CacheEntry& entry, const gen::BoxSplineSpec& spec, const EntryInfo& info,
                 const Toolchain& toolchain, const CompileOptions& options) {
  const double compile_seconds = compile_time_limit(options);
  Progress progress(options.progress);
  const std::string what = fmt::format("\"{}\" on the {} lattice", info.spec, info.lattice);
  progress.stage(fmt::format("first use of filter {}: deriving", what));
  gen::DerivationOptions d;
  d.max_seconds = options.max_seconds;
  d.max_bytes = options.max_bytes;
  const gen::Derivation derivation = gen::derive(spec, d);
  progress.stage(fmt::format("first use of filter {}: emitting", what));
  const std::string name = "spec_" + entry.key;
  gen::EmissionRequest request;
  request.name = name;
  request.command =
      fmt::format("the run-time filter \"{}\" --lattice \"{}\"", info.spec, info.rows);
  // q1opt and q2opt as `boxgen emit` writes them (their free parameters optimised numerically).
  request.q1opt = frontend::optimised_table(spec, "q1opt");
  request.q2opt = frontend::optimised_table(spec, "q2opt");
  const auto sources = glue_sources(name, gen::emit(derivation, request), info.stamp);
  try {
    write_entry_file(entry.file(".cpp"), sources[0]);
    write_entry_file(entry.file("_double.cpp"), sources[1]);
    progress.stage(fmt::format("first use of filter {}: compiling with {} (cached in {})", what,
                               toolchain.compiler, entry.dir.string()));
    support::PendingOutput so(entry.file(".so"), {}, support::LinkPolicy::replace);
    compile_shared_object(toolchain, {entry.file(".cpp"), entry.file("_double.cpp")},
                          so.temporary(), entry.file(".log"), what, compile_seconds,
                          options.check_interrupt);
    EntryInfo written = info;
    const int fd = open_entry_file(so.temporary());
    const auto hash = fd < 0 ? std::nullopt : hash_descriptor(fd, written.so_size);
    if (fd >= 0) ::close(fd);
    if (!hash) so.abandon("the compiled object cannot be read back");
    written.so_hash = *hash;
    so.commit();
    write_glsl(entry, derivation, written);
    write_entry(entry, written);
  } catch (const support::OutputFileError& e) {
    throw LoadError(fmt::format("cannot write the compiled filter into the cache: {}", e.what()));
  }
}

// The directions as the cache key sees them: the centred box spline (what the loader derives,
// emits and compiles) is the same for any order of the directions and either sign of each, so
// each is taken with its first nonzero entry positive and the list is sorted. The same matrix
// reordered or with a direction negated then loads the entry compiled first.
std::string key_directions(gen::BoxSplineSpec spec) {
  for (gen::IntVec& d : spec.directions) d = gen::sign_canonical(std::move(d));
  std::sort(spec.directions.begin(), spec.directions.end());
  return spec.directions_text();
}

// A SPEC (not a registry name) and its place in the cache.
struct Resolved {
  gen::BoxSplineSpec spec;
  EntryInfo info;
  CacheEntry entry;
  Toolchain toolchain;
};

Resolved resolve(const std::string& spec_or_name, const std::optional<std::string>& lattice,
                 const CompileOptions& options) {
  gen::BoxSplineSpec spec = [&] {
    try {
      return gen::parse_spec(spec_or_name, lattice.value_or(""));
    } catch (const gen::InputError& e) {
      throw LoadError(e.what());
    }
  }();
  if (spec.dimension() != 3)
    throw LoadError(fmt::format(
        "filter \"{}\" is {}-D: volumes are 3-D (boxgen analyzes and emits {}-D splines)",
        spec_or_name.substr(0, 60), spec.dimension(), spec.dimension()));

  Toolchain toolchain = find_toolchain(options);
  EntryInfo info;
  info.spec = spec.directions_text();
  info.lattice = spec.lattice.name();
  info.rows = rows_text(spec.lattice);
  const std::string identity = fmt::format("abi {}\n{}\n{}\n{}\n{}", kAbiVersion, kVersion,
                                           key_directions(spec), info.rows, toolchain.identity());
  // The directory is made, and checked, before anything is read from it or written to it.
  CacheEntry entry{*checked_cache_dir(resolve_cache_dir(options.cache_dir), true),
                   hash_text(identity)};
  check_entry_files(entry);
  info.stamp = entry_stamp(entry.key);
  return {std::move(spec), std::move(info), std::move(entry), std::move(toolchain)};
}

// The SPEC's filter from a complete entry, built under the entry's lock unless one is there.
std::shared_ptr<const rt::FilterSource> ensure_entry(const Resolved& r,
                                                     const CompileOptions& options) {
  const std::string& name = r.info.spec;
  std::string why;
  std::shared_ptr<const rt::FilterSource> filter;
  const auto ready = [&] {
    return (filter = open_entry(r.entry, r.info.stamp, name, why)) != nullptr;
  };
  if (ready()) return filter;
  {
    // One process builds; another one wanting the same filter waits and then loads its result.
    const EntryLock lock(r.entry);
    if (ready()) return filter;
    try {
      auto kept = why == kGlslChanged ? intact_object(r.entry, r.info.stamp) : std::nullopt;
      if (kept) {
        // Only a GLSL file is not what the .json says: emitted again, without a compile.
        gen::DerivationOptions d;
        d.max_seconds = options.max_seconds;
        d.max_bytes = options.max_bytes;
        write_glsl(r.entry, gen::derive(r.spec, d), *kept);
        write_entry(r.entry, *kept);
      } else {
        build_entry(r.entry, r.spec, r.info, r.toolchain, options);
      }
    } catch (const gen::InputError& e) {
      throw LoadError(e.what());
    } catch (const support::OutputFileError& e) {
      throw LoadError(fmt::format("cannot write the compiled filter into the cache: {}", e.what()));
    }
  }
  if (ready()) return filter;
  throw LoadError(fmt::format("the compiled filter {} cannot be loaded: {}",
                              runtime::nrrd_checks::printable(r.entry.file(".so").string()), why));
}

}  // namespace

fs::path cache_directory(const CompileOptions& options) {
  return resolve_cache_dir(options.cache_dir);
}

std::string cache_key_directions(const std::string& spec, const std::string& lattice) {
  try {
    return key_directions(gen::parse_spec(spec, lattice));
  } catch (const gen::InputError& e) {
    throw LoadError(e.what());
  }
}

rt::SplineFilter load_filter(const std::string& spec_or_name, std::optional<std::string> lattice,
                             const CompileOptions& options) {
  if (lattice && lattice->empty()) lattice.reset();
  if (const auto registry = registry_filter(spec_or_name)) {
    if (!lattice) return *registry;
    const rt::CosetLattice given = rt::CosetLattice::parse(*lattice);
    if (rt::same_points(registry->lattice(), given)) return *registry;
    // The registry's own message (boxrecon's contract); the directions on another lattice are a
    // SPEC (boxgen presets lists them).
    throw LoadError(fmt::format("filter {} is for the {} lattice, but --lattice is {}",
                                registry->name(), registry->lattice().name(), given.name()));
  }
  return rt::SplineFilter(ensure_entry(resolve(spec_or_name, lattice, options), options));
}

std::vector<CachedFilter> cached_filters(const CompileOptions& options) {
  std::vector<CachedFilter> out;
  const auto dir = checked_cache_dir(resolve_cache_dir(options.cache_dir), false);
  if (!dir) return out;
  // What the .json says is printed (boxrecon filters): only entries named as the loader names
  // them, and only text a terminal shows as text.
  const auto is_key = [](const std::string& k) {
    return k.size() == 16 && k.find_first_not_of("0123456789abcdef") == std::string::npos;
  };
  const auto plain = [](const std::string& t) {
    return std::all_of(t.begin(), t.end(), [](char c) { return c >= 0x20 && c < 0x7f; });
  };
  std::error_code ec;
  for (fs::directory_iterator it(*dir, ec), end; !ec && it != end; it.increment(ec)) {
    if (it->path().extension() != ".json" || !is_key(it->path().stem().string())) continue;
    const CacheEntry entry{*dir, it->path().stem().string()};
    const auto info = read_entry(entry);
    if (!info || open_entry_file(entry.file(".so")) < 0) continue;
    if (!plain(info->spec) || !plain(info->lattice) || !plain(info->rows)) continue;
    out.push_back({info->spec, info->lattice, info->rows, entry.key, entry.file(".so")});
  }
  std::sort(out.begin(), out.end(), [](const CachedFilter& a, const CachedFilter& b) {
    return std::tie(a.spec, a.rows, a.key) < std::tie(b.spec, b.rows, b.key);
  });
  return out;
}

}  // namespace boxgen::loader
