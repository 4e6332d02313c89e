// Compiled into every program of a sanitizer build (STEADY_SANITIZE, see CMakeLists.txt): the sanitizers' default
// options and the leak suppressions, so that ctest, gtest's test discovery, the fuzz targets and a program run by
// hand all behave alike. ASAN_OPTIONS / UBSAN_OPTIONS / LSAN_OPTIONS in the environment still override these.
//
// Suppressions are for third-party code only (docs/reliability.md): Debian's OpenCASCADE and oneTBB are not
// instrumented, and what they allocate once per process and keep until exit is not a leak of ours.

extern "C" {

// halt_on_error: the first report ends the program (no test passes with a report);
// detect_stack_use_after_return stays off: it doubles the tests' time and the kernel keeps no stack addresses.
const char* __asan_default_options() {
  return "halt_on_error=1:abort_on_error=1:detect_leaks=1:check_initialization_order=1:strict_init_order=1";
}

const char* __ubsan_default_options() { return "halt_on_error=1:print_stacktrace=1"; }

const char* __lsan_default_suppressions() {
  return "";
}

}  // extern "C"
