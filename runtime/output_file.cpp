#include "runtime/output_file.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <fmt/format.h>

#include <atomic>
#include <cerrno>
#include <cstring>
#include <string>
#include <string_view>

namespace boxgen::runtime {

namespace {

namespace fs = std::filesystem;

// A path made fit for a one-line message: control characters become '?'.
std::string shown(const fs::path& path) {
  std::string out;
  const std::string text = path.string();
  for (char ch : std::string_view(text).substr(0, 200))
    out += (static_cast<unsigned char>(ch) < 0x20 || ch == 0x7f) ? '?' : ch;
  if (text.size() > 200) out += "...";
  return out;
}

[[noreturn]] void refuse(const fs::path& path, const std::string& why) {
  throw OutputFileError("cannot write '" + shown(path) + "': " + why);
}

const char* kind_of(mode_t mode) {
  if (S_ISDIR(mode)) return "a directory";
  if (S_ISFIFO(mode)) return "a FIFO";
  if (S_ISCHR(mode)) return "a character device";
  if (S_ISBLK(mode)) return "a block device";
  if (S_ISSOCK(mode)) return "a socket";
  return "not a regular file";
}

// Follows the symbolic links of `path` (at most 40, as the kernel does) to the file a write lands
// in. Sets `exists` and, if it exists, `info`.
fs::path follow_links(const fs::path& path, bool& exists, struct stat& info) {
  fs::path target = path;
  for (int depth = 0; depth <= 40; ++depth) {
    if (::lstat(target.c_str(), &info) != 0) {
      if (errno != ENOENT) refuse(path, std::strerror(errno));
      exists = false;
      return target;
    }
    if (!S_ISLNK(info.st_mode)) {
      exists = true;
      return target;
    }
    std::error_code ec;
    const fs::path next = fs::read_symlink(target, ec);
    if (ec) refuse(path, ec.message());
    target = next.is_absolute() ? next : target.parent_path() / next;
  }
  refuse(path, "too many levels of symbolic links");
}

}  // namespace

fs::path check_output_file(const fs::path& path, std::span<const fs::path> inputs) {
  const std::string name = path.filename().string();
  if (name.empty() || name == "." || name == "..") refuse(path, "not a file name");
  bool exists = false;
  struct stat info {};
  fs::path target = follow_links(path, exists, info);
  if (exists) {
    if (!S_ISREG(info.st_mode))
      refuse(path, fmt::format("{}{} is {}; only regular files are written",
                               target == path ? "it" : "its link target '",
                               target == path ? "" : shown(target) + "'", kind_of(info.st_mode)));
    for (const fs::path& input : inputs) {
      struct stat in {};
      if (::stat(input.c_str(), &in) == 0 && in.st_dev == info.st_dev && in.st_ino == info.st_ino)
        refuse(path, fmt::format("it is the input '{}'; write to another file", shown(input)));
    }
  } else {
    const fs::path dir = target.has_parent_path() ? target.parent_path() : fs::path(".");
    std::error_code ec;
    if (!fs::is_directory(dir, ec))
      refuse(path, fmt::format("the directory '{}' does not exist", shown(dir)));
    if (target.filename().empty()) refuse(path, "not a file name");
  }
  return target;
}

void write_output_file(const fs::path& path, const std::function<bool(std::FILE*)>& fill,
                       const std::function<std::string()>& describe_failure) {
  const fs::path target = check_output_file(path);
  struct stat old {};
  const bool replacing = ::stat(target.c_str(), &old) == 0;
  const fs::path dir = target.has_parent_path() ? target.parent_path() : fs::path(".");
  const std::string name = target.filename().string();

  static std::atomic<unsigned> counter{0};
  fs::path temp;
  int fd = -1;
  for (int attempt = 0; attempt < 100 && fd < 0; ++attempt) {
    temp = dir / fmt::format(".{}.tmp-{}-{}", name, static_cast<long>(::getpid()), counter++);
    fd = ::open(temp.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0666);
    if (fd < 0 && errno != EEXIST) refuse(path, std::strerror(errno));
  }
  if (fd < 0) refuse(path, "could not create a temporary file next to it");
  // The replacement keeps the permissions of the file it replaces (a new file gets 0666 & ~umask).
  if (replacing && ::fchmod(fd, old.st_mode & 07777) != 0) {
    const int error = errno;
    ::close(fd);
    ::unlink(temp.c_str());
    refuse(path, std::strerror(error));
  }
  std::FILE* file = ::fdopen(fd, "wb");
  if (!file) {
    const int error = errno;
    ::close(fd);
    ::unlink(temp.c_str());
    refuse(path, std::strerror(error));
  }
  std::string problem;
  if (!fill(file)) {
    problem = describe_failure ? describe_failure() : std::string();
    if (problem.empty())
      problem = std::ferror(file) ? std::strerror(errno) : "the data could not be written";
  } else if (std::fflush(file) != 0 || std::ferror(file) || ::fsync(::fileno(file)) != 0) {
    problem = std::strerror(errno);
  }
  if (std::fclose(file) != 0 && problem.empty()) problem = std::strerror(errno);
  if (problem.empty() && std::rename(temp.c_str(), target.c_str()) != 0)
    problem = std::strerror(errno);
  if (!problem.empty()) {
    ::unlink(temp.c_str());
    refuse(path, problem);
  }
}

}  // namespace boxgen::runtime
