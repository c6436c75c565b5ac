#include "runtime/batch_threads.h"

#include <fmt/format.h>
#include <omp.h>
#include <sys/resource.h>

#include <algorithm>

#include <atomic>
#include <cerrno>
#include <cstdlib>
#include <stdexcept>
#include <string>

namespace boxgen::runtime {

namespace {
std::atomic<int> program_cap{0};

// Why `n` threads cannot be had, or empty.
std::string too_many(long n) {
  const int most = max_batch_threads();
  if (n <= most) return {};
  return fmt::format(
      "{} threads are more than this process can use: at most {} (4 per processor, {} "
      "processors{})",
      n, most, omp_get_num_procs(),
      most < 4 * omp_get_num_procs()
          ? ", and the thread stacks that fit in half the address-space limit"
          : "");
}
}  // namespace

int max_batch_threads() {
  long most = 4L * std::max(1, omp_get_num_procs());
  rlimit space{}, stack{};
  if (::getrlimit(RLIMIT_AS, &space) == 0 && space.rlim_cur != RLIM_INFINITY) {
    const double stack_bytes =
        ::getrlimit(RLIMIT_STACK, &stack) == 0 && stack.rlim_cur != RLIM_INFINITY
            ? static_cast<double>(stack.rlim_cur)
            : 8.0 * 1024 * 1024;
    most = std::min(most, static_cast<long>(static_cast<double>(space.rlim_cur) / 2 / stack_bytes));
  }
  return static_cast<int>(std::max(1L, most));
}

int batch_threads() {
  if (const int cap = program_cap.load(); cap > 0) return cap;
  if (const char* env = std::getenv("BOXGEN_THREADS"); env && *env) {
    char* end = nullptr;
    errno = 0;
    const long n = std::strtol(env, &end, 10);
    if (*end != '\0' || errno != 0 || n < 1)
      throw std::invalid_argument(fmt::format("BOXGEN_THREADS must be a positive integer, got '{}'",
                                              std::string(env).substr(0, 40)));
    if (const std::string why = too_many(n); !why.empty())
      throw std::invalid_argument("BOXGEN_THREADS=" + std::string(env).substr(0, 40) + ": " + why);
    return static_cast<int>(n);
  }
  return omp_get_max_threads();
}

void set_batch_threads(int n) {
  if (n < 0)
    throw std::invalid_argument(fmt::format("the thread count must be positive, got {}", n));
  if (const std::string why = too_many(n); !why.empty()) throw std::invalid_argument(why);
  program_cap.store(n);
}

}  // namespace boxgen::runtime
