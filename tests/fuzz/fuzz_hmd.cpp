// libFuzzer entry point; the body is foveal::fuzz::hmd (fuzz_targets.hpp).
#include "fuzz_targets.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  return foveal::fuzz::hmd(data, size);
}
