// The cache of compiled filters (docs/runtime.md "Filters from any SPEC"): where it is, the key
// of an entry, an entry's files and the checks that decide whether it may be loaded.
//
// An entry is <key>.so (the filter), <key>.cpp (its source, for the curious) and <key>.json (what
// it is, and the size and hash of the .so), each written through a temporary file and a rename;
// the .json goes last, so an entry without it, or whose .so is not the one it describes, is
// incomplete or corrupt and is rebuilt. <key>.lock serialises first uses of the same filter.
#pragma once
#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>

namespace boxgen::loader {

// BOXGEN_CACHE_DIR, else $XDG_CACHE_HOME/boxgen, else $HOME/.cache/boxgen (`explicit_dir` first
// when not empty).
std::filesystem::path resolve_cache_dir(const std::filesystem::path& explicit_dir);

// 64-bit FNV-1a, as 16 hex digits: the cache key of a text, and the hash of a file.
std::string hash_text(const std::string& text);
std::optional<std::string> hash_file(const std::filesystem::path& path);

struct EntryInfo {
  std::string spec, lattice, rows, stamp, so_hash;
  std::uintmax_t so_size = 0;
};

struct CacheEntry {
  std::filesystem::path dir;
  std::string key;
  std::filesystem::path file(const char* extension) const { return dir / (key + extension); }
};

// The entry's description, or nothing when it is missing or unreadable.
std::optional<EntryInfo> read_entry(const CacheEntry& entry);
// True when the .json describes the .so that is there: same size and hash.
bool entry_intact(const CacheEntry& entry, const EntryInfo& info);
// Writes the .json (atomically).
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
