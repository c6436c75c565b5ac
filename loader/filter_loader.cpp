#include "loader/filter_loader.h"

#include <dlfcn.h>
#include <unistd.h>

#include <fmt/format.h>
#include <atomic>
#include <chrono>
#include <cstdio>
#include <fstream>
#include <sstream>

#include "boxgen/version.h"
#include "generator/derivation.h"
#include "generator/emitter.h"
#include "generator/error.h"
#include "generator/spec.h"
#include "loader/filter_cache.h"
#include "loader/filter_compiler.h"
#include "runtime/batch_threads.h"
#include "support/output_file.h"

namespace boxgen::loader {

namespace fs = std::filesystem;
namespace rt = boxgen::runtime;
namespace gen = boxgen::generator;

namespace {

// The version of the interface between this loader and a compiled filter: the two extern "C"
// functions of glue_source() and the runtime types they pass (FilterSource, EvaluationPath,
// LatticeVolume). Raise it whenever one of them changes.
constexpr int kAbiVersion = 1;

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

std::string strip_pragma_once(std::string text) {
  const std::string pragma = "#pragma once\n";
  if (const auto at = text.find(pragma); at != std::string::npos) text.erase(at, pragma.size());
  return text;
}

// The shared object's one source: the emitted evaluator and prefilters, and the two exported
// functions. boxgen_filter_stamp() says which loader, boxgen and entry it was built for;
// boxgen_filter_create() returns the filter as a FilterSource of the runtime's engine, whose
// batch paths follow the host's thread cap (the object has its own copy of the runtime's
// functions, so the cap is asked from the host before each batch).
std::string glue_source(const std::string& name, const std::vector<gen::EmittedFile>& files,
                        const std::string& stamp) {
  const std::string& prefilters = files.at(1).text;
  const auto table = [&](const char* q) {
    return prefilters.find(fmt::format("PrefilterTap {}[]", q)) != std::string::npos
               ? fmt::format("rt::prefilter_from(g::{})", q)
               : std::string("rt::PrefilterTaps{}");
  };
  return fmt::format(
      R"(// A run-time filter of boxgen (loader/filter_loader.cpp): do not edit, it is rebuilt.
#include <memory>
#include <span>
#include <string>

// One instruction set, this machine's (-march=native): no dynamic dispatch inside the object.
#define HWY_COMPILE_ONLY_STATIC 1
#include <hwy/highway.h>

#include "runtime/batch_threads.h"
#include "runtime/emitted_filter.h"

{evaluator}
{prefilters}
#include "runtime/simd_kernels-inl.h"

namespace {{
namespace g = boxgen::generated::{name};
namespace rt = boxgen::runtime;
using HostThreads = int (*)();

// The SIMD kernels of this filter for the instruction set it is compiled for (-march=native);
// none for a scaled pair, which the kernels do not handle (the scalar path serves it).
template <class Tr>
const rt::simd::Kernels* own_kernels() {{
  if constexpr (Tr::kScale == 1) {{
    static const rt::simd::Kernels kernels = rt::simd::HWY_NAMESPACE::kernels_for<Tr>();
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
      : filter_({q1}, {q2}, g::kApproximationOrder, -1, own_kernels<g::Traits>()),
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
  rt::EmittedFilter<g::Traits> filter_;
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
      fmt::arg("evaluator", strip_pragma_once(files.at(0).text)),
      fmt::arg("prefilters", strip_pragma_once(prefilters)), fmt::arg("name", name),
      fmt::arg("q1", table("q1")), fmt::arg("q2", table("q2")), fmt::arg("stamp", stamp));
}

// dlopen of the entry's object through a name of its own (a hard link removed again at once):
// glibc hands back an object already loaded under the same name without looking at the file, so
// an entry rebuilt in this process would otherwise still load as the old object. The same file
// loaded twice is still recognised (glibc compares device and inode) and mapped once.
void* load_library(const fs::path& so) {
  static std::atomic<int> counter{0};
  const fs::path link = so.parent_path() / fmt::format(".{}.load-{}-{}", so.filename().string(),
                                                       ::getpid(), counter++);
  std::error_code ec;
  fs::create_hard_link(so, link, ec);
  void* handle = ::dlopen((ec ? so : link).c_str(), RTLD_NOW | RTLD_LOCAL);
  if (!ec) fs::remove(link, ec);
  return handle;
}

using StampFn = const char* (*)();
using CreateFn = rt::FilterSource* (*)(const char*, int (*)());

// The entry's filter, or nothing (with the reason) when it is missing, incomplete, corrupt or
// built for another loader, boxgen or key. The library stays loaded for the life of the process:
// the paths it makes may outlive the filter.
std::shared_ptr<const rt::FilterSource> open_entry(const CacheEntry& entry,
                                                   const std::string& stamp,
                                                   const std::string& name, std::string& why) {
  const auto info = read_entry(entry);
  if (!info) return why = "no complete entry", nullptr;
  if (info->stamp != stamp) return why = "built for another boxgen", nullptr;
  if (!entry_intact(entry, *info)) return why = "its shared object is not the one built", nullptr;
  void* handle = load_library(entry.file(".so"));
  if (!handle) {
    const char* error = ::dlerror();
    return why = error ? error : "dlopen failed", nullptr;
  }
  const auto stamp_fn = reinterpret_cast<StampFn>(::dlsym(handle, "boxgen_filter_stamp"));
  const auto create = reinterpret_cast<CreateFn>(::dlsym(handle, "boxgen_filter_create"));
  if (!stamp_fn || !create || stamp != stamp_fn()) {
    ::dlclose(handle);
    return why = "its stamp is not this boxgen's", nullptr;
  }
  return std::shared_ptr<const rt::FilterSource>(create(name.c_str(), &rt::batch_threads));
}

// The entry's GLSL evaluators (float, double) for the GL device (runtime/gl), written beside the
// shared object: NAME.glsl and NAME_double.glsl with NAME = spec_KEY.
fs::path glsl_file(const CacheEntry& entry, bool double_precision) {
  return entry.file(double_precision ? "_double.glsl" : ".glsl");
}
void write_glsl(const CacheEntry& entry, const gen::Derivation& derivation, const EntryInfo& info) {
  for (const bool dbl : {false, true}) {
    gen::EmissionRequest request;
    request.name = "spec_" + entry.key;
    request.command =
        fmt::format("the run-time filter \"{}\" --lattice \"{}\"", info.spec, info.rows);
    request.target = gen::EmissionTarget::Glsl;
    request.double_precision = dbl;
    const std::string text = gen::emit(derivation, request).at(0).text;
    support::write_output_file(glsl_file(entry, dbl), [&](std::FILE* f) {
      return std::fwrite(text.data(), 1, text.size(), f) == text.size();
    });
  }
}

void build_entry(const CacheEntry& entry, const gen::BoxSplineSpec& spec, const EntryInfo& info,
                 const Toolchain& toolchain, const CompileOptions& options) {
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
  const auto files = gen::emit(derivation, request);
  const std::string source = glue_source(name, files, info.stamp);
  try {
    support::write_output_file(entry.file(".cpp"), [&](std::FILE* f) {
      return std::fwrite(source.data(), 1, source.size(), f) == source.size();
    });
    progress.stage(fmt::format("first use of filter {}: compiling with {} (cached in {})", what,
                               toolchain.compiler, entry.dir.string()));
    support::PendingOutput so(entry.file(".so"));
    compile_shared_object(toolchain, entry.file(".cpp"), so.temporary(), entry.file(".log"), what);
    so.commit();
    write_glsl(entry, derivation, info);
    EntryInfo written = info;
    written.so_size = fs::file_size(entry.file(".so"));
    written.so_hash = hash_file(entry.file(".so")).value_or("");
    write_entry(entry, written);
  } catch (const support::OutputFileError& e) {
    throw LoadError(fmt::format("cannot write the compiled filter into the cache: {}", e.what()));
  }
}

// A SPEC (not a registry name) and its place in the cache: load_filter and load_glsl share it.
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
                                           info.spec, info.rows, toolchain.identity());
  CacheEntry entry{resolve_cache_dir(options.cache_dir), hash_text(identity)};
  info.stamp =
      fmt::format("boxgen-filter abi {}; boxgen {}; key {}", kAbiVersion, kVersion, entry.key);
  return {std::move(spec), std::move(info), std::move(entry), std::move(toolchain)};
}

}  // namespace

fs::path cache_directory(const CompileOptions& options) {
  return resolve_cache_dir(options.cache_dir);
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
  const Resolved r = resolve(spec_or_name, lattice, options);
  const gen::BoxSplineSpec& spec = r.spec;
  const EntryInfo& info = r.info;
  const CacheEntry& entry = r.entry;
  const Toolchain& toolchain = r.toolchain;
  std::error_code ec;
  fs::create_directories(entry.dir, ec);
  if (ec)
    throw LoadError(
        fmt::format("cannot create the filter cache {}: {}", entry.dir.string(), ec.message()));
  const std::string name = info.spec;
  std::string why;
  if (auto source = open_entry(entry, info.stamp, name, why)) return rt::SplineFilter(source);
  {
    // One process builds; another one wanting the same filter waits and then loads its result.
    const EntryLock lock(entry);
    if (auto source = open_entry(entry, info.stamp, name, why)) return rt::SplineFilter(source);
    try {
      build_entry(entry, spec, info, toolchain, options);
    } catch (const gen::InputError& e) {
      throw LoadError(e.what());
    }
  }
  if (auto source = open_entry(entry, info.stamp, name, why)) return rt::SplineFilter(source);
  throw LoadError(
      fmt::format("the compiled filter {} cannot be loaded: {}", entry.file(".so").string(), why));
}

EmittedGlsl load_glsl(const std::string& spec, std::optional<std::string> lattice,
                      bool double_precision, const CompileOptions& options) {
  if (lattice && lattice->empty()) lattice.reset();
  const Resolved r = resolve(spec, lattice, options);
  const fs::path file = glsl_file(r.entry, double_precision);
  std::error_code ec;
  if (!fs::exists(file, ec)) {  // an entry built before the GL device: derive it again
    fs::create_directories(r.entry.dir, ec);
    const EntryLock lock(r.entry);
    gen::DerivationOptions d;
    d.max_seconds = options.max_seconds;
    d.max_bytes = options.max_bytes;
    try {
      write_glsl(r.entry, gen::derive(r.spec, d), r.info);
    } catch (const gen::InputError& e) {
      throw LoadError(e.what());
    } catch (const support::OutputFileError& e) {
      throw LoadError(fmt::format("cannot write the GLSL evaluator into the cache: {}", e.what()));
    }
  }
  std::ifstream in(file);
  std::stringstream text;
  text << in.rdbuf();
  if (!in) throw LoadError(fmt::format("cannot read the GLSL evaluator {}", file.string()));
  return {"spec_" + r.entry.key, text.str()};
}

std::vector<CachedFilter> cached_filters(const CompileOptions& options) {
  std::vector<CachedFilter> out;
  std::error_code ec;
  const fs::path dir = resolve_cache_dir(options.cache_dir);
  for (fs::directory_iterator it(dir, ec), end; !ec && it != end; it.increment(ec)) {
    if (it->path().extension() != ".json") continue;
    const CacheEntry entry{dir, it->path().stem().string()};
    const auto info = read_entry(entry);
    if (!info || !fs::exists(entry.file(".so"), ec)) continue;
    out.push_back({info->spec, info->lattice, info->rows, entry.key, entry.file(".so")});
  }
  std::sort(out.begin(), out.end(), [](const CachedFilter& a, const CachedFilter& b) {
    return std::tie(a.spec, a.rows, a.key) < std::tie(b.spec, b.rows, b.key);
  });
  return out;
}

}  // namespace boxgen::loader
