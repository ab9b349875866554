#pragma once
// The gaze data model (docs/conventions.md has units and frames).
#include <array>
#include <cstdint>

#include <glm/vec3.hpp>

#include "foveal/core/clock.hpp"
#include "foveal/core/pose.hpp"

namespace foveal {

enum class Eye : std::uint8_t { left = 0, right = 1 };
constexpr std::array<Eye, 2> kEyes = {Eye::left, Eye::right};
const char* eye_name(Eye e);

/// Validity bits of one eye's (or the combined) data. A field whose bit is clear holds 0.
enum EyeValid : std::uint32_t {
  kValidDirection = 1u << 0,  ///< direction: unit vector in the eye frame
  kValidOrigin = 1u << 1,     ///< origin_mm: gaze origin in the head frame, mm
  kValidPupil = 1u << 2,      ///< pupil_mm: pupil diameter, mm
  kValidOpenness = 1u << 3,   ///< openness: 0 closed .. 1 open
  kValidAll = 0xFu,
};

struct EyeSample {
  std::uint32_t valid = 0;
  glm::vec3 direction{0.0f};  ///< unit; x right, y up, -z forward
  glm::vec3 origin_mm{0.0f};
  float pupil_mm = 0.0f;
  float openness = 0.0f;

  bool has(EyeValid bit) const { return (valid & bit) != 0; }
  bool operator==(const EyeSample&) const = default;
};

/// One tracker frame. `combined` uses only direction and origin. `head` is the head
/// pose at `t_ns` when the source knows it (a log with head-pose columns), else invalid.
struct GazeSample {
  TimeNs t_ns = 0;  ///< CLOCK_MONOTONIC of the runtime (or the log's own time base in files)
  std::array<EyeSample, 2> eyes{};
  EyeSample combined{};
  HeadPose head{};

  EyeSample& eye(Eye e) { return eyes[static_cast<std::size_t>(e)]; }
  const EyeSample& eye(Eye e) const { return eyes[static_cast<std::size_t>(e)]; }
  bool operator==(const GazeSample&) const = default;
};

}  // namespace foveal
