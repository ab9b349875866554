#include "foveal/drivers/psvr2/psvr2_gaze_packet.hpp"

#include <cmath>
#include <string>

#include <glm/geometric.hpp>

#include "foveal/core/le_bytes.hpp"

namespace foveal::usb {
namespace {

using Reader = LeBytes;

Error at(std::size_t offset, const std::string& what) {
  return bad_input("psvr2 gaze record: byte " + std::to_string(offset) + ": " + what);
}

Status read_bool(const Reader& r, std::size_t offset, bool& out) {
  const std::uint32_t v = r.u32(offset);
  if (v > 1) return at(offset, "boolean word is " + std::to_string(v) + ", not 0 or 1");
  out = v == 1;
  return {};
}

bool finite(const glm::vec3& v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }

Status read_eye(const Reader& r, std::size_t base, Psvr2Eye& e) {
  // valid, origin vec3, valid, direction vec3, valid, pupil, (valid, vec2) x2, valid, blink
  if (Status s = read_bool(r, base, e.origin_valid); !s) return s;
  e.origin_mm = r.vec3(base + 4);
  if (Status s = read_bool(r, base + 16, e.direction_valid); !s) return s;
  e.direction = r.vec3(base + 20);
  if (Status s = read_bool(r, base + 32, e.pupil_valid); !s) return s;
  e.pupil_mm = r.f32(base + 36);
  if (Status s = read_bool(r, base + 64, e.blink_valid); !s) return s;
  if (Status s = read_bool(r, base + 68, e.blink); !s) return s;
  if ((e.origin_valid && !finite(e.origin_mm)) || (e.direction_valid && !finite(e.direction)) ||
      (e.pupil_valid && !std::isfinite(e.pupil_mm)))
    return at(base, "a valid eye value is not finite");
  return {};
}

}  // namespace

Result<Psvr2GazeRecord> parse_psvr2_gaze(std::span<const std::uint8_t> data) {
  if (data.size() < 8) return at(0, "too short for a header: " + std::to_string(data.size()) + " bytes");
  if (data[0] != psvr2::kMagic0 || data[1] != psvr2::kMagicState)
    return at(0, "not a gaze state record (magic " + std::to_string(data[0]) + " " + std::to_string(data[1]) + ")");
  if (data.size() < psvr2::kRecordBytes)
    return at(data.size(), "truncated: " + std::to_string(data.size()) + " of " + std::to_string(psvr2::kRecordBytes) +
                               " bytes");
  const Reader r(data);
  Psvr2GazeRecord rec;
  rec.version = static_cast<std::uint16_t>(data[2] | data[3] << 8);
  rec.size = r.u32(4);
  if (rec.size < psvr2::kRecordBytes || rec.size > data.size())
    return at(4, "size field " + std::to_string(rec.size) + " does not fit the " + std::to_string(data.size()) +
                     "-byte transfer");
  if (Status s = read_eye(r, psvr2::kLeftEye, rec.eyes[0]); !s) return s.error();
  if (Status s = read_eye(r, psvr2::kRightEye, rec.eyes[1]); !s) return s.error();
  const std::size_t c = psvr2::kCombined;
  if (Status s = read_bool(r, c, rec.combined_origin_valid); !s) return s.error();
  rec.combined_origin_mm = r.vec3(c + 4);
  if (Status s = read_bool(r, c + 16, rec.combined_direction_valid); !s) return s.error();
  rec.combined_direction = r.vec3(c + 20);
  if (Status s = read_bool(r, c + 32, rec.combined_valid); !s) return s.error();
  rec.timestamp_us = r.u32(c + 36);
  if ((rec.combined_origin_valid && !finite(rec.combined_origin_mm)) ||
      (rec.combined_direction_valid && !finite(rec.combined_direction)))
    return at(c, "a valid combined value is not finite");
  return rec;
}

namespace {

glm::vec3 to_head(const glm::vec3& v) { return {-v.x, v.y, -v.z}; }

}  // namespace

GazeSample psvr2_to_sample(const Psvr2GazeRecord& r) {
  GazeSample s;
  for (std::size_t i = 0; i < 2; ++i) {
    const Psvr2Eye& e = r.eyes[i];
    EyeSample& out = s.eyes[i];
    const float len = glm::length(e.direction);
    if (e.direction_valid && len > 0.5f && len < 1.5f) {  // a unit vector, give or take float noise
      out.direction = to_head(e.direction) / len;
      out.valid |= kValidDirection;
    }
    if (e.origin_valid) {
      out.origin_mm = to_head(e.origin_mm);
      out.valid |= kValidOrigin;
    }
    if (e.pupil_valid && e.pupil_mm > 0) {
      out.pupil_mm = e.pupil_mm;
      out.valid |= kValidPupil;
    }
    if (e.blink_valid) {
      out.openness = e.blink ? 0.0f : 1.0f;
      out.valid |= kValidOpenness;
    }
  }
  const float len = glm::length(r.combined_direction);
  if (r.combined_direction_valid && len > 0.5f && len < 1.5f) {
    s.combined.direction = to_head(r.combined_direction) / len;
    s.combined.valid |= kValidDirection;
  }
  if (r.combined_origin_valid) {
    s.combined.origin_mm = to_head(r.combined_origin_mm);
    s.combined.valid |= kValidOrigin;
  }
  return s;
}

std::int64_t WrapCounter::unwrap_ns(std::uint32_t us) {
  if (started_ && us < last_ && last_ - us > 0x8000'0000u) ++wraps_;  // wrapped, not reordered
  started_ = true;
  last_ = us;
  return ((wraps_ << 32) + static_cast<std::int64_t>(us)) * 1000;
}

}  // namespace foveal::usb
