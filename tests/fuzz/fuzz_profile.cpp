// Profile reader: a hand-broken profile is an error, never a crash or a half-load.
#include "fuzz_targets.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  return foveal::fuzz::profile(data, size);
}
