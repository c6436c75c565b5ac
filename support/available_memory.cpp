#include "support/available_memory.h"

#include <sys/resource.h>

#include <algorithm>
#include <fstream>
#include <limits>
#include <sstream>
#include <string>

namespace boxgen::support {

namespace {

// The number after `key` in a "Key: value kB" file, in bytes, or a negative number.
double kib_field(const char* file, const std::string& key) {
  std::ifstream in(file);
  std::string line;
  while (std::getline(in, line))
    if (line.rfind(key, 0) == 0) {
      std::istringstream fields(line.substr(key.size()));
      double kib = -1;
      if (fields >> kib) return kib * 1024.0;
    }
  return -1;
}

// One number from a cgroup file ("max" or unreadable: negative).
double cgroup_value(const std::string& path) {
  std::ifstream in(path);
  std::string text;
  if (!(in >> text) || text == "max") return -1;
  try {
    return std::stod(text);
  } catch (const std::exception&) {
    return -1;
  }
}

// The cgroup v2 directory of this process ("0::/path" in /proc/self/cgroup), or empty.
std::string cgroup_directory() {
  std::ifstream in("/proc/self/cgroup");
  std::string line;
  while (std::getline(in, line))
    if (line.rfind("0::", 0) == 0) return "/sys/fs/cgroup" + line.substr(3);
  return {};
}

}  // namespace

double available_memory_bytes() {
  double least = std::numeric_limits<double>::infinity();
  if (const double available = kib_field("/proc/meminfo", "MemAvailable:"); available >= 0)
    least = available;
  rlimit space{};
  if (::getrlimit(RLIMIT_AS, &space) == 0 && space.rlim_cur != RLIM_INFINITY) {
    const double mapped = std::max(0.0, kib_field("/proc/self/status", "VmSize:"));
    least = std::min(least, std::max(0.0, static_cast<double>(space.rlim_cur) - mapped));
  }
  if (const std::string cgroup = cgroup_directory(); !cgroup.empty()) {
    const double most = cgroup_value(cgroup + "/memory.max");
    const double used = cgroup_value(cgroup + "/memory.current");
    if (most >= 0 && used >= 0) least = std::min(least, std::max(0.0, most - used));
  }
  return least == std::numeric_limits<double>::infinity() ? 0 : least;
}

}  // namespace boxgen::support
