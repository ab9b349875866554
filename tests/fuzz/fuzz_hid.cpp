// HID report-descriptor parser and report decoder on arbitrary bytes.
#include "fuzz_targets.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  return foveal::fuzz::hid(data, size);
}
