// An OpenXR "runtime" that misbehaves on purpose: hostile input for `foveal openxr`'s
// probe, not a stand-in for any part of foveal. The loader calls its negotiation
// function when it loads it; FOVEAL_TEST_RUNTIME_MODE says what happens there:
//   crash: 30 numbered lines on stderr, then SIGSEGV;
//   hang:  its pid to FOVEAL_TEST_RUNTIME_PIDFILE, then it waits for ever.
#include <signal.h>
#include <unistd.h>

#include <cstdio>
#include <cstdlib>
#include <cstring>

extern "C" __attribute__((visibility("default"))) int xrNegotiateLoaderRuntimeInterface(const void*, void*) {
  const char* mode = std::getenv("FOVEAL_TEST_RUNTIME_MODE");
  if (mode && std::strcmp(mode, "crash") == 0) {
    for (int i = 1; i <= 30; ++i) std::fprintf(stderr, "hostile runtime: line %d\n", i);
    std::fflush(stderr);
    ::raise(SIGSEGV);
  }
  if (mode && std::strcmp(mode, "hang") == 0) {
    if (const char* pidfile = std::getenv("FOVEAL_TEST_RUNTIME_PIDFILE")) {
      if (FILE* f = std::fopen(pidfile, "w")) {
        std::fprintf(f, "%d\n", static_cast<int>(::getpid()));
        std::fclose(f);
      }
    }
    for (;;) ::pause();
  }
  return -1;  // XR_ERROR_VALIDATION_FAILURE: no runtime here
}
