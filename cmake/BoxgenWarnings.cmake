# Warnings are errors for the project's own code only; third-party headers
# (GiNaC, CLN, fmt, GoogleTest) come in as SYSTEM includes through their targets.
function(boxgen_warnings target)
  target_compile_options(${target} PRIVATE -Wall -Wextra -Wpedantic -Wshadow -Wnon-virtual-dtor -Werror)
  # GCC 12 reports -Wrestrict and -Wfree-nonheap-object inside inlined libstdc++ string and
  # vector code at -O2 where there is no overlap or bad free (GCC bugs 105329, 105651):
  # those two diagnostics are off for GCC 12 only; clang builds (fuzz) keep everything.
  if(CMAKE_CXX_COMPILER_ID STREQUAL "GNU" AND CMAKE_CXX_COMPILER_VERSION VERSION_LESS 13)
    target_compile_options(${target} PRIVATE -Wno-restrict -Wno-free-nonheap-object)
    # Sanitizer instrumentation defeats GCC 12's flow analysis: it reports -Wmaybe-uninitialized
    # inside libstdc++ (std::regex, std::function) where nothing is uninitialised. The optimised
    # build keeps the warning as an error (it found a real bug in the emitted lookup code).
    if(BOXGEN_SANITIZE)
      target_compile_options(${target} PRIVATE -Wno-maybe-uninitialized)
    endif()
  endif()
endfunction()

# Every executable of a sanitized build carries the LeakSanitizer suppression for CLN's one-off
# start-up allocation and Teem's leaks on failed reads (support/lsan_suppressions.cpp); without it GoogleTest discovery and
# every CLI run would fail at exit.
function(boxgen_executable target)
  boxgen_warnings(${target})
  if(BOXGEN_SANITIZE)
    target_sources(${target} PRIVATE ${PROJECT_SOURCE_DIR}/support/lsan_suppressions.cpp)
  endif()
endfunction()
