#include "loader/filter_cache.h"

#include <fcntl.h>
#include <sys/file.h>
#include <unistd.h>

#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <nlohmann/json.hpp>

#include "loader/filter_loader.h"
#include "support/output_file.h"

namespace boxgen::loader {

namespace fs = std::filesystem;

fs::path resolve_cache_dir(const fs::path& explicit_dir) {
  if (!explicit_dir.empty()) return explicit_dir;
  const auto env = [](const char* name) -> std::string {
    const char* v = std::getenv(name);
    return v ? v : "";
  };
  if (!env("BOXGEN_CACHE_DIR").empty()) return env("BOXGEN_CACHE_DIR");
  if (!env("XDG_CACHE_HOME").empty()) return fs::path(env("XDG_CACHE_HOME")) / "boxgen";
  if (!env("HOME").empty()) return fs::path(env("HOME")) / ".cache" / "boxgen";
  throw LoadError(
      "no cache directory for compiled filters: set BOXGEN_CACHE_DIR (or XDG_CACHE_HOME or HOME)");
}

namespace {

struct Fnv {
  std::uint64_t h = 14695981039346656037ULL;
  void add(const char* data, std::size_t n) {
    for (std::size_t i = 0; i < n; ++i) {
      h ^= static_cast<unsigned char>(data[i]);
      h *= 1099511628211ULL;
    }
  }
  std::string hex() const {
    char out[17];
    std::snprintf(out, sizeof out, "%016llx", static_cast<unsigned long long>(h));
    return out;
  }
};

}  // namespace

std::string hash_text(const std::string& text) {
  Fnv f;
  f.add(text.data(), text.size());
  return f.hex();
}

std::optional<std::string> hash_file(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) return std::nullopt;
  Fnv f;
  char buffer[1 << 16];
  while (in) {
    in.read(buffer, sizeof buffer);
    f.add(buffer, static_cast<std::size_t>(in.gcount()));
  }
  if (in.bad()) return std::nullopt;
  return f.hex();
}

std::optional<EntryInfo> read_entry(const CacheEntry& entry) {
  std::ifstream in(entry.file(".json"));
  if (!in) return std::nullopt;
  try {
    const nlohmann::json j = nlohmann::json::parse(in);
    EntryInfo info;
    info.spec = j.at("spec").get<std::string>();
    info.lattice = j.at("lattice").get<std::string>();
    info.rows = j.at("rows").get<std::string>();
    info.stamp = j.at("stamp").get<std::string>();
    info.so_hash = j.at("so_hash").get<std::string>();
    info.so_size = j.at("so_size").get<std::uintmax_t>();
    return info;
  } catch (const std::exception&) {  // truncated or edited: the entry is rebuilt
    return std::nullopt;
  }
}

bool entry_intact(const CacheEntry& entry, const EntryInfo& info) {
  std::error_code ec;
  const std::uintmax_t size = fs::file_size(entry.file(".so"), ec);
  if (ec || size != info.so_size) return false;
  const auto hash = hash_file(entry.file(".so"));
  return hash && *hash == info.so_hash;
}

void write_entry(const CacheEntry& entry, const EntryInfo& info) {
  const nlohmann::json j{{"spec", info.spec},       {"lattice", info.lattice},
                         {"rows", info.rows},       {"stamp", info.stamp},
                         {"so_hash", info.so_hash}, {"so_size", info.so_size}};
  const std::string text = j.dump(2) + "\n";
  support::write_output_file(entry.file(".json"), [&](std::FILE* f) {
    return std::fwrite(text.data(), 1, text.size(), f) == text.size();
  });
}

EntryLock::EntryLock(const CacheEntry& entry) {
  const fs::path path = entry.file(".lock");
  fd_ = ::open(path.c_str(), O_RDWR | O_CREAT | O_CLOEXEC, 0644);
  if (fd_ < 0) throw LoadError("cannot create " + path.string() + ": " + std::strerror(errno));
  while (::flock(fd_, LOCK_EX) != 0)
    if (errno != EINTR) {
      const int error = errno;
      ::close(fd_);
      throw LoadError("cannot lock " + path.string() + ": " + std::strerror(error));
    }
}

EntryLock::~EntryLock() {
  if (fd_ >= 0) ::close(fd_);  // closing releases the lock
}

}  // namespace boxgen::loader
