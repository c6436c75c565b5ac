// How much memory this process may still take, for the checks that refuse a request before
// allocating it (docs/errors.md "Memory"): a limit must come from what is actually available,
// not from the machine's size alone, or an address-space limit (ulimit -v) or a container's
// memory limit turns a refusal into std::bad_alloc or the OOM killer.
#pragma once

namespace boxgen::support {

// The least of: MemAvailable of /proc/meminfo; the address-space limit (RLIMIT_AS) less what the
// process has mapped (VmSize of /proc/self/status); the cgroup v2 memory.max less memory.current.
// In bytes; 0 where none of them can be read (then only fixed caps apply).
double available_memory_bytes();

}  // namespace boxgen::support
