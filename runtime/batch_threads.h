// How many threads the batch paths (Reconstructor::evaluate, resample) use. They run on OpenMP;
// the environment variable BOXGEN_THREADS caps them (1: the calling thread only), and a program
// may set its own cap (boxrecon --threads N), which takes precedence.
#pragma once

namespace boxgen::runtime {

// The cap in force: set_batch_threads(n) if n > 0 was set, else BOXGEN_THREADS if set, else
// OpenMP's default (the number of cores). Throws std::invalid_argument (one line) when
// BOXGEN_THREADS is not a positive integer.
int batch_threads();

// n > 0 caps every batch path at n threads; 0 returns to BOXGEN_THREADS / the default. Throws
// std::invalid_argument for n < 0.
void set_batch_threads(int n);

}  // namespace boxgen::runtime
