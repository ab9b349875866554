#pragma once
// The PlayStation VR2 gaze record read from interface 5, bulk endpoint 0x85. The layout
// is reverse engineered by others (Monado, psvr2-toolkit) and not documented by Sony;
// docs/drivers.md lists what is known and what this parser relies on. All values are
// little-endian; booleans are 32-bit words holding 0 or 1.
#include <array>
#include <cstdint>
#include <span>

#include <glm/vec3.hpp>

#include "foveal/core/error.hpp"
#include "foveal/core/gaze_sample.hpp"

namespace foveal::usb {

constexpr std::uint16_t kPsvr2Vendor = 0x054c, kPsvr2Product = 0x0cde;
constexpr int kPsvr2GazeInterface = 5;
constexpr std::uint8_t kPsvr2GazeEndpoint = 0x85;

/// Record layout: offsets in bytes.
namespace psvr2 {
constexpr std::uint8_t kMagic0 = 'G', kMagicState = 'S';
constexpr std::size_t kLeftEye = 92, kRightEye = 164, kCombined = 236;
constexpr std::size_t kEyeBlockBytes = 72;
constexpr std::size_t kRecordBytes = 328;  ///< header + per-eye blocks + combined block
}  // namespace psvr2

/// One eye as the headset reports it, in its own frame (x left, y up, +z forward).
struct Psvr2Eye {
  bool origin_valid = false, direction_valid = false, pupil_valid = false, blink_valid = false;
  glm::vec3 origin_mm{0.0f}, direction{0.0f};
  float pupil_mm = 0;
  bool blink = false;
};

struct Psvr2GazeRecord {
  std::uint16_t version = 0;
  std::uint32_t size = 0;
  std::array<Psvr2Eye, 2> eyes{};
  bool combined_origin_valid = false, combined_direction_valid = false, combined_valid = false;
  glm::vec3 combined_origin_mm{0.0f}, combined_direction{0.0f};
  std::uint32_t timestamp_us = 0;  ///< wraps every 2^32 us (~71.6 min)
};

/// Parses one record. Errors (bad_input) name the offset: wrong magic, too short, a size
/// field that disagrees, a boolean word other than 0/1, a non-finite valid value.
Result<Psvr2GazeRecord> parse_psvr2_gaze(std::span<const std::uint8_t> data);

/// The record as a GazeSample in the head frame (docs/conventions.md: x right, y up,
/// -z forward; x and z flip). Openness is 0 during a blink, 1 otherwise, when the blink
/// flag is valid. t_ns is left to the caller.
GazeSample psvr2_to_sample(const Psvr2GazeRecord& r);

/// Extends the wrapping 32-bit microsecond counter to 64-bit nanoseconds.
class WrapCounter {
 public:
  std::int64_t unwrap_ns(std::uint32_t us);

 private:
  bool started_ = false;
  std::uint32_t last_ = 0;
  std::int64_t wraps_ = 0;
};

}  // namespace foveal::usb
