#pragma once
// The real HUTRR74 eye-tracker descriptor bundled in data/hid (SOURCE.md there), loaded once.
#include <vector>

#include "foveal/drivers/hid/report_descriptor.hpp"
#include "test_support.hpp"

namespace foveal::test {

inline std::vector<std::uint8_t> eye_tracker_descriptor_bytes() {
  auto bytes = hid::parse_hex_bytes(read_file(source_path("data/hid/ms_gazehid_eye_tracker.desc.hex")));
  return bytes ? *bytes : std::vector<std::uint8_t>{};
}

}  // namespace foveal::test
