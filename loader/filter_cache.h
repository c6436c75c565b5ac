// The cache of compiled filters (docs/runtime.md "Filters from any SPEC"): where it is, the key
// of an entry, an entry's files and the checks that decide whether it may be loaded.
//
// An entry is <key>.so (the filter), <key>.cpp and <key>_double.cpp (its two sources, compiled
// at once; kept for the curious, never read back), <key>.glsl and <key>_double.glsl (its GLSL
// evaluators), <key>_buffered.glsl and <key>_buffered_double.glsl (the same with their tables in
// a storage block) and <key>.json (what it is, the size and hash of the .so, the hashes of the
// .glsl files and the storage block's contents), each written through a temporary file and a
// rename; the .json goes last, so an entry without it, or whose files are not the ones it
// describes, is incomplete or corrupt and is rebuilt. <key>.lock serialises first uses of the
// same filter; <key>.log holds the compiler's messages of a failed compile.
//
// The cache holds code this process runs, so it is trusted only as far as nobody else can write
// it (as ssh treats its keys): the directory must be the user's own and not writable by others,
// every directory above it must be the user's or root's and not writable by others (unless
// sticky), and every file of an entry must be a regular file of the user's that others cannot
// write. A link is never followed inside the cache: files are read with O_NOFOLLOW and written
// through the atomic writer's LinkPolicy::replace. An object is hashed and checked against the
// .json before it is loaded, through the very descriptor it is loaded from.
#pragma once
#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

namespace boxgen::loader {

// BOXGEN_CACHE_DIR, else $XDG_CACHE_HOME/boxgen, else $HOME/.cache/boxgen (`explicit_dir` first
// when not empty).
std::filesystem::path resolve_cache_dir(const std::filesystem::path& explicit_dir);

// The cache directory `dir`, created (mode 0700) when `create` and it is missing, as a path
// without links (its canonical form), after the checks above. Throws LoadError (one line, with
// what to do) for a directory others could write; returns nothing when it is missing and not
// created.
std::optional<std::filesystem::path> checked_cache_dir(const std::filesystem::path& dir,
                                                       bool create);

// 64-bit FNV-1a, as 16 hex digits: the cache key of a text, and the hash of a file's bytes. It
// detects corruption; tampering is kept out by the directory's checks (nobody else can write
// the .json that holds the hashes).
std::string hash_text(const std::string& text);

// The version of the interface between this loader and a compiled filter: the two extern "C"
// functions of its glue (filter_loader.cpp) and the runtime types they pass (FilterSource,
// EvaluationPath, LatticeVolume). Raise it whenever one of them changes; an entry of another
// version is built again.
inline constexpr int kAbiVersion = 3;

// The stamp of an entry this loader builds under `key`: its object returns it
// (boxgen_filter_stamp) and its .json records it.
std::string entry_stamp(const std::string& key);

struct EntryInfo {
  std::string spec, lattice, rows, stamp, so_hash, glsl_hash, glsl_double_hash;
  // The GLSL evaluators with their run-time-indexed tables in a storage block, and the block's
  // contents (generator/codegen/targets/glsl_evaluator.h): the GL device's data beside the text.
  std::string glsl_buffered_hash, glsl_buffered_double_hash;
  std::vector<int> glsl_block;
  std::uintmax_t so_size = 0;
};

struct CacheEntry {
  std::filesystem::path dir;  // as checked_cache_dir returns it
  std::string key;
  std::filesystem::path file(const char* extension) const { return dir / (key + extension); }
};

// Throws LoadError (one line) when a file of the entry exists but is not a regular file of this
// user that others cannot write (a symbolic link, a directory, another user's file, mode 0666).
void check_entry_files(const CacheEntry& entry);

// The whole content of an entry's file, read without following a link, or nothing when it is
// missing or fails the checks of check_entry_files.
std::optional<std::string> read_entry_file(const std::filesystem::path& path);

// An entry's file opened for reading without following a link and checked as above, or -1. The
// caller owns the descriptor.
int open_entry_file(const std::filesystem::path& path);
// The FNV-1a hash and size of what a descriptor holds (read from its start), or nothing.
std::optional<std::string> hash_descriptor(int fd, std::uintmax_t& size);

// The entry's description, or nothing when it is missing or unreadable.
std::optional<EntryInfo> read_entry(const CacheEntry& entry);
// Writes a file of the entry (atomically, replacing a link instead of following it).
void write_entry_file(const std::filesystem::path& path, const std::string& text);
// Writes the .json (as write_entry_file).
void write_entry(const CacheEntry& entry, const EntryInfo& info);

// An exclusive lock on <key>.lock, held while the object lives.
class EntryLock {
 public:
  explicit EntryLock(const CacheEntry& entry);
  ~EntryLock();
  EntryLock(const EntryLock&) = delete;
  EntryLock& operator=(const EntryLock&) = delete;

 private:
  int fd_ = -1;
};

}  // namespace boxgen::loader
