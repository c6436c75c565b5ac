#include "analysis/output_file.h"

#include "runtime/output_file.h"

#include <fmt/format.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cstdio>
#include <filesystem>
#include <stdexcept>
#include <vector>

namespace boxgen::analysis {

AtomicOutput::AtomicOutput(std::string path) : path_(std::move(path)) {
  if (path_.empty()) throw std::invalid_argument("empty output path");
  if (std::filesystem::is_directory(path_))
    throw std::invalid_argument(fmt::format("output '{}' is a directory", path_));
  // Where the file lands, as for every output (runtime/output_file.h): through symbolic links,
  // never onto a FIFO, device or socket.
  try {
    path_ = runtime::check_output_file(path_).string();
  } catch (const runtime::OutputFileError& e) {
    throw std::invalid_argument(e.what());
  }
  std::vector<char> name(path_.begin(), path_.end());
  const std::string suffix = ".partial-XXXXXX";
  name.insert(name.end(), suffix.begin(), suffix.end());
  name.push_back('\0');
  const int fd = ::mkstemp(name.data());
  if (fd < 0)
    throw std::invalid_argument(
        fmt::format("cannot write '{}' (missing directory or no permission)", path_));
  ::close(fd);
  temporary_ = name.data();
}

AtomicOutput::~AtomicOutput() {
  if (!committed_) std::remove(temporary_.c_str());
}

void AtomicOutput::commit() {
  std::error_code ec;
  const auto size = std::filesystem::file_size(temporary_, ec);
  if (ec || size == 0) throw std::runtime_error(fmt::format("nothing was written for '{}'", path_));
  // mkstemp creates the file 0600; give it the mode an ordinary new file gets (0666 & ~umask).
  const mode_t mask = ::umask(0);
  ::umask(mask);
  ::chmod(temporary_.c_str(), 0666 & ~mask);
  if (std::rename(temporary_.c_str(), path_.c_str()) != 0)
    throw std::runtime_error(fmt::format("cannot rename the finished file to '{}'", path_));
  committed_ = true;
}

}  // namespace boxgen::analysis
