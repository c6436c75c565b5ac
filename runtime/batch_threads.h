// How many threads the batch paths (Reconstructor::evaluate, resample) use. They run on OpenMP;
// the environment variable BOXGEN_THREADS caps them (1: the calling thread only), and a program
// may set its own cap (boxrecon --threads N), which takes precedence.
#pragma once

namespace boxgen::runtime {

// The cap in force: set_batch_threads(n) if n > 0 was set, else BOXGEN_THREADS if set, else
// OpenMP's default (the number of cores). Throws std::invalid_argument (one line) when
// BOXGEN_THREADS is not a positive integer or above max_batch_threads().
int batch_threads();

// n > 0 caps every batch path at n threads; 0 returns to BOXGEN_THREADS / the default. Throws
// std::invalid_argument (one line) for n < 0 or n > max_batch_threads().
void set_batch_threads(int n);

// The most threads a batch path may be given: 4 times the processors this process may run on
// (more only adds switching), and no more than the stacks that fit in half of the address-space
// limit (RLIMIT_AS) when one is set, each thread's stack as large as RLIMIT_STACK (8 MiB when
// that is unlimited). Beyond it OpenMP's thread creation fails and libgomp ends the process
// (the hostile trial: set_threads(66000) crashed, 33000 ended the interpreter).
int max_batch_threads();

}  // namespace boxgen::runtime
