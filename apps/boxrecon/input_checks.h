// boxrecon's checks of argument values that CLI11 cannot express: each refuses a bad value with
// std::invalid_argument (one line; exit code 1) before any work, instead of a silent default, a
// silent wrap-around or an allocation that cannot succeed.
#pragma once
#include <cstdint>
#include <optional>
#include <string>

namespace boxgen::app {

// --h: absent, or finite and > 0.
void check_spacing(const std::optional<double>& h);

// --seed: a decimal integer in [0, 2^64 - 1]; no sign, no wrap-around.
std::uint64_t parse_seed(const std::string& text);

// The memory a volume of `samples` values of `bytes_per_sample` bytes needs must be at most half
// of the machine's physical memory (the other half leaves room for the prefiltered copy that
// eval, error and resample make). `what` names the request in the message, e.g. "--n 1024".
void check_volume_memory(std::uint64_t samples, std::uint64_t bytes_per_sample,
                         const std::string& what);

// The one memory pre-check of every command: `items` (samples, points, pixels) of
// `bytes_per_item` bytes each must fit in volume_memory_budget(); else std::invalid_argument
// naming the size needed, the budget and `what` (the option that asked, e.g. "--points 1000000").
void check_memory(std::uint64_t items, std::uint64_t bytes_per_item, const std::string& what,
                  const std::string& unit);

// Half of the physical memory (the budget check_volume_memory allows), in bytes.
std::uint64_t volume_memory_budget();

}  // namespace boxgen::app
