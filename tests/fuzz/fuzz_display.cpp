// Display models and view files (first byte picks): a clean error or a valid result.
#include "fuzz_targets.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  return foveal::fuzz::display(data, size);
}
