// BOXGEN_HOST_DEVICE: a function that CUDA compiles for the host and the device (nvcc, and clang
// with or without the CUDA SDK), and plain C++ compiles as usual. The glue the C++ and CUDA
// evaluators share (support/cell_glue.h, support/integer_math.h) is marked with it.
#pragma once

#ifndef BOXGEN_HOST_DEVICE
#if defined(__host__) && defined(__device__)
#define BOXGEN_HOST_DEVICE __host__ __device__
#elif defined(__CUDA__)
#define BOXGEN_HOST_DEVICE __attribute__((host)) __attribute__((device))
#else
#define BOXGEN_HOST_DEVICE
#endif
#endif
