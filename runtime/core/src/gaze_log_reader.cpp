#include <algorithm>
#include <cmath>
#include <cstdio>

#include "foveal/core/gaze_log.hpp"
#include "foveal/core/text_fields.hpp"

namespace foveal {

namespace {

constexpr std::size_t kEyeFields = 9;       // valid, dir xyz, origin xyz, pupil, openness
constexpr std::size_t kCombinedFields = 7;  // valid, dir xyz, origin xyz
constexpr std::size_t kHeadFields = 8;      // valid, position xyz, quaternion wxyz (v2)
constexpr std::size_t kHeadColumn = 1 + 2 * kEyeFields + kCombinedFields;  // head_valid's index
constexpr const char* kHeadQuatColumns = "head_qw..head_qz";
constexpr const char* kExpectedMagic = "expected '# foveal-gaze-log v1' or '... v2'";

std::size_t row_fields(int version) { return kHeadColumn + (version >= kGazeLogV2 ? kHeadFields : 0); }

std::string where(const std::string& path, std::uint64_t line) {
  return path + ":" + std::to_string(line);
}

std::string quat_norm_error(const glm::quat& q) {
  char buf[160];
  std::snprintf(buf, sizeof buf, "quaternion norm %.6g is not 1 (tolerance %g): not a head orientation", quaternion_norm(q),
                static_cast<double>(kUnitQuaternionTolerance));
  return buf;
}

std::string head_position_error(float m) {
  char buf[160];
  std::snprintf(buf, sizeof buf, "%.6g m is out of range (a head position is within ±%g m of the tracking origin)",
                static_cast<double>(m), static_cast<double>(kMaxHeadPositionM));
  return buf;
}

}  // namespace

Error GazeLogReader::row_error(std::uint64_t line, std::string_view column, const std::string& what) const {
  return bad_input(where(path(), line) + ": " + std::string(column) + ": " + what);
}

Result<GazeLogReader> GazeLogReader::open(const std::string& path) {
  auto lines = LineReader::open(path);
  if (!lines) return lines.error();
  GazeLogReader r(std::move(lines.value()));
  if (Status s = r.read_header(); !s) return s.error();
  return r;
}

Status GazeLogReader::read_header() {
  header_ = GazeLogHeader{};
  LineReader::Line line;
  auto check_line = [&](const LineReader::Line& l) -> Status {
    if (l.crlf)
      return bad_input(where(path(), l.number) + ": line ends in CRLF; gaze logs use LF line ends");
    if (!l.terminated)
      return bad_input(where(path(), l.number) + ": truncated: the file ends inside this line");
    return {};
  };
  auto got = lines_.next(line);
  if (!got) return got.error();
  if (!*got) return bad_input(where(path(), 1) + ": file is empty; " + kExpectedMagic);
  if (line.text.size() >= 3 && static_cast<unsigned char>(line.text[0]) == 0xEF &&
      static_cast<unsigned char>(line.text[1]) == 0xBB && static_cast<unsigned char>(line.text[2]) == 0xBF)
    return bad_input(where(path(), 1) + ": starts with a UTF-8 byte-order mark; gaze logs have none");
  if (line.text.substr(0, kGazeLogMagic.size()) != kGazeLogMagic)
    return bad_input(where(path(), 1) + ": not a foveal gaze log; " + kExpectedMagic);
  if (Status s = check_line(line); !s) return s;
  {
    const std::string_view v = line.text.substr(kGazeLogMagic.size());
    int version = 0;
    if (!parse_number(v, version))
      return bad_input(where(path(), 1) + ": format version: '" + std::string(v) + "' is not a number");
    if (version != kGazeLogV1 && version != kGazeLogV2)
      return Error{ErrorKind::unsupported, where(path(), 1) + ": format version: v" + std::to_string(version) +
                                          " is not supported (this build reads v1 and v2)"};
    header_.version = version;
  }
  // "# key=value" lines, then the column row.
  for (;;) {
    got = lines_.next(line);
    if (!got) return got.error();
    if (!*got) return bad_input(where(path(), line.number + 1) + ": header: the column row is missing");
    if (Status s = check_line(line); !s) return s;
    if (line.text.empty() || line.text[0] != '#') break;
    std::string_view kv = line.text.substr(1);
    while (!kv.empty() && kv.front() == ' ') kv.remove_prefix(1);
    const auto eq = kv.find('=');
    if (eq == std::string_view::npos || eq == 0)
      return bad_input(where(path(), line.number) + ": header: expected '# key=value'");
    const std::string key(kv.substr(0, eq));
    const std::string value(kv.substr(eq + 1));
    if (key == "rate_hz") {
      if (!parse_number(std::string_view(value), header_.rate_hz) || !std::isfinite(header_.rate_hz) ||
          header_.rate_hz <= 0 || header_.rate_hz > 100000)
        return bad_input(where(path(), line.number) + ": rate_hz: '" + value + "' is not a rate in (0, 100000] Hz");
    } else {
      header_.meta[key] = value;
    }
  }
  if (header_.rate_hz <= 0)
    return bad_input(where(path(), line.number) + ": header: '# rate_hz=...' is missing");
  split_fields(line.text, ',', fields_);
  const auto& cols = gaze_log_columns(header_.version);
  for (std::size_t i = 0; i < cols.size(); ++i) {
    if (i >= fields_.size())
      return bad_input(where(path(), line.number) + ": column row: column '" + cols[i] + "' is missing");
    if (fields_[i] != cols[i])
      return bad_input(where(path(), line.number) + ": column row: column " + std::to_string(i + 1) +
                       " is '" + std::string(fields_[i]) + "', expected '" + cols[i] + "'");
  }
  if (fields_.size() > cols.size())
    return bad_input(where(path(), line.number) + ": column row: unexpected extra column '" +
                     std::string(fields_[cols.size()]) + "'");
  return {};
}

Status GazeLogReader::rewind() {
  if (Status s = lines_.rewind(); !s) return s;
  samples_ = 0;
  last_t_ = 0;
  markers_.clear();
  return read_header();
}

Status GazeLogReader::read_marker(const LineReader::Line& line) {
  if (line.text.substr(0, kMarkerRowPrefix.size()) != kMarkerRowPrefix)
    return bad_input(where(path(), line.number) + ": a row starting with '#' is a marker row, '#mark,T_NS,TEXT'");
  if (!line.terminated)
    return bad_input(where(path(), line.number) + ": truncated: the file ends inside this marker row");
  auto m = parse_marker_row(line.text);
  if (!m) return bad_input(where(path(), line.number) + ": " + m.error().message);
  // Rows are in time order, so the latest time so far is the previous row's.
  const bool any_row = samples_ > 0 || !markers_.empty();
  const TimeNs before = std::max(samples_ > 0 ? last_t_ : INT64_MIN, markers_.empty() ? INT64_MIN : markers_.back().t_ns);
  if (any_row && m->t_ns < before)
    return bad_input(where(path(), line.number) + ": t_ns: marker time " + std::to_string(m->t_ns) +
                     " is earlier than the row before it (" + std::to_string(before) + ")");
  if (markers_.size() >= kMaxGazeLogMarkers)
    return bad_input(where(path(), line.number) + ": more than " + std::to_string(kMaxGazeLogMarkers) +
                     " markers; a gaze log holds at most that many");
  markers_.push_back(std::move(m.value()));
  return {};
}

Result<bool> GazeLogReader::next(GazeSample& out) {
  LineReader::Line line;
  for (;;) {  // marker rows are kept aside; the first sample row ends the loop
    auto got = lines_.next(line);
    if (!got) return got.error();
    if (!*got) {
      if (samples_ == 0) return bad_input(path() + ": no samples: the log has a header only");
      return false;
    }
    if (line.crlf) return bad_input(where(path(), line.number) + ": line ends in CRLF; gaze logs use LF line ends");
    if (line.text.empty() || line.text[0] != '#') break;
    if (Status s = read_marker(line); !s) return s.error();
  }

  // One pass over the row: each field is parsed where it starts and must end at a ','
  // (or the line's end for the last). This is the replay hot path; the slow path
  // (describe_row_error) re-reads the row to say exactly what is wrong.
  const char* p = line.text.data();
  const char* const end = p + line.text.size();
  GazeSample& s = out;  // parsed in place; `out` is unspecified after an error
  auto field_end = [&](const char* q) { return q == end || *q == ','; };
  auto advance = [&](const char* q, bool last) -> const char* {
    if (last) return q == end ? q : nullptr;
    return q != end && *q == ',' ? q + 1 : nullptr;
  };
  bool ok = true;
  {
    auto [q, ec] = std::from_chars(p, end, s.t_ns);
    ok = ec == std::errc() && (p = advance(q, false)) != nullptr;
  }
  auto read_float = [&](bool present, float& dst, bool last) {
    if (!ok) return;
    if (!present) {
      dst = 0.0f;
      ok = field_end(p) && (p = advance(p, last)) != nullptr;
      return;
    }
    const char* q = detail::parse_float_prefix<true>(p, end, dst);
    if (!q) {  // rare: let from_chars decide
      q = p;
      while (!field_end(q)) ++q;
      auto [r, ec] = std::from_chars(p, q, dst);
      if (ec != std::errc() || r != q) q = nullptr;
    }
    ok = q && q != p && std::isfinite(dst) && (p = advance(q, last)) != nullptr;
  };
  auto read_block = [&](EyeSample& e, bool with_pupil, bool last_block) {
    if (!ok) return;
    // The mask is one or two digits (0..15): no need for from_chars.
    const char* q = p;
    e.valid = 0;
    while (q != end && static_cast<unsigned>(*q - '0') < 10 && q - p < 3) e.valid = e.valid * 10 + static_cast<unsigned>(*q++ - '0');
    ok = q != p && e.valid <= (with_pupil ? kValidAll : 3u) && (p = advance(q, false)) != nullptr;
    for (int i = 0; i < 3; ++i) read_float(e.has(kValidDirection), e.direction[i], false);
    for (int i = 0; i < 3; ++i) read_float(e.has(kValidOrigin), e.origin_mm[i], last_block && !with_pupil && i == 2);
    if (with_pupil) {
      read_float(e.has(kValidPupil), e.pupil_mm, false);
      read_float(e.has(kValidOpenness), e.openness, last_block);
    }
  };
  const bool with_head = header_.has_head_pose();
  read_block(s.eyes[0], true, false);
  read_block(s.eyes[1], true, false);
  read_block(s.combined, false, !with_head);
  s.combined.pupil_mm = s.combined.openness = 0.0f;  // not stored for the combined gaze
  s.head = HeadPose{};
  if (with_head && ok) {
    const char flag = p != end ? *p : '\0';
    s.head.valid = flag == '1';
    ok = (flag == '0' || flag == '1') && (p = advance(p + 1, false)) != nullptr;
    Pose& h = s.head.pose;
    float* dst[] = {&h.position_m.x, &h.position_m.y, &h.position_m.z, &h.orientation.w,
                    &h.orientation.x, &h.orientation.y, &h.orientation.z};
    for (int i = 0; i < 7; ++i) read_float(s.head.valid, *dst[i], i == 6);
    if (ok && s.head.valid && !is_unit(h.orientation))
      return row_error(line.number, kHeadQuatColumns, quat_norm_error(h.orientation));
    for (int i = 0; ok && s.head.valid && i < 3; ++i)
      if (!(std::abs(*dst[i]) <= kMaxHeadPositionM))
        return row_error(line.number, gaze_log_columns(header_.version)[kHeadColumn + 1 + static_cast<std::size_t>(i)],
                         head_position_error(*dst[i]));
    if (!s.head.valid) h = Pose{};  // read_float wrote zeros
  }
  if (!ok || !line.terminated) return describe_row_error(line);
  if (s.t_ns < -kMaxGazeLogTimeNs || s.t_ns >= kMaxGazeLogTimeNs)
    return row_error(line.number, gaze_log_columns()[0],
                     std::to_string(s.t_ns) + " is out of range (timestamps are in [-2^62, 2^62) ns, ±146 years)");
  if (samples_ > 0 && s.t_ns <= last_t_)
    return row_error(line.number, gaze_log_columns()[0],
                     std::to_string(s.t_ns) +
                         (s.t_ns == last_t_ ? " repeats the previous timestamp"
                                            : " goes back from " + std::to_string(last_t_)) +
                         "; timestamps must increase strictly");
  if (!markers_.empty() && s.t_ns < markers_.back().t_ns)
    return row_error(line.number, gaze_log_columns()[0],
                     std::to_string(s.t_ns) + " is earlier than the marker before it (" +
                         std::to_string(markers_.back().t_ns) + ")");
  last_t_ = s.t_ns;
  ++samples_;
  return true;
}

Error GazeLogReader::describe_row_error(const LineReader::Line& line) {
  const auto& cols = gaze_log_columns(header_.version);
  const std::size_t want = row_fields(header_.version);
  split_fields(line.text, ',', fields_);
  if (fields_.size() < want) {
    const std::string what = line.terminated ? "missing (row has " + std::to_string(fields_.size()) + " of " +
                                                   std::to_string(want) + " fields)"
                                             : "missing: truncated last row (no line end)";
    return row_error(line.number, cols[fields_.size()], what);
  }
  if (fields_.size() > want)
    return bad_input(where(path(), line.number) + ": row has " + std::to_string(fields_.size()) +
                     " fields, expected " + std::to_string(want));
  if (!line.terminated) return bad_input(where(path(), line.number) + ": truncated last row (no line end)");

  std::int64_t t = 0;
  if (!parse_number(fields_[0], t))
    return row_error(line.number, cols[0], "'" + std::string(fields_[0]) + "' is " + number_problem<std::int64_t>(fields_[0], "not an integer"));
  std::size_t col = 1;
  std::uint32_t valid = 0;
  for (int block = 0; block < 3; ++block) {
    const bool with_pupil = block < 2;
    const std::uint32_t max_mask = with_pupil ? kValidAll : 3u;
    if (!parse_number(fields_[col], valid) || valid > max_mask)
      return row_error(line.number, cols[col], "'" + std::string(fields_[col]) + "' is not a validity mask (0.." +
                                                   std::to_string(max_mask) + ")");
    ++col;
    const std::uint32_t bits[] = {kValidDirection, kValidDirection, kValidDirection, kValidOrigin,
                                  kValidOrigin,    kValidOrigin,    kValidPupil,     kValidOpenness};
    for (int i = 0; i < (with_pupil ? 8 : 6); ++i, ++col) {
      const std::string_view f = fields_[col];
      const bool present = (valid & bits[i]) != 0;
      if (!present && !f.empty()) return row_error(line.number, cols[col], "has a value but its validity bit is clear");
      if (!present) continue;
      if (f.empty()) return row_error(line.number, cols[col], "empty but its validity bit is set");
      float v = 0;
      if (!parse_number(f, v)) return row_error(line.number, cols[col], "'" + std::string(f) + "' is " + number_problem<float>(f));
      if (!std::isfinite(v)) return row_error(line.number, cols[col], "'" + std::string(f) + "' is not finite");
    }
  }
  if (header_.has_head_pose()) {
    const std::string_view hv = fields_[col];
    if (hv != "0" && hv != "1")
      return row_error(line.number, cols[col], "'" + std::string(hv) + "' is not 0 or 1");
    const bool present = hv == "1";
    for (++col; col < want; ++col) {
      const std::string_view f = fields_[col];
      if (!present && !f.empty()) return row_error(line.number, cols[col], "has a value but head_valid is 0");
      if (!present) continue;
      if (f.empty()) return row_error(line.number, cols[col], "empty but head_valid is 1");
      float v = 0;
      if (!parse_number(f, v)) return row_error(line.number, cols[col], "'" + std::string(f) + "' is " + number_problem<float>(f));
      if (!std::isfinite(v)) return row_error(line.number, cols[col], "'" + std::string(f) + "' is not finite");
    }
  }
  return bad_input(where(path(), line.number) + ": malformed row");
}

Result<std::vector<GazeSample>> read_gaze_log(const std::string& path, GazeLogHeader* header,
                                              std::vector<GazeMarker>* markers) {
  auto r = GazeLogReader::open(path);
  if (!r) return r.error();
  std::vector<GazeSample> out;
  GazeSample s;
  for (;;) {
    auto got = r->next(s);
    if (!got) return got.error();
    if (!*got) break;
    out.push_back(s);
  }
  if (header) *header = r->header();
  if (markers) *markers = r->markers();
  return out;
}

}  // namespace foveal
