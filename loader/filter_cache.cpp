#include "loader/filter_cache.h"

#include <fcntl.h>
#include <sys/file.h>
#include <sys/stat.h>
#include <unistd.h>

#include <fmt/format.h>
#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <nlohmann/json.hpp>

#include "boxgen/version.h"
#include "loader/filter_loader.h"
#include "runtime/nrrd_checks.h"
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

std::string shown(const fs::path& path) { return runtime::nrrd_checks::printable(path.string()); }

std::string mode_text(mode_t mode) { return fmt::format("mode {:04o}", mode & 07777); }

// Why a file or directory of the cache may not be trusted (empty: it may be): not this user's,
// or writable by its group or by others.
std::string untrusted(const struct stat& info) {
  const uid_t me = ::geteuid();
  if (info.st_uid != me)
    return fmt::format("owned by uid {}, not by you (uid {})", info.st_uid, me);
  if ((info.st_mode & S_IWOTH) != 0) return "writable by others (" + mode_text(info.st_mode) + ")";
  if ((info.st_mode & S_IWGRP) != 0)
    return "writable by its group (" + mode_text(info.st_mode) + ")";
  return {};
}

[[noreturn]] void refuse_directory(const fs::path& dir, const std::string& why) {
  throw LoadError(fmt::format(
      "the filter cache '{}' {}: compiled filters are loaded only from a directory nobody else can "
      "write (chmod 700 it, or set BOXGEN_CACHE_DIR to a directory of your own)",
      shown(dir), why));
}

struct Fnv {
  std::uint64_t h = 14695981039346656037ULL;
  void add(const char* data, std::size_t n) {
    for (std::size_t i = 0; i < n; ++i) {
      h ^= static_cast<unsigned char>(data[i]);
      h *= 1099511628211ULL;
    }
  }
  std::string hex() const { return fmt::format("{:016x}", h); }
};

// The problem of an entry's file as lstat or fstat sees it, or empty.
std::string entry_file_problem(const struct stat& info) {
  if (S_ISLNK(info.st_mode)) return "is a symbolic link";
  if (!S_ISREG(info.st_mode)) return "is not a regular file";
  const std::string why = untrusted(info);
  return why.empty() ? why : "is " + why;
}

constexpr const char* kEntryFiles[] = {
    ".so",   ".json",        ".cpp",           "_double.cpp",
    ".glsl", "_double.glsl", "_buffered.glsl", "_buffered_double.glsl",
    ".log",  ".lock"};

}  // namespace

std::optional<fs::path> checked_cache_dir(const fs::path& dir, bool create) {
  std::error_code ec;
  fs::path absolute = fs::absolute(dir, ec);
  if (ec) refuse_directory(dir, "cannot be found: " + ec.message());
  if (create && !fs::exists(absolute, ec)) {
    fs::create_directories(absolute.parent_path(), ec);
    // The cache itself is private from the start (mode 0700, whatever the umask).
    if (::mkdir(absolute.c_str(), 0700) != 0 && errno != EEXIST)
      throw LoadError(fmt::format("cannot create the filter cache '{}': {}", shown(absolute),
                                  std::strerror(errno)));
  }
  if (!fs::exists(absolute, ec)) return std::nullopt;
  const fs::path real = fs::canonical(absolute, ec);
  if (ec) refuse_directory(absolute, "cannot be resolved: " + ec.message());
  struct stat info {};
  if (::stat(real.c_str(), &info) != 0 || !S_ISDIR(info.st_mode))
    refuse_directory(real, "is not a directory");
  if (const std::string why = untrusted(info); !why.empty()) refuse_directory(real, "is " + why);
  // Every directory above it: someone who can write one could replace the cache with theirs.
  // Root's directories are trusted, and a sticky one (/tmp) lets nobody else rename ours.
  for (fs::path up = real.parent_path();; up = up.parent_path()) {
    struct stat above {};
    if (::stat(up.c_str(), &above) != 0) refuse_directory(real, "has a parent that cannot be read");
    const bool owner_ok = above.st_uid == 0 || above.st_uid == ::geteuid();
    const bool shared =
        (above.st_mode & (S_IWGRP | S_IWOTH)) != 0 && (above.st_mode & S_ISVTX) == 0;
    if (!owner_ok || shared)
      refuse_directory(
          real, fmt::format("lies in '{}', which {} and could replace it", shown(up),
                            !owner_ok ? fmt::format("is owned by uid {}", above.st_uid)
                                      : "others can write (" + mode_text(above.st_mode) + ")"));
    if (up == up.root_path()) break;
  }
  return real;
}

std::string hash_text(const std::string& text) {
  Fnv f;
  f.add(text.data(), text.size());
  return f.hex();
}

std::string entry_stamp(const std::string& key) {
  return fmt::format("boxgen-filter abi {}; boxgen {}; key {}", kAbiVersion, kVersion, key);
}

void check_entry_files(const CacheEntry& entry) {
  for (const char* ending : kEntryFiles) {
    const fs::path file = entry.file(ending);
    struct stat info {};
    if (::lstat(file.c_str(), &info) != 0) continue;  // absent: fine
    if (const std::string why = entry_file_problem(info); !why.empty())
      throw LoadError(fmt::format(
          "the filter cache entry '{}' {}: boxgen never writes such a file, so it is neither "
          "loaded nor replaced; remove the entry ({}.*)",
          shown(file), why, shown(entry.dir / entry.key)));
  }
}

int open_entry_file(const fs::path& path) {
  const int fd = ::open(path.c_str(), O_RDONLY | O_NOFOLLOW | O_CLOEXEC);
  if (fd < 0) return -1;
  struct stat info {};
  if (::fstat(fd, &info) != 0 || !entry_file_problem(info).empty()) {
    ::close(fd);
    return -1;
  }
  return fd;
}

std::optional<std::string> hash_descriptor(int fd, std::uintmax_t& size) {
  Fnv f;
  size = 0;
  char buffer[1 << 16];
  for (off_t at = 0;;) {
    const ssize_t n = ::pread(fd, buffer, sizeof buffer, at);
    if (n < 0 && errno == EINTR) continue;
    if (n < 0) return std::nullopt;
    if (n == 0) break;
    f.add(buffer, static_cast<std::size_t>(n));
    at += n;
    size += static_cast<std::uintmax_t>(n);
  }
  return f.hex();
}

std::optional<std::string> read_entry_file(const fs::path& path) {
  const int fd = open_entry_file(path);
  if (fd < 0) return std::nullopt;
  std::string text;
  char buffer[1 << 16];
  for (;;) {
    const ssize_t n = ::read(fd, buffer, sizeof buffer);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) {
      ::close(fd);
      if (n < 0) return std::nullopt;
      return text;
    }
    text.append(buffer, static_cast<std::size_t>(n));
  }
}

std::optional<EntryInfo> read_entry(const CacheEntry& entry) {
  const auto text = read_entry_file(entry.file(".json"));
  if (!text) return std::nullopt;
  try {
    const nlohmann::json j = nlohmann::json::parse(*text);
    EntryInfo info;
    info.spec = j.at("spec").get<std::string>();
    info.lattice = j.at("lattice").get<std::string>();
    info.rows = j.at("rows").get<std::string>();
    info.stamp = j.at("stamp").get<std::string>();
    info.so_hash = j.at("so_hash").get<std::string>();
    info.so_size = j.at("so_size").get<std::uintmax_t>();
    info.glsl_hash = j.at("glsl_hash").get<std::string>();
    info.glsl_double_hash = j.at("glsl_double_hash").get<std::string>();
    info.glsl_buffered_hash = j.at("glsl_buffered_hash").get<std::string>();
    info.glsl_buffered_double_hash = j.at("glsl_buffered_double_hash").get<std::string>();
    info.glsl_block = j.at("glsl_block").get<std::vector<int>>();
    return info;
  } catch (const std::exception&) {  // truncated, edited or older: the entry is rebuilt
    return std::nullopt;
  }
}

void write_entry_file(const fs::path& path, const std::string& text) {
  support::write_output_file(
      path,
      [&](std::FILE* f) { return std::fwrite(text.data(), 1, text.size(), f) == text.size(); }, {},
      support::LinkPolicy::replace);
}

void write_entry(const CacheEntry& entry, const EntryInfo& info) {
  const nlohmann::json j{{"spec", info.spec},
                         {"lattice", info.lattice},
                         {"rows", info.rows},
                         {"stamp", info.stamp},
                         {"so_hash", info.so_hash},
                         {"so_size", info.so_size},
                         {"glsl_hash", info.glsl_hash},
                         {"glsl_double_hash", info.glsl_double_hash},
                         {"glsl_buffered_hash", info.glsl_buffered_hash},
                         {"glsl_buffered_double_hash", info.glsl_buffered_double_hash},
                         {"glsl_block", info.glsl_block}};
  write_entry_file(entry.file(".json"), j.dump(2) + "\n");
}

EntryLock::EntryLock(const CacheEntry& entry) {
  const fs::path path = entry.file(".lock");
  fd_ = ::open(path.c_str(), O_RDWR | O_CREAT | O_NOFOLLOW | O_CLOEXEC, 0600);
  if (fd_ < 0) throw LoadError("cannot create " + shown(path) + ": " + std::strerror(errno));
  while (::flock(fd_, LOCK_EX) != 0)
    if (errno != EINTR) {
      const int error = errno;
      ::close(fd_);
      throw LoadError("cannot lock " + shown(path) + ": " + std::strerror(error));
    }
}

EntryLock::~EntryLock() {
  if (fd_ >= 0) ::close(fd_);  // closing releases the lock
}

}  // namespace boxgen::loader
