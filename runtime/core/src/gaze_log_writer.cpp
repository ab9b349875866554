#include <charconv>
#include <cmath>

#include "foveal/core/gaze_log.hpp"

namespace foveal {

namespace {

void append_float(std::string& row, float v) {
  char buf[32];
  auto [p, ec] = std::to_chars(buf, buf + sizeof buf, v);  // shortest form that reads back exactly
  (void)ec;
  row.append(buf, p);
}

void append_int(std::string& row, std::int64_t v) {
  char buf[24];
  auto [p, ec] = std::to_chars(buf, buf + sizeof buf, v);
  (void)ec;
  row.append(buf, p);
}

}  // namespace

Result<GazeLogWriter> GazeLogWriter::create(const std::string& path, const GazeLogHeader& header) {
  if (!(header.rate_hz > 0) || !std::isfinite(header.rate_hz))
    return bad_input(path + ": rate_hz must be a positive number");
  for (const auto& [k, v] : header.meta)
    if (k.empty() || k.find_first_of("=\n\r") != std::string::npos || v.find_first_of("\n\r") != std::string::npos)
      return bad_input(path + ": header key '" + k + "' or its value has a forbidden character");
  if (header.version != kGazeLogV1 && header.version != kGazeLogV2)
    return Error{ErrorKind::unsupported, path + ": format version v" + std::to_string(header.version) +
                                             " cannot be written (this build writes v1 and v2)"};
  auto f = AtomicFile::create(path);
  if (!f) return f.error();
  GazeLogWriter w(std::move(f.value()), header.has_head_pose());
  std::string head = std::string(kGazeLogMagic) + std::to_string(header.version) + "\n";
  char rate[32];
  auto [p, ec] = std::to_chars(rate, rate + sizeof rate, header.rate_hz);
  (void)ec;
  head += "# rate_hz=" + std::string(rate, p) + "\n";
  for (const auto& [k, v] : header.meta) head += "# " + k + "=" + v + "\n";
  const auto& cols = gaze_log_columns(header.version);
  for (std::size_t i = 0; i < cols.size(); ++i) head += (i ? "," : "") + cols[i];
  head += "\n";
  w.file_.write(head);
  return w;
}

Status GazeLogWriter::mark(const GazeMarker& m) {
  if (Status s = check_marker_text(m.text); !s) return bad_input(file_.path() + ": " + s.error().message);
  if (any_row_ && m.t_ns < last_row_t_)
    return bad_input(file_.path() + ": mark: time " + std::to_string(m.t_ns) + " is earlier than the row before it (" +
                     std::to_string(last_row_t_) + ")");
  if (m.t_ns < -kMaxGazeLogTimeNs || m.t_ns >= kMaxGazeLogTimeNs)
    return bad_input(file_.path() + ": mark: time " + std::to_string(m.t_ns) + " is out of range ([-2^62, 2^62) ns)");
  file_.write(marker_row(m));
  last_row_t_ = m.t_ns;
  any_row_ = true;
  return {};
}

Status GazeLogWriter::write(const GazeSample& s) {
  if (samples_ > 0 && s.t_ns <= last_t_)
    return bad_input(file_.path() + ": sample " + std::to_string(samples_ + 1) + ": timestamp " +
                     std::to_string(s.t_ns) + " does not increase");
  if (any_row_ && s.t_ns < last_row_t_)
    return bad_input(file_.path() + ": sample " + std::to_string(samples_ + 1) + ": timestamp " +
                     std::to_string(s.t_ns) + " is earlier than the marker before it");
  if (s.t_ns < -kMaxGazeLogTimeNs || s.t_ns >= kMaxGazeLogTimeNs)
    return bad_input(file_.path() + ": sample " + std::to_string(samples_ + 1) + ": timestamp " +
                     std::to_string(s.t_ns) + " is out of range ([-2^62, 2^62) ns)");
  row_.clear();
  append_int(row_, s.t_ns);
  auto put = [&](bool present, float v) -> bool {
    row_ += ',';
    if (!present) return true;
    if (!std::isfinite(v)) return false;
    append_float(row_, v);
    return true;
  };
  auto block = [&](const EyeSample& e, bool with_pupil) -> bool {
    row_ += ',';
    append_int(row_, e.valid & (with_pupil ? kValidAll : 3u));
    bool ok = true;
    for (int i = 0; i < 3; ++i) ok &= put(e.has(kValidDirection), e.direction[i]);
    for (int i = 0; i < 3; ++i) ok &= put(e.has(kValidOrigin), e.origin_mm[i]);
    if (with_pupil) {
      ok &= put(e.has(kValidPupil), e.pupil_mm);
      ok &= put(e.has(kValidOpenness), e.openness);
    }
    return ok;
  };
  // Every block is written (no short-circuit): the row stays complete either way.
  bool ok = block(s.eyes[0], true);
  ok = block(s.eyes[1], true) && ok;
  ok = block(s.combined, false) && ok;
  if (!ok)
    return bad_input(file_.path() + ": sample " + std::to_string(samples_ + 1) +
                     ": a field marked valid is NaN or infinite");
  if (s.head.valid && !head_)
    return bad_input(file_.path() + ": sample " + std::to_string(samples_ + 1) +
                     ": has a head pose, but a v1 log has no head-pose columns (write v2)");
  if (head_) {
    const Pose& h = s.head.pose;
    row_ += s.head.valid ? ",1" : ",0";
    bool finite = true;
    for (float v : {h.position_m.x, h.position_m.y, h.position_m.z, h.orientation.w, h.orientation.x, h.orientation.y,
                    h.orientation.z})
      finite = put(s.head.valid, v) && finite;
    if (!finite || (s.head.valid && !is_unit(h.orientation)))
      return bad_input(file_.path() + ": sample " + std::to_string(samples_ + 1) +
                       ": the head pose is not finite or its orientation is not a unit quaternion");
  }
  row_ += '\n';
  file_.write(row_);
  last_t_ = last_row_t_ = s.t_ns;
  any_row_ = true;
  ++samples_;
  return {};
}

}  // namespace foveal
