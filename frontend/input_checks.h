// boxrecon's checks of argument values that CLI11 cannot express: each refuses a bad value with
// std::invalid_argument (one line; exit code 1) before any work, instead of a silent default, a
// silent wrap-around or an allocation that cannot succeed.
#pragma once
#include <cstdint>
#include <optional>
#include <string>

namespace boxgen::frontend {

// --h: absent, or finite and > 0.
void check_spacing(const std::optional<double>& h);

// --seed: a decimal integer in [0, 2^64 - 1]; no sign, no wrap-around.
std::uint64_t parse_seed(const std::string& text);

// The one memory pre-check of every command: `items` (samples, points, pixels) of
// `bytes_per_item` bytes each must fit in volume_memory_budget(), half of the machine's physical
// memory (the other half leaves room for the prefiltered copy that eval, error, resample and
// render make), or what this process may still take when that is less (an address-space or
// cgroup limit, support/available_memory.h); else std::invalid_argument naming the size needed, the
// budget and `what` (the option that asked, e.g. "--n 1024" or "--points 1000000").
void check_memory(std::uint64_t items, std::uint64_t bytes_per_item, const std::string& what,
                  const std::string& unit);

// The budget check_memory allows, in bytes: half of the physical memory, or the memory this
// process may still take when that is less.
std::uint64_t volume_memory_budget();

}  // namespace boxgen::frontend
