// SRanipal and Pupil importers: clean error or a valid log, never a crash; a failed
// import leaves no output file.
#include "fuzz_targets.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  return foveal::fuzz::import(data, size);
}
