// Native gaze-log reader: any bytes must give samples or a clean error, never a crash.
#include "fuzz_targets.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  return foveal::fuzz::gaze_log(data, size);
}
