#include "frontend/input_checks.h"

#include <unistd.h>

#include <fmt/format.h>

#include <algorithm>
#include <charconv>
#include <cmath>
#include <limits>
#include <stdexcept>

#include "support/available_memory.h"

namespace boxgen::frontend {

void check_spacing(const std::optional<double>& h) {
  if (h && !(std::isfinite(*h) && *h > 0))
    throw std::invalid_argument(
        fmt::format("--h must be a finite spacing greater than 0, got {}", *h));
}

std::uint64_t parse_seed(const std::string& text) {
  std::uint64_t seed = 0;
  const char* end = text.data() + text.size();
  const auto [stop, error] = std::from_chars(text.data(), end, seed);
  if (text.empty() || error == std::errc::invalid_argument || stop != end)
    throw std::invalid_argument(fmt::format("--seed must be an integer from 0 to {}, got '{}'",
                                            std::numeric_limits<std::uint64_t>::max(),
                                            text.substr(0, 40)));
  if (error == std::errc::result_out_of_range)
    throw std::invalid_argument(fmt::format("--seed {} is out of range (0 to {})",
                                            text.substr(0, 40),
                                            std::numeric_limits<std::uint64_t>::max()));
  return seed;
}

std::uint64_t volume_memory_budget() {
  const long pages = ::sysconf(_SC_PHYS_PAGES), page_size = ::sysconf(_SC_PAGE_SIZE);
  double budget = pages > 0 && page_size > 0
                      ? static_cast<double>(pages) / 2 * static_cast<double>(page_size)
                      : 1.8e19;  // unknown: the memory available decides
  if (const double available = support::available_memory_bytes(); available > 0)
    budget = std::min(budget, available);
  return static_cast<std::uint64_t>(budget);
}

void check_memory(std::uint64_t items, std::uint64_t bytes_per_item, const std::string& what,
                  const std::string& unit) {
  const std::uint64_t budget = volume_memory_budget();
  if (items > budget / bytes_per_item) {
    constexpr double kGiB = 1024.0 * 1024.0 * 1024.0;
    throw std::invalid_argument(fmt::format(
        "{} needs {:.1f} GiB for its {} {}, more than the {:.1f} GiB allowed (half of this "
        "machine's memory, or less: what this process may still take); ask for fewer",
        what, static_cast<double>(items) * static_cast<double>(bytes_per_item) / kGiB, items, unit,
        static_cast<double>(budget) / kGiB));
  }
}

}  // namespace boxgen::frontend
