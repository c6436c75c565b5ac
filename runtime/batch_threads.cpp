#include "runtime/batch_threads.h"

#include <fmt/format.h>
#include <omp.h>

#include <atomic>
#include <cerrno>
#include <cstdlib>
#include <stdexcept>
#include <string>

namespace boxgen::runtime {

namespace {
std::atomic<int> program_cap{0};
}

int batch_threads() {
  if (const int cap = program_cap.load(); cap > 0) return cap;
  if (const char* env = std::getenv("BOXGEN_THREADS"); env && *env) {
    char* end = nullptr;
    errno = 0;
    const long n = std::strtol(env, &end, 10);
    if (*end != '\0' || errno != 0 || n < 1 || n > 4096)
      throw std::invalid_argument(fmt::format("BOXGEN_THREADS must be a positive integer, got '{}'",
                                              std::string(env).substr(0, 40)));
    return static_cast<int>(n);
  }
  return omp_get_max_threads();
}

void set_batch_threads(int n) {
  if (n < 0)
    throw std::invalid_argument(fmt::format("the thread count must be positive, got {}", n));
  program_cap.store(n);
}

}  // namespace boxgen::runtime
