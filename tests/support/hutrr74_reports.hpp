#pragma once
// Builds reports of the real HUTRR74 tracker descriptor (data/hid) byte by byte, from
// its layout as read off the descriptor by hand: an encoder independent of the decoder,
// for unit tests, the VM feeder and the uhid device.
#include <array>
#include <cstdint>
#include <vector>

namespace foveal::test::hutrr74 {

inline void put_le(std::vector<std::uint8_t>& r, std::size_t at, std::uint64_t v, int bytes) {
  for (int k = 0; k < bytes; ++k) r[at + static_cast<std::size_t>(k)] = static_cast<std::uint8_t>(v >> (8 * k));
}
inline void put_i32(std::vector<std::uint8_t>& r, std::size_t at, std::int32_t v) {
  put_le(r, at, static_cast<std::uint32_t>(v), 4);
}

struct Tracking {
  std::uint64_t timestamp_us = 0;
  std::int32_t gaze_x_um = 0, gaze_y_um = 0;
  std::array<std::int32_t, 3> left_um{0, 0, 0}, right_um{0, 0, 0};
};

constexpr std::size_t kTrackingBytes = 65;

/// Input report 0x10: timestamp (8 bytes), gaze X/Y, left eye X/Y/Z, right eye X/Y/Z, 6 head fields.
inline std::vector<std::uint8_t> tracking_report(const Tracking& t) {
  std::vector<std::uint8_t> r(kTrackingBytes, 0);
  r[0] = 0x10;
  put_le(r, 1, t.timestamp_us, 8);
  put_i32(r, 9, t.gaze_x_um);
  put_i32(r, 13, t.gaze_y_um);
  for (std::size_t k = 0; k < 3; ++k) {
    put_i32(r, 17 + 4 * k, t.left_um[k]);
    put_i32(r, 29 + 4 * k, t.right_um[k]);
  }
  return r;
}

/// Tracker Status 0x13 (input or feature): configuration status, sampling frequency.
inline std::vector<std::uint8_t> status_report(std::uint8_t configuration_status, std::uint16_t hz) {
  std::vector<std::uint8_t> r(4, 0);
  r[0] = 0x13;
  r[1] = configuration_status;
  put_le(r, 2, hz, 2);
  return r;
}

/// Capabilities 0x11: quality, min/optimum/max distance, max screen width/height (um).
inline std::vector<std::uint8_t> capabilities_report(std::uint8_t quality, std::int32_t min_um, std::int32_t opt_um,
                                                     std::int32_t max_um, std::int32_t width_um, std::int32_t height_um) {
  std::vector<std::uint8_t> r(22, 0);
  r[0] = 0x11;
  r[1] = quality;
  put_i32(r, 2, min_um);
  put_i32(r, 6, opt_um);
  put_i32(r, 10, max_um);
  put_i32(r, 14, width_um);
  put_i32(r, 18, height_um);
  return r;
}

/// Configuration 0x12: display IDs and the calibrated screen size (um).
inline std::vector<std::uint8_t> configuration_report(std::int32_t width_um, std::int32_t height_um) {
  std::vector<std::uint8_t> r(19, 0);
  r[0] = 0x12;
  put_le(r, 1, 0x1234, 2);  // display manufacturer ID
  put_le(r, 3, 0x5678, 2);  // display product ID
  put_le(r, 5, 42, 4);      // serial
  put_le(r, 9, 2024, 2);    // date
  put_i32(r, 11, width_um);
  put_i32(r, 15, height_um);
  return r;
}

}  // namespace foveal::test::hutrr74
