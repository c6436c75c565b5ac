// LeakSanitizer suppressions linked into every sanitized executable (fuzz targets, tests, CLI) (LSan calls this hook at start-up), so
// they hold however a fuzzer is run. libcln.so allocates 26 bytes in a static initialiser and
// never frees them: any program that merely loads CLN reports that leak, and libFuzzer would
// record every run as a crash. The stack of that allocation has no frame but CLN's malloc
// wrapper, so the suppression names the module; it also hides leaks of CLN numbers themselves,
// which our value-type use of cl_RA/cl_I cannot produce. Leaks of our own objects are reported.
extern "C" const char* __lsan_default_suppressions();
extern "C" const char* __lsan_default_suppressions() { return "leak:libcln.so\n"; }

// Without this LeakSanitizer prints a "Suppressions used" summary on stderr at every exit, which
// would break the one-line-on-stderr contract of the command-line programs under test.
extern "C" const char* __lsan_default_options();
extern "C" const char* __lsan_default_options() { return "print_suppressions=0"; }
