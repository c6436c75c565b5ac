// The filter cache as an attacker and a broken compiler see it (loader/filter_cache.h,
// docs/runtime.md "The cache"): a cache others can write (or whose parent they can write) is
// refused before anything is read or loaded from it, so code planted there never runs; an entry's
// file that is a link, or not the user's, or writable by others, is refused and nothing is
// written through it; a compiler that writes nothing, hangs (in its compile or in `--version`)
// or talks without end is stopped, and its log is bounded. None of these tests compiles a filter:
// the compilers are shell scripts the test writes, and the planted object is compiled from a
// few lines of C by the system's cc.
#include <gtest/gtest.h>
#include <sys/stat.h>
#include <unistd.h>

#include <chrono>
#include <csignal>
#include <cstdlib>
#include <fstream>
#include <sstream>

#include "../support/scratch_directory.h"
#include "loader/filter_cache.h"
#include "loader/filter_compiler.h"
#include "loader/filter_loader.h"
#include "support/output_file.h"

namespace boxgen::loader {
namespace {

namespace fs = std::filesystem;

constexpr const char* kSpec = "1,1,1; 1,-1,-1; -1,1,-1; -1,-1,1; 2,0,0; 0,2,0";

std::string read_text(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

void write_text(const fs::path& path, const std::string& text, fs::perms perms = fs::perms(0644)) {
  std::ofstream(path, std::ios::binary) << text;
  fs::permissions(path, perms);
}

bool process_gone(pid_t pid) {
  // Gone, or a zombie waiting for a reaper that is not ours.
  if (::kill(pid, 0) != 0) return true;
  const std::string stat = read_text("/proc/" + std::to_string(pid) + "/stat");
  const std::size_t paren = stat.rfind(')');
  return paren != std::string::npos && stat.size() > paren + 2 && stat[paren + 2] == 'Z';
}

class FilterCacheTest : public test::ScratchDirectoryTest {
 protected:
  FilterCacheTest() : ScratchDirectoryTest("boxgen-cache") {}

  // A compiler: a shell script answering `--version` with one line and doing `compile` (shell
  // code, with the output path in $out) for a compile.
  std::string compiler(const std::string& name, const std::string& compile,
                       const std::string& version = "echo fake-cxx 1.0") const {
    const fs::path path = dir_ / name;
    write_text(path,
               "#!/bin/sh\nif [ \"$1\" = --version ]; then " + version +
                   "; exit 0; fi\nout=\nwhile [ $# -gt 0 ]; do [ \"$1\" = -o ] && out=$2; shift; "
                   "done\n" +
                   compile + "\n",
               fs::perms(0755));
    return path.string();
  }
  CompileOptions options(const fs::path& cache, const std::string& cxx) const {
    CompileOptions o;
    o.cache_dir = cache;
    o.compiler = cxx;
    return o;
  }
  // The message of the LoadError that load_filter throws (a failure when it throws none).
  static std::string refusal(const CompileOptions& o) {
    try {
      (void)load_filter(kSpec, "bcc", o);
    } catch (const LoadError& e) {
      const std::string what = e.what();
      EXPECT_EQ(what.find('\n'), std::string::npos) << what;
      return what;
    }
    ADD_FAILURE() << "load_filter succeeded";
    return {};
  }
  // The key of kSpec's entry for compiler `cxx`: a failing compile names the entry's log.
  std::string key_for(const std::string& cxx) {
    const fs::path probe = dir_ / "probe";
    const std::string what = refusal(options(probe, cxx));
    const std::size_t end = what.find(".log");
    EXPECT_NE(end, std::string::npos) << what;
    fs::remove_all(probe);
    return what.substr(end - 16, 16);
  }
};

TEST_F(FilterCacheTest, CacheOthersCanWriteIsRefused) {
  const std::string cxx = compiler("cxx", "exit 1");
  for (const auto mode : {01777, 0777, 0775, 0730}) {
    const fs::path cache = dir_ / ("cache-" + std::to_string(mode));
    fs::create_directory(cache);
    ASSERT_EQ(::chmod(cache.c_str(), static_cast<mode_t>(mode)), 0);
    const std::string what = refusal(options(cache, cxx));
    EXPECT_NE(what.find("the filter cache '" + cache.string() + "' is writable by"),
              std::string::npos)
        << what;
    EXPECT_NE(what.find("set BOXGEN_CACHE_DIR"), std::string::npos) << what;
    EXPECT_TRUE(fs::is_empty(cache)) << "something was written into " << cache;
  }
}

TEST_F(FilterCacheTest, CacheInADirectoryOthersCanWriteIsRefused) {
  const std::string cxx = compiler("cxx", "exit 1");
  const fs::path open = dir_ / "open", sticky = dir_ / "sticky";
  fs::create_directories(open / "cache");
  fs::create_directories(sticky / "cache");
  ASSERT_EQ(::chmod(open.c_str(), 0777), 0);
  ASSERT_EQ(::chmod(sticky.c_str(), 01777), 0);  // as /tmp: others cannot rename our cache
  const std::string what = refusal(options(open / "cache", cxx));
  EXPECT_NE(what.find("lies in '" + open.string() + "', which others can write"), std::string::npos)
      << what;
  // Under the sticky directory the cache is used: the refusal is the compiler's failure.
  EXPECT_NE(refusal(options(sticky / "cache", cxx)).find("compiling filter"), std::string::npos);
  // A cache created by the loader is private, whatever the umask.
  const mode_t old = ::umask(0);
  (void)refusal(options(dir_ / "new" / "cache", cxx));
  ::umask(old);
  EXPECT_EQ(fs::status(dir_ / "new" / "cache").permissions(), fs::perms(0700));
}

TEST_F(FilterCacheTest, CacheOfAnotherUserIsRefused) {
  if (::geteuid() != 0) GTEST_SKIP() << "needs root to give the cache to another user";
  const std::string cxx = compiler("cxx", "exit 1");
  const fs::path cache = dir_ / "cache";
  fs::create_directory(cache);
  ASSERT_EQ(::chmod(cache.c_str(), 0700), 0);
  ASSERT_EQ(::chown(cache.c_str(), 65534, 65534), 0);
  EXPECT_NE(refusal(options(cache, cxx)).find("is owned by uid 65534, not by you"),
            std::string::npos);
}

// The hostile trial's case: in a cache others can write, an object whose constructor leaves a
// mark, described by a .json with its true size and hash and this loader's stamp. It never runs.
// The same entry in the user's own private cache does load (the mark appears), which shows that
// the entry is complete and only the directory's checks keep it out.
TEST_F(FilterCacheTest, PlantedObjectInASharedCacheNeverRuns) {
  const std::string cxx = compiler("cxx", "exit 1");
  const std::string key = key_for(cxx);
  ASSERT_EQ(key.size(), 16U);
  const fs::path mark = dir_ / "planted-code-ran";
  write_text(dir_ / "planted.c",
             "#include <stdio.h>\n__attribute__((constructor)) static void plant(void) {\n"
             "  FILE* f = fopen(\"" +
                 mark.string() + "\", \"w\"); if (f) fclose(f);\n}\n");
  const std::string cc = "cc -shared -fPIC -o '" + (dir_ / "planted.so").string() + "' '" +
                         (dir_ / "planted.c").string() + "'";
  ASSERT_EQ(std::system(cc.c_str()), 0) << cc;
  const std::string object = read_text(dir_ / "planted.so");
  const auto plant = [&](const fs::path& cache, fs::perms so_mode) {
    const CacheEntry entry{cache, key};
    write_text(entry.file(".so"), object, so_mode);
    write_text(entry.file(".glsl"), "// float\n");
    write_text(entry.file("_double.glsl"), "// double\n");
    write_text(entry.file("_buffered.glsl"), "// float, buffered\n");
    write_text(entry.file("_buffered_double.glsl"), "// double, buffered\n");
    EntryInfo info;
    info.spec = kSpec;
    info.lattice = "bcc";
    info.rows = "2,0,0; 0,2,0; 1,1,1";
    info.stamp = entry_stamp(key);
    info.so_size = object.size();
    info.so_hash = hash_text(object);
    info.glsl_hash = hash_text("// float\n");
    info.glsl_double_hash = hash_text("// double\n");
    info.glsl_buffered_hash = hash_text("// float, buffered\n");
    info.glsl_buffered_double_hash = hash_text("// double, buffered\n");
    write_entry(entry, info);
  };
  const fs::path shared = dir_ / "shared";
  fs::create_directory(shared);
  plant(shared, fs::perms(0644));
  ASSERT_EQ(::chmod(shared.c_str(), 01777), 0);
  EXPECT_NE(refusal(options(shared, cxx)).find("is writable by others (mode 1777)"),
            std::string::npos);
  EXPECT_FALSE(fs::exists(mark)) << "the planted object was loaded";

  const fs::path own = dir_ / "own";
  fs::create_directory(own);
  ASSERT_EQ(::chmod(own.c_str(), 0700), 0);
  plant(own, fs::perms(0666));  // an object others could have written: not loaded either
  EXPECT_NE(refusal(options(own, cxx)).find(key + ".so' is writable by others (mode 0666)"),
            std::string::npos);
  EXPECT_FALSE(fs::exists(mark)) << "the planted object was loaded";

  fs::permissions(own / (key + ".so"), fs::perms(0644));
  (void)refusal(options(own, cxx));  // loaded; its stamp is not a filter's: rebuilt, which fails
  EXPECT_TRUE(fs::exists(mark)) << "the control did not load the entry: the test proves nothing";
}

// A link of any of the entry's names, to a victim file: refused in one line, and neither the
// victim nor the link is touched (the trial saw KEY.log truncate its victim and KEY.cpp, .so,
// .json and .glsl overwrite theirs).
TEST_F(FilterCacheTest, LinksInTheCacheAreNeverFollowed) {
  const std::string cxx = compiler("cxx", "echo oops; exit 1");
  const std::string key = key_for(cxx);
  const fs::path victim = dir_ / "victim";
  for (const char* ending : {".log", ".cpp", "_double.cpp", ".so", ".json", ".glsl", "_double.glsl",
                             "_buffered.glsl", "_buffered_double.glsl", ".lock"}) {
    const fs::path cache = dir_ / ("cache" + std::string(ending));
    fs::create_directory(cache);
    write_text(victim, "precious\n");
    fs::create_symlink(victim, cache / (key + ending));
    const std::string what = refusal(options(cache, cxx));
    EXPECT_NE(what.find(key + ending + "' is a symbolic link"), std::string::npos) << what;
    EXPECT_EQ(read_text(victim), "precious\n") << ending;
    EXPECT_TRUE(fs::is_symlink(cache / (key + ending))) << ending;
  }
  // The writer the cache writes through replaces a link and never writes its target.
  const fs::path link = dir_ / "link";
  fs::create_symlink(victim, link);
  write_entry_file(link, "new\n");
  EXPECT_FALSE(fs::is_symlink(link));
  EXPECT_EQ(read_text(link), "new\n");
  EXPECT_EQ(read_text(victim), "precious\n");
}

TEST_F(FilterCacheTest, CompilerThatWritesNothingCommitsNothing) {
  const fs::path cache = dir_ / "cache";
  const std::string what = refusal(options(cache, compiler("true", "exit 0")));
  EXPECT_NE(what.find("exited 0 but wrote no object file"), std::string::npos) << what;
  // A file that is not an object is no better.
  EXPECT_NE(refusal(options(cache, compiler("text", "echo text > \"$out\"")))
                .find("wrote no object file"),
            std::string::npos);
  for (const auto& e : fs::directory_iterator(cache)) {
    const std::string name = e.path().filename().string();
    EXPECT_TRUE(name.ends_with(".cpp") || name.ends_with(".lock") || name.ends_with(".log"))
        << name << " was left in the cache";
  }
}

// A compile that does not end is stopped at the limit, with the compiler's whole process group
// (its background child included), and the entry's lock is released; `--version` alike.
TEST_F(FilterCacheTest, HangingCompilerIsStoppedWithItsChildren) {
  const fs::path cache = dir_ / "cache", pids = dir_ / "pids";
  const std::string cxx =
      compiler("hang", "sleep 1000 & echo $$ $! > '" + pids.string() + "'; wait");
  CompileOptions o = options(cache, cxx);
  o.compile_seconds = 1;
  for (int attempt = 0; attempt < 2; ++attempt) {  // the second would wait for a held lock
    fs::remove(pids);
    const auto start = std::chrono::steady_clock::now();
    const std::string what = refusal(o);
    const double seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    EXPECT_NE(what.find("was stopped after 1 s (the limit: BOXGEN_COMPILE_TIMEOUT)"),
              std::string::npos)
        << what;
    EXPECT_LT(seconds, 20);
    std::istringstream in(read_text(pids));
    pid_t shell = 0, child = 0;
    ASSERT_TRUE(in >> shell >> child);
    for (int wait = 0; wait < 50 && !(process_gone(shell) && process_gone(child)); ++wait)
      ::usleep(100000);
    EXPECT_TRUE(process_gone(shell) && process_gone(child)) << "the compiler outlived its limit";
  }
  CompileOptions v = options(cache, compiler("mute", "exit 1", "sleep 1000"));
  v.compile_seconds = 1;
  EXPECT_NE(refusal(v).find("did not answer `--version` within 1 s"), std::string::npos);
}

TEST_F(FilterCacheTest, CompilerLogIsBounded) {
  const fs::path cache = dir_ / "cache";
  const std::string what =
      refusal(options(cache, compiler("talker", "head -c 5000000 /dev/zero | tr '\\0' x; exit 1")));
  const std::size_t at = what.find("the compiler's messages: ");
  ASSERT_NE(at, std::string::npos) << what;
  const fs::path log = what.substr(at + 25, what.size() - at - 26);
  ASSERT_TRUE(fs::is_regular_file(log)) << log;
  EXPECT_LE(fs::file_size(log), kMaxLogBytes + 200);
  EXPECT_NE(read_text(log).find("more bytes of the compiler's messages were dropped"),
            std::string::npos);
}

TEST_F(FilterCacheTest, CompileTimeoutMustBeAPositiveNumber) {
  const std::string cxx = compiler("cxx", "exit 1");
  for (const char* bad : {"0", "-1", "nan", "inf", "ten", "5s"}) {
    ::setenv("BOXGEN_COMPILE_TIMEOUT", bad, 1);
    EXPECT_NE(refusal(options(dir_ / "cache", cxx)).find("BOXGEN_COMPILE_TIMEOUT must be"),
              std::string::npos)
        << bad;
  }
  ::unsetenv("BOXGEN_COMPILE_TIMEOUT");
}

}  // namespace
}  // namespace boxgen::loader
