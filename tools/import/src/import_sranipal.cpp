#include <cmath>
#include <string>

#include "foveal/core/gaze_log.hpp"
#include "foveal/import/importers.hpp"
#include "foveal/import/table_reader.hpp"

namespace foveal {

namespace {

// SRanipal eye-data validity bits.
constexpr std::uint32_t kSrGazeOrigin = 1u << 0;
constexpr std::uint32_t kSrGazeDirection = 1u << 1;
constexpr std::uint32_t kSrPupilDiameter = 1u << 2;
constexpr std::uint32_t kSrOpenness = 1u << 3;

struct EyeColumns {
  std::size_t valid, openness, pupil, origin[3], dir[3];
};

Result<EyeColumns> eye_columns(const TableReader& t, char side) {
  EyeColumns c{};
  const std::string s(1, side);
  const std::string names[] = {"eye_valid_" + s, "openness_" + s, "pupil_diameter_" + s + "(mm)"};
  std::size_t* dst[] = {&c.valid, &c.openness, &c.pupil};
  for (int i = 0; i < 3; ++i) {
    auto col = t.column(names[i]);
    if (!col) return col.error();
    *dst[i] = *col;
  }
  const char axes[] = {'x', 'y', 'z'};
  for (int a = 0; a < 3; ++a) {
    auto o = t.column("gaze_origin_" + s + "." + axes[a] + "(mm)");
    if (!o) return o.error();
    c.origin[a] = *o;
    auto d = t.column("gaze_direct_" + s + "." + axes[a]);
    if (!d) return d.error();
    c.dir[a] = *d;
  }
  return c;
}

// SRanipal (x left, y up, +z forward) -> foveal (x right, y up, -z forward).
glm::vec3 from_sranipal(float x, float y, float z) { return {-x, y, -z}; }

Status read_eye(const TableReader& t, const EyeColumns& c, EyeSample& e) {
  auto valid = t.number<std::uint32_t>(c.valid);
  if (!valid) return valid.error();
  float v[8];
  const std::size_t cols[8] = {c.dir[0], c.dir[1], c.dir[2], c.origin[0], c.origin[1], c.origin[2], c.pupil, c.openness};
  for (int i = 0; i < 8; ++i) {
    auto f = t.number<float>(cols[i]);
    if (!f) return f.error();
    v[i] = *f;
  }
  e = EyeSample{};
  const bool zero_dir = v[0] == 0.0f && v[1] == 0.0f && v[2] == 0.0f;
  if ((*valid & kSrGazeDirection) && !zero_dir) {
    e.valid |= kValidDirection;
    e.direction = from_sranipal(v[0], v[1], v[2]);
  }
  if (*valid & kSrGazeOrigin) {
    e.valid |= kValidOrigin;
    e.origin_mm = from_sranipal(v[3], v[4], v[5]);
  }
  if ((*valid & kSrPupilDiameter) && v[6] >= 0.0f) {
    e.valid |= kValidPupil;
    e.pupil_mm = v[6];
  }
  if (*valid & kSrOpenness) {
    e.valid |= kValidOpenness;
    e.openness = v[7];
  }
  return {};
}

}  // namespace

Result<ImportSummary> import_sranipal(const std::string& in, const std::string& out) {
  auto table = TableReader::open(in, ';');
  if (!table) return table.error();
  TableReader& t = table.value();
  auto time_col = t.column("time(100ns)");
  if (!time_col) return time_col.error();
  auto left = eye_columns(t, 'L');
  if (!left) return left.error();
  auto right = eye_columns(t, 'R');
  if (!right) return right.error();

  GazeLogHeader header;
  header.rate_hz = 120.0;  // the Vive Pro Eye's nominal rate
  const auto slash = in.find_last_of('/');
  header.meta["source"] = "sranipal:" + (slash == std::string::npos ? in : in.substr(slash + 1));
  auto writer = GazeLogWriter::create(out, header);
  if (!writer) return writer.error();

  ImportSummary sum;
  sum.format = "sranipal";
  sum.rate_hz = header.rate_hz;
  std::int64_t first_tick = 0, last_tick = 0;
  for (;;) {
    auto got = t.next();
    if (!got) return got.error();
    if (!*got) break;
    auto tick = t.number<std::int64_t>(*time_col);
    if (!tick) return tick.error();
    if (sum.rows == 0) first_tick = *tick;
    else if (*tick <= last_tick)
      return t.field_error(*time_col, std::to_string(*tick) + (*tick == last_tick ? " repeats the previous time" : " goes back in time") +
                                          "; timestamps must increase strictly");
    last_tick = *tick;
    GazeSample s;
    // 100 ns ticks -> ns from the first row; a span past 2^62 ns (146 years) is bad data.
    std::int64_t span = 0;
    if (__builtin_sub_overflow(*tick, first_tick, &span) || __builtin_mul_overflow(span, std::int64_t{100}, &s.t_ns) ||
        s.t_ns >= kMaxGazeLogTimeNs)
      return t.field_error(*time_col, std::to_string(*tick) + " is too far from the first row's time");
    if (Status st = read_eye(t, *left, s.eye(Eye::left)); !st) return st.error();
    if (Status st = read_eye(t, *right, s.eye(Eye::right)); !st) return st.error();
    for (int e = 0; e < 2; ++e) sum.invalid[e] += s.eyes[e].has(kValidDirection) ? 0 : 1;
    if (Status st = writer->write(s); !st) return st.error();
    ++sum.rows;
  }
  if (sum.rows == 0) return bad_input(in + ": no data rows after the header");
  if (Status st = writer->commit(); !st) return st.error();
  return sum;
}

}  // namespace foveal
