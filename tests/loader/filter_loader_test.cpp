// The run-time path from a SPEC to a filter (loader/filter_loader.h), for SPECs no preset has:
// the compiled evaluator against the generator's exact rational values (the de Boor-Hoellig
// recurrence, which shares nothing with the emitted code) on delta data, polynomial reproduction
// of the filter's order with q1 (the smallest prefilter), and the cache: a second use loads without
// compiling, a corrupt or stale entry is rebuilt, concurrent first uses both succeed, no compiler
// is one line. Each compile takes seconds: the tests named Slow* (label slow) hold the FCC and
// custom-lattice cases, the truncated object and the stale stamp rebuilt, and the concurrent first
// uses; the fast suite compiles one BCC filter once. qfir:K (docs/design.md §18) is checked
// against the generator's exact weights and for reproduction on the registry and these SPECs.
#include <dlfcn.h>
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <map>
#include <random>
#include <set>
#include <sstream>
#include <thread>
#include <type_traits>

#include "../support/scratch_directory.h"
#include "boxgen/loader_config.h"
#include "generator/approximation_order.h"
#include "generator/interpolation_symbol.h"
#include "generator/prefilter.h"
#include "generator/rational.h"
#include "generator/recurrence.h"
#include "generator/spec.h"
#include "loader/filter_cache.h"
#include "loader/filter_compiler.h"
#include "loader/filter_loader.h"
#include "runtime/prefilter.h"
#include "runtime/reconstruction.h"
#include "runtime/resample.h"
#include "runtime/sampling.h"

namespace boxgen::loader {
namespace {

namespace fs = std::filesystem;
namespace rt = boxgen::runtime;
namespace gen = boxgen::generator;

// Six of M7's seven directions (no preset): a cubic on BCC.
constexpr const char* kBccSpec = "1,1,1; 1,-1,-1; -1,1,-1; -1,-1,1; 2,0,0; 0,2,0";
// The same directions in another order, four of them negated: the same centred spline.
constexpr const char* kBccReordered = "0,-2,0; -1,-1,1; 2,0,0; 1,-1,1; -1,-1,-1; 1,-1,-1";
// Five of fcc6's six directions on FCC.
constexpr const char* kFccSpec = "1,1,0; 1,-1,0; 1,0,1; 1,0,-1; 0,1,1";
// A lattice that is none of the three (rows of G, |det G| = 3), and four of its points.
constexpr const char* kCustomLattice = "1,0,0; 0,1,0; 1,1,3";
constexpr const char* kCustomSpec = "1,0,1; 0,1,1; 1,1,-1; 1,-1,0; 0,0,3";

class LoaderTest : public test::ScratchDirectoryTest {
 protected:
  LoaderTest() : ScratchDirectoryTest("boxgen-loader") {}
  CompileOptions options() const {
    CompileOptions o;
    o.cache_dir = dir_;
    return o;
  }
  // The one entry of the cache (the tests compile one filter each unless they say otherwise).
  fs::path only(const char* extension) const {
    for (const auto& e : fs::directory_iterator(dir_))
      if (e.path().extension() == extension) return e.path();
    return {};
  }
};

// Replaces `target` by a new file holding the first `bytes` bytes of `source` (renamed into
// place, so that the object this process has loaded from `target` stays intact).
void replace_with_prefix(const fs::path& target, const fs::path& source, std::uintmax_t bytes) {
  std::ifstream in(source, std::ios::binary);
  std::string data(bytes, '\0');
  in.read(data.data(), static_cast<std::streamsize>(bytes));
  const fs::path temporary = target.string() + ".new";
  std::ofstream(temporary, std::ios::binary)
      .write(data.data(), static_cast<std::streamsize>(bytes));
  fs::rename(temporary, target);
}

// The cache's hash of a file's bytes.
std::string hash_of(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream text;
  text << in.rdbuf();
  return hash_text(text.str());
}

// Replaces `target` by a new file holding the first `bytes` bytes of `text` (renamed into place).
void replace_with_prefix(const fs::path& target, const std::string& text, std::size_t bytes) {
  const fs::path temporary = target.string() + ".new";
  std::ofstream(temporary, std::ios::binary)
      .write(text.data(), static_cast<std::streamsize>(bytes));
  fs::rename(temporary, target);
}

// A generic rational near 0 (large prime denominators keep it off every knot plane).
gen::Rational generic(std::mt19937_64& rng, int range, long denominator) {
  std::uniform_int_distribution<long> u(-range * denominator, range * denominator);
  return gen::Rational(u(rng)) / gen::Rational(denominator);
}

// The filter on a volume that is 0 except for a 1 at lattice point j: s(x) = M(x - j), which the
// recurrence gives exactly as |det G| M^c_Xi(x - j). Values, at 40 generic points around j.
// T: the precision of the volume and the path (a compiled filter builds each in a translation
// unit of its own); float's tolerance is its rounding of a few hundred operations.
template <class T = double>
void expect_exact_on_delta(const rt::SplineFilter& f, const std::string& spec,
                           const std::string& lattice) {
  const double tolerance = std::is_same_v<T, float> ? 2e-5 : 1e-13;
  const gen::BoxSplineSpec s = gen::parse_spec(spec, lattice);
  const rt::CosetLattice& l = f.lattice();
  const int n = 12;
  rt::LatticeVolume<T> v(l, {n, n, n}, 1.0, {0, 0, 0});
  const rt::Offset& o = l.offsets()[0];
  const rt::LatticePoint j{o[0] + l.period() * n / 2, o[1] + l.period() * n / 2,
                           o[2] + l.period() * n / 2};
  v.samples()[static_cast<std::size_t>(v.storage_offset(j))] = 1;
  const rt::Reconstructor<T> r(v, f);
  std::mt19937_64 rng(7);
  const long denominators[3] = {1009, 1013, 1019};
  int checked = 0;
  for (int t = 0; t < 40; ++t) {
    gen::RatVec d(3);
    for (int a = 0; a < 3; ++a) d[a] = generic(rng, 2, denominators[a]);
    if (!gen::is_generic_point(s.directions, d)) continue;
    const double exact = gen::to_double(gen::Rational(s.lattice.det_abs()) *
                                        gen::box_spline_centred_recurrence(s.directions, d));
    const rt::Vec3 x{static_cast<double>(j[0]) + gen::to_double(d[0]),
                     static_cast<double>(j[1]) + gen::to_double(d[1]),
                     static_cast<double>(j[2]) + gen::to_double(d[2])};
    EXPECT_NEAR(r.value(x), exact, tolerance)
        << spec << " at offset " << gen::to_double(d[0]) << " " << gen::to_double(d[1]) << " "
        << gen::to_double(d[2]);
    std::vector<rt::Vec3> points{x};
    std::vector<T> values(1);
    r.evaluate(points, values);  // the batch path (SIMD where the filter has kernels)
    EXPECT_NEAR(values[0], exact, tolerance);
    ++checked;
  }
  EXPECT_GT(checked, 30);
}

// qfir:K (docs/design.md §18) as the runtime solves it, in double from the evaluator's lattice
// values, against the generator's exact weights from the pieces: the least K that has one and the
// next two.
void expect_fir_taps_exact(const rt::SplineFilter& f, const std::string& spec,
                           const std::string& lattice) {
  const gen::BoxSplineSpec s = gen::parse_spec(spec, lattice);
  const auto samples = gen::lattice_samples(s);
  const int least = gen::quasi_interpolation_shells(s, 1).back();
  for (int k = least; k <= least + 2; ++k) {
    std::map<std::vector<std::int64_t>, double> exact;
    double largest = 0;
    for (const auto& w : gen::derive_fir_prefilter(s, k, samples).weights) {
      exact[w.offset] = gen::to_double(w.weight);
      largest = std::max(largest, std::abs(gen::to_double(w.weight)));
    }
    const rt::PrefilterTaps taps = f.prefilter(rt::PrefilterChoice::qfir(k));
    ASSERT_EQ(taps.size(), exact.size()) << spec << " qfir:" << k;
    for (const auto& [o, w] : taps) {
      const std::vector<std::int64_t> at{o[0], o[1], o[2]};
      ASSERT_TRUE(exact.count(at)) << spec << " qfir:" << k;
      EXPECT_NEAR(w, exact.at(at), 1e-12 * largest) << spec << " qfir:" << k;
    }
  }
}

// q1 and qfir:K (the least K and the next) reproduce every polynomial of degree < the filter's
// order: a product of linear factors of that degree, sampled over [-1,1]^3, prefiltered and
// evaluated at random points there.
void expect_reproduction(const rt::SplineFilter& f, const std::string& spec,
                         const std::string& lattice) {
  const gen::BoxSplineSpec s = gen::parse_spec(spec, lattice);
  const int order = gen::approximation_order(s.directions, 3);
  ASSERT_EQ(f.approximation_order(), order);
  ASSERT_GE(order, 2);
  const auto poly = [order](const rt::Vec3& p) {
    double y = 1;
    for (int k = 0; k < order - 1; ++k) y *= 0.3 + p[k % 3] - 0.5 * p[(k + 1) % 3];
    return y;
  };
  const int least = gen::quasi_interpolation_shells(s, 1).back();
  for (const rt::PrefilterChoice q : {rt::PrefilterChoice::Q1, rt::PrefilterChoice::qfir(least),
                                      rt::PrefilterChoice::qfir(least + 1)}) {
    rt::LatticeVolume<double> v = rt::sample_lattice<double>(
        poly, rt::cube_lattice_grid(f.lattice(), 9, f.required_margin(q)));
    v = rt::prefilter(v, f.prefilter(q));
    const rt::Reconstructor<double> r(v, f);
    std::mt19937_64 rng(3);
    std::uniform_real_distribution<double> u(-1, 1);
    for (int t = 0; t < 200; ++t) {
      const rt::Vec3 p{u(rng), u(rng), u(rng)};
      EXPECT_NEAR(r.value(p), poly(p), 1e-10)
          << spec << " " << q.text() << " at " << p[0] << " " << p[1] << " " << p[2];
    }
  }
}

TEST(FirPrefilter, EveryRegistryFiltersTapsAreTheGeneratorsExactWeights) {
  for (int i = 0; i < rt::SplineFilter::count(); ++i) {
    const rt::SplineFilter f = rt::SplineFilter::at(i);  // registry names are presets
    expect_fir_taps_exact(f, f.name(), "");
    expect_reproduction(f, f.name(), "");
  }
}

// The cache key's directions: one text for every order and sign of the same directions (the
// centred spline is the same), another for a different matrix. Written out by hand: each
// direction with its first nonzero entry positive, sorted as integer vectors.
TEST(CacheKeyDirections, InvariantUnderOrderAndSignOnly) {
  const std::string canonical = "0,2,0; 1,-1,-1; 1,-1,1; 1,1,-1; 1,1,1; 2,0,0";
  EXPECT_EQ(cache_key_directions(kBccSpec, "bcc"), canonical);
  EXPECT_EQ(cache_key_directions(kBccReordered, "bcc"), canonical);
  EXPECT_EQ(cache_key_directions("0,2,0; 2,0,0; 1,1,1; -1,-1,1; -1,1,-1; 1,-1,-1", "bcc"),
            canonical);
  // Not the same spline: (1,1,1) twice instead of (1,1,1) and (-1,-1,1); (0,0,2) for (0,2,0).
  EXPECT_NE(cache_key_directions("1,1,1; 1,-1,-1; -1,1,-1; 1,1,1; 2,0,0; 0,2,0", "bcc"), canonical);
  EXPECT_NE(cache_key_directions("1,1,1; 1,-1,-1; -1,1,-1; -1,-1,1; 2,0,0; 0,0,2", "bcc"),
            canonical);
  // A repeated direction stays repeated; its sign does not matter either.
  EXPECT_EQ(cache_key_directions("1,0,0; -1,0,0; 0,1,0; 0,0,-1"), "0,0,1; 0,1,0; 1,0,0; 1,0,0");
  EXPECT_THROW((void)cache_key_directions("1,0; 0,x"), LoadError);
}

TEST_F(LoaderTest, RegistryNamesAreTheRegistrysFilters) {
  const rt::SplineFilter m7 = load_filter("m7", std::nullopt, options());
  EXPECT_EQ(m7, rt::SplineFilter::parse("m7"));
  EXPECT_EQ(load_filter("fcc6", "fcc", options()), rt::SplineFilter::parse("fcc6"));
  try {
    load_filter("fcc6", "bcc", options());
    FAIL() << "fcc6 on bcc was accepted";
  } catch (const LoadError& e) {
    EXPECT_NE(
        std::string(e.what()).find("filter fcc6 is for the fcc lattice, but --lattice is bcc"),
        std::string::npos)
        << e.what();
  }
  EXPECT_TRUE(fs::is_empty(dir_));  // nothing compiled
}

TEST_F(LoaderTest, RefusesWhatCannotBeAFilterInOneLine) {
  for (const auto& [spec, lattice, words] :
       std::vector<std::tuple<std::string, std::string, std::string>>{
           {"zp", "", "2-D"},
           {"1,1,1; 1,0,0", "cartesian", "span"},
           {"1,0,0; 0,1,0; 0,0,1", "bcc", "lattice"},
           {"nonsense", "", "nonsense"}}) {
    try {
      load_filter(spec, lattice, options());
      ADD_FAILURE() << spec << " was accepted";
    } catch (const LoadError& e) {
      const std::string what = e.what();
      EXPECT_EQ(what.find('\n'), std::string::npos) << what;
      EXPECT_NE(what.find(words), std::string::npos) << spec << ": " << what;
    }
  }
}

TEST_F(LoaderTest, NoCompilerSaysWhatToInstall) {
  CompileOptions o = options();
  o.compiler = (dir_ / "no-such-compiler").string();
  try {
    load_filter(kBccSpec, "bcc", o);
    FAIL() << "compiled without a compiler";
  } catch (const LoadError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("install g++"), std::string::npos) << what;
    EXPECT_EQ(what.find('\n'), std::string::npos) << what;
  }
}

// The build's precompiled runtime/compiled_filter.h (loader/CMakeLists.txt): the loader puts its
// folder first for the build's own compiler only, and that compiler takes it with the loader's
// flags (-H marks a precompiled header it uses with "!"), so the two cannot drift apart unseen.
TEST_F(LoaderTest, PrecompiledEngineHeaderIsTakenWithTheLoadersFlags) {
  if (std::string_view(config::kPrecompiledDir).empty()) GTEST_SKIP() << "not built with GCC";
  const Toolchain t = find_toolchain(options());
  ASSERT_EQ(t.precompiled_dir, fs::path(config::kPrecompiledDir));
  const fs::path source = dir_ / "first.cpp";
  std::ofstream(source) << "// a comment first\n#include <runtime/compiled_filter.h>\nint x;\n";
  std::string command = "'" + t.compiler + "' '-I" + t.precompiled_dir.string() + "'";
  for (const std::string& f : t.flags) command += " '" + f + "'";
  command += " -H -fsyntax-only '" + source.string() + "' 2>&1";
  std::string out;
  if (FILE* pipe = ::popen(command.c_str(), "r")) {
    char buffer[4096];
    for (std::size_t n; (n = std::fread(buffer, 1, sizeof buffer, pipe)) > 0;)
      out.append(buffer, n);
    EXPECT_EQ(::pclose(pipe), 0) << out;
  }
  const std::string used =
      "! " + (t.precompiled_dir / "runtime" / "compiled_filter.h.gch").string() + "\n";
  EXPECT_EQ(out.rfind(used, 0), 0u) << out.substr(0, 2000);
  // Another compiler (here a script in front of the same one) gets none.
  const fs::path script = dir_ / "cxx";
  std::ofstream(script) << "#!/bin/sh\nexec '" << t.compiler << "' \"$@\"\n";
  fs::permissions(script, fs::perms(0755));
  CompileOptions o = options();
  o.compiler = script.string();
  EXPECT_TRUE(find_toolchain(o).precompiled_dir.empty());
}

// A precompiled header the compiler cannot take (here not one at all; equally one of another
// compiler, target or macros) is passed over: the compile reads the header itself, and the object
// holds what the header declares.
TEST_F(LoaderTest, UnusablePrecompiledHeaderIsPassedOver) {
  Toolchain t = find_toolchain(options());
  t.precompiled_dir = dir_ / "precompiled";
  fs::create_directories(t.precompiled_dir / "runtime");
  std::ofstream(t.precompiled_dir / "runtime" / "compiled_filter.h.gch") << "not one\n";
  const fs::path source = dir_ / "probe.cpp", object = dir_ / "probe.so";
  std::ofstream(source) << "#include <runtime/compiled_filter.h>\n"
                           "extern \"C\" __attribute__((visibility(\"default\"))) int probe() {\n"
                           "  return static_cast<int>(boxgen::runtime::StencilPolicy::kLattice);\n"
                           "}\n";
  compile_shared_object(t, {source}, object, dir_ / "probe.log", "the probe", 600);
  void* handle = ::dlopen(object.c_str(), RTLD_NOW | RTLD_LOCAL);
  ASSERT_NE(handle, nullptr) << ::dlerror();
  auto* probe = reinterpret_cast<int (*)()>(::dlsym(handle, "probe"));
  ASSERT_NE(probe, nullptr);
  EXPECT_EQ(probe(), 2);
  ::dlclose(handle);
}

// One BCC filter: exact, reproduces with q1, then loaded from the cache without a compile.
TEST_F(LoaderTest, BccSpecIsExactReproducesAndIsCached) {
  const rt::SplineFilter f = load_filter(kBccSpec, "bcc", options());
  EXPECT_EQ(f.name(), kBccSpec);
  EXPECT_EQ(f.lattice(), rt::CosetLattice::bcc());
  EXPECT_EQ(f.registry_index(), -1);
  expect_exact_on_delta(f, kBccSpec, "bcc");
  expect_reproduction(f, kBccSpec, "bcc");
  expect_fir_taps_exact(f, kBccSpec, "bcc");

  const fs::path so = only(".so");
  ASSERT_FALSE(so.empty());
  const auto size = fs::file_size(so);
  const auto time = fs::last_write_time(so);
  ASSERT_GT(size, 0U);
  // Second use: the same file, untouched (no compile), the same values.
  const rt::SplineFilter again = load_filter(kBccSpec, "bcc", options());
  EXPECT_EQ(fs::last_write_time(so), time);
  EXPECT_EQ(fs::file_size(so), size);
  expect_exact_on_delta(again, kBccSpec, "bcc");
  expect_exact_on_delta<float>(again, kBccSpec, "bcc");
  // The sources (the float half with the glue, the double half) are written for the compile and
  // for the curious, and never read back: edited ones change nothing that is loaded.
  const fs::path double_half = fs::path(so).replace_extension().string() + "_double.cpp";
  ASSERT_TRUE(fs::is_regular_file(double_half));
  ASSERT_TRUE(fs::is_regular_file(fs::path(so).replace_extension(".cpp")));
  for (const fs::path& source : {double_half, fs::path(so).replace_extension(".cpp")})
    replace_with_prefix(source, std::string("#error planted\n"), 15);
  const rt::SplineFilter edited_sources = load_filter(kBccSpec, "bcc", options());
  EXPECT_EQ(fs::last_write_time(so), time);
  expect_exact_on_delta(edited_sources, kBccSpec, "bcc");
  // Reordered and with directions negated: the same entry, loaded without a compile,
  // named as given, and exact against the recurrence of the directions as given.
  const rt::SplineFilter reordered = load_filter(kBccReordered, "bcc", options());
  EXPECT_EQ(fs::last_write_time(so), time);
  EXPECT_EQ(reordered.name(), kBccReordered);
  expect_exact_on_delta(reordered, kBccReordered, "bcc");
  ASSERT_EQ(cached_filters(options()).size(), 1U);
  EXPECT_EQ(cached_filters(options())[0].spec, kBccSpec);
  EXPECT_EQ(cached_filters(options())[0].lattice, "bcc");

  // The filter carries its GLSL evaluators (the GL device's), read and checked against the .json
  // as the object is: one edited constant, or another evaluator with its prefix renamed, is
  // emitted again (without a compile), never used.
  const auto glsl_of = [&](bool double_precision) {
    const auto glsl = load_filter(kBccSpec, "bcc", options()).source().glsl(double_precision);
    EXPECT_TRUE(glsl.has_value());
    return glsl.value_or(rt::GlslEvaluator{});
  };
  const rt::GlslEvaluator glsl = glsl_of(false);
  const fs::path glsl_path = fs::path(so).replace_extension(".glsl");
  ASSERT_EQ(hash_of(glsl_path), hash_text(glsl.text));
  EXPECT_EQ(glsl.name, "spec_" + fs::path(so).stem().string());
  EXPECT_FALSE(glsl.buffered.empty());
  EXPECT_FALSE(glsl.block.empty());
  const rt::GlslEvaluator other = glsl_of(true);
  EXPECT_EQ(hash_of(fs::path(so).replace_extension().string() + "_double.glsl"),
            hash_text(other.text));
  EXPECT_EQ(other.name, glsl.name);
  const std::size_t digit = glsl.text.find_first_of("123456789", glsl.text.find("const"));
  ASSERT_NE(digit, std::string::npos);
  std::string edited = glsl.text;
  edited[digit] = edited[digit] == '9' ? '8' : static_cast<char>(edited[digit] + 1);
  std::string renamed = other.text;
  for (std::size_t at = 0; (at = renamed.find(glsl.name, at)) != std::string::npos; ++at)
    renamed.insert(at + glsl.name.size(), "x");
  for (const std::string& planted : {edited, renamed}) {
    replace_with_prefix(glsl_path, planted, planted.size());
    EXPECT_EQ(glsl_of(false).text, glsl.text);
    EXPECT_EQ(hash_of(glsl_path), hash_text(glsl.text));
  }
  // A filter loaded before its file was planted keeps the text that was checked.
  const rt::SplineFilter loaded = load_filter(kBccSpec, "bcc", options());
  replace_with_prefix(glsl_path, edited, edited.size());
  EXPECT_EQ(loaded.source().glsl(false)->text, glsl.text);
  EXPECT_EQ(glsl_of(false).text, glsl.text);
  EXPECT_EQ(fs::last_write_time(so), time);  // not compiled again
}

// A truncated object (a crash mid-copy, a full disk) is never loaded: it is rebuilt.
TEST_F(LoaderTest, SlowTruncatedObjectIsRebuilt) {
  (void)load_filter(kBccSpec, "bcc", options());
  const fs::path so = only(".so");
  const auto size = fs::file_size(so);
  // Put in place as another program would (a new file renamed over it): truncating the file in
  // place would pull the pages from under this process, which has the object mapped.
  replace_with_prefix(so, so, size / 2);
  // The rebuild writes its sources again rather than compiling what it finds (here a double
  // half that cannot compile).
  const fs::path double_half = fs::path(so).replace_extension().string() + "_double.cpp";
  replace_with_prefix(double_half, std::string("#error planted\n"), 15);
  const rt::SplineFilter rebuilt = load_filter(kBccSpec, "bcc", options());
  EXPECT_EQ(fs::file_size(so), size);
  expect_exact_on_delta(rebuilt, kBccSpec, "bcc");
  expect_exact_on_delta<float>(rebuilt, kBccSpec, "bcc");
}

TEST_F(LoaderTest, SlowFccSpecIsExactAndReproduces) {
  const rt::SplineFilter f = load_filter(kFccSpec, "fcc", options());
  EXPECT_EQ(f.lattice(), rt::CosetLattice::fcc());
  expect_exact_on_delta(f, kFccSpec, "fcc");
  expect_reproduction(f, kFccSpec, "fcc");
  expect_fir_taps_exact(f, kFccSpec, "fcc");
}

TEST_F(LoaderTest, SlowCustomLatticeSpecIsExactAndReproduces) {
  const rt::SplineFilter f = load_filter(kCustomSpec, kCustomLattice, options());
  EXPECT_EQ(f.lattice().name(), "custom");
  expect_exact_on_delta(f, kCustomSpec, kCustomLattice);
  expect_reproduction(f, kCustomSpec, kCustomLattice);
}

// An entry whose object is intact but was built for another entry (its stamp, read through the
// exported boxgen_filter_stamp(), names another key): rebuilt, never trusted.
TEST_F(LoaderTest, SlowStaleStampIsRebuilt) {
  (void)load_filter(kFccSpec, "fcc", options());
  const fs::path fcc_so = only(".so"), fcc_json = only(".json");
  const fs::path other = dir_ / "other";
  fs::create_directories(other);
  CompileOptions o = options();
  o.cache_dir = other;
  (void)load_filter(kBccSpec, "bcc", o);
  fs::path bcc_so, bcc_json;
  for (const auto& e : fs::directory_iterator(other)) {
    if (e.path().extension() == ".so") bcc_so = e.path();
    if (e.path().extension() == ".json") bcc_json = e.path();
  }
  // The BCC entry's .so under the FCC entry's name, its description made to match the file.
  replace_with_prefix(fcc_so, bcc_so, fs::file_size(bcc_so));
  const CacheEntry entry{dir_, fcc_so.stem().string()};
  EntryInfo info = read_entry(entry).value();
  info.so_size = fs::file_size(fcc_so);
  info.so_hash = hash_of(fcc_so);
  write_entry(entry, info);
  const rt::SplineFilter f = load_filter(kFccSpec, "fcc", options());
  EXPECT_EQ(f.lattice(), rt::CosetLattice::fcc());
  EXPECT_NE(hash_of(fcc_so), hash_of(bcc_so));
  expect_exact_on_delta(f, kFccSpec, "fcc");
}

// Two first uses at once (threads here; the entry lock is a file lock, so processes alike): both
// get the filter, one entry results (with the GL device's two GLSL files), no temporary is left.
TEST_F(LoaderTest, SlowConcurrentFirstUsesBothSucceed) {
  std::optional<rt::SplineFilter> a, b;
  std::string error_a, error_b;
  const auto use = [&](std::optional<rt::SplineFilter>& out, std::string& error) {
    try {
      out = load_filter(kBccSpec, "bcc", options());
    } catch (const std::exception& e) {
      error = e.what();
    }
  };
  std::thread first(use, std::ref(a), std::ref(error_a));
  std::thread second(use, std::ref(b), std::ref(error_b));
  first.join();
  second.join();
  ASSERT_TRUE(a && b) << error_a << " / " << error_b;
  expect_exact_on_delta(*a, kBccSpec, "bcc");
  expect_exact_on_delta(*b, kBccSpec, "bcc");
  std::multiset<std::string> endings;  // of the one entry's files: KEY (hex digits) + ending
  for (const auto& e : fs::directory_iterator(dir_)) {
    const std::string name = e.path().filename().string();
    EXPECT_EQ(name.find(".tmp-"), std::string::npos) << e.path();
    endings.insert(name.substr(std::min(name.size(), name.find_first_of("._"))));
  }
  EXPECT_EQ(endings, (std::multiset<std::string>{".so", ".cpp", "_double.cpp", ".json", ".lock",
                                                 ".glsl", "_double.glsl", "_buffered.glsl",
                                                 "_buffered_double.glsl"}));
}

}  // namespace
}  // namespace boxgen::loader
