// libFuzzer entry point; the body is foveal::fuzz::vive (fuzz_targets.hpp).
#include "fuzz_targets.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  return foveal::fuzz::vive(data, size);
}
