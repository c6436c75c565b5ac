// LeakSanitizer suppressions compiled into every sanitized executable of the build (the
// programs, the tests and the fuzz targets; cmake/BoxgenWarnings.cmake and fuzz/CMakeLists.txt
// add this file). LSan calls these hooks at start-up, so the suppressions hold however a program
// is run: no LSAN_OPTIONS and no suppression file is needed.
//
// - CLN: libcln.so allocates 26 bytes in a static initialiser and never frees them, so any
//   program that merely loads CLN would report a leak (and libFuzzer would record every run as a
//   crash). The allocation's stack has no frame but CLN's malloc wrapper, so the line names the
//   module; it also hides leaks of CLN numbers themselves, which our value-type use of cl_RA and
//   cl_I cannot produce.
// - Teem 1.12 leaks on some failed reads, a few KB to a few MB each (never when a read
//   succeeds): _nrrdRead returns without freeing its cleanup list (an airArray) when the nrrd it
//   read fails Teem's final consistency check, and the gzip and bzip2 readers return on corrupt
//   data without closing the decompressor. Teem and the compression libraries are built without
//   frame pointers, so a report shows only the allocating frame; the lines name those frames,
//   all internal to Teem, zlib and bzip2. A Nrrd or NrrdIoState that we failed to free would still
//   be reported (nrrdNew, nrrdIoStateNew).
// Leaks of our own objects are always reported.
extern "C" const char* __lsan_default_suppressions();
extern "C" const char* __lsan_default_suppressions() {
  return "leak:libcln.so\n"
         "leak:airArrayNew\nleak:airArrayLenSet\nleak:_nrrdGzOpen\nleak:libz.so\nleak:libbz2.so\n";
}

// Without this LeakSanitizer prints a "Suppressions used" summary on stderr at every exit, which
// would break the one-line-on-stderr contract of the command-line programs under test.
extern "C" const char* __lsan_default_options();
extern "C" const char* __lsan_default_options() { return "print_suppressions=0"; }
