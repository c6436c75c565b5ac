// What each source of a filter compiled from a SPEC (loader/filter_loader.cpp) starts with: the
// runtime's engine for one instruction set, this machine's (the object is compiled with
// -march=native: no dynamic dispatch inside it). It is the first thing those sources include, so
// that the build can precompile it (loader/CMakeLists.txt): parsing it is about a fifth of each
// compile. An include guard, not #pragma once: the precompiled header's guard macro then keeps
// the header's text from being read a second time.
#ifndef BOXGEN_RUNTIME_COMPILED_FILTER_H_
#define BOXGEN_RUNTIME_COMPILED_FILTER_H_

#include <memory>
#include <span>
#include <string>

#define HWY_COMPILE_ONLY_STATIC 1
#include <hwy/highway.h>

#include "runtime/batch_threads.h"
#include "runtime/emitted_filter.h"
#include "runtime/simd_kernels-inl.h"

#endif  // BOXGEN_RUNTIME_COMPILED_FILTER_H_
