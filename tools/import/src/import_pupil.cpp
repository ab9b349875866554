#include <cmath>
#include <string>

#include "foveal/core/gaze_log.hpp"
#include "foveal/import/importers.hpp"
#include "foveal/import/table_reader.hpp"

namespace foveal {

namespace {

constexpr double kMinConfidence = 0.6;

// Pupil camera frame (x right, y down, +z forward) -> foveal (x right, y up, -z forward).
glm::vec3 from_pupil(float x, float y, float z) { return {x, -y, -z}; }

struct NormalColumns {
  long n[3] = {-1, -1, -1};
  long c[3] = {-1, -1, -1};  // eye_center*_3d (mm), optional
};

// A camera's columns: each x/y/z triple is all there or all absent.
Result<NormalColumns> normal_columns(const TableReader& t, int cam) {
  NormalColumns nc;
  const char axes[] = {'x', 'y', 'z'};
  const std::string prefixes[] = {"gaze_normal" + std::to_string(cam) + "_", "eye_center" + std::to_string(cam) + "_3d_"};
  long* dst[] = {nc.n, nc.c};
  for (int g = 0; g < 2; ++g) {
    int found = 0;
    for (int a = 0; a < 3; ++a) found += (dst[g][a] = t.find_column(prefixes[g] + axes[a])) >= 0;
    for (int a = 0; a < 3 && found > 0 && found < 3; ++a)
      if (dst[g][a] < 0) return bad_input(t.path() + ":1: column '" + prefixes[g] + axes[a] + "' is missing from the header");
  }
  return nc;
}

// Fills one eye from its camera's columns; empty fields (monocular rows) leave it invalid.
Status read_eye(const TableReader& t, const NormalColumns& nc, bool confident, EyeSample& e) {
  e = EyeSample{};
  if (nc.n[0] < 0 || t.field(static_cast<std::size_t>(nc.n[0])).empty()) return {};
  float v[3];
  for (int a = 0; a < 3; ++a) {
    auto f = t.number<float>(static_cast<std::size_t>(nc.n[a]));
    if (!f) return f.error();
    v[a] = *f;
  }
  // In double: a float's square overflows from 1.9e19 on (1e30 would give an infinite
  // length and a zero direction) and underflows below 1e-23.
  const double len = std::sqrt(static_cast<double>(v[0]) * v[0] + static_cast<double>(v[1]) * v[1] +
                               static_cast<double>(v[2]) * v[2]);
  if (confident && len > 0.0) {
    e.valid |= kValidDirection;
    e.direction = from_pupil(static_cast<float>(v[0] / len), static_cast<float>(v[1] / len), static_cast<float>(v[2] / len));
  }
  if (nc.c[0] >= 0 && !t.field(static_cast<std::size_t>(nc.c[0])).empty()) {
    for (int a = 0; a < 3; ++a) {
      auto f = t.number<float>(static_cast<std::size_t>(nc.c[a]));
      if (!f) return f.error();
      v[a] = *f;
    }
    e.valid |= kValidOrigin;
    e.origin_mm = from_pupil(v[0], v[1], v[2]);
  }
  return {};
}

}  // namespace

Result<ImportSummary> import_pupil(const std::string& in, const std::string& out) {
  auto table = TableReader::open(in, ',');
  if (!table) return table.error();
  TableReader& t = table.value();
  auto ts_col = t.column("gaze_timestamp");
  if (!ts_col) return ts_col.error();
  auto conf_col = t.column("confidence");
  if (!conf_col) return conf_col.error();
  for (const char* required : {"norm_pos_x", "norm_pos_y", "gaze_normal0_x", "gaze_normal0_y", "gaze_normal0_z"})
    if (auto c = t.column(required); !c) return c.error();
  auto right = normal_columns(t, 0);
  if (!right) return right.error();
  auto left = normal_columns(t, 1);
  if (!left) return left.error();

  // Pupil Core has no fixed rate; the header gets the rate measured over the file,
  // which needs a first pass.
  double first_s = 0, last_s = 0;
  std::uint64_t rows = 0;
  for (;;) {
    auto got = t.next();
    if (!got) return got.error();
    if (!*got) break;
    auto ts = t.number<double>(*ts_col);
    if (!ts) return ts.error();
    if (rows > 0 && *ts <= last_s)
      return t.field_error(*ts_col, std::string(*ts == last_s ? "repeats the previous time" : "goes back in time") +
                                        "; timestamps must increase strictly");
    if (rows == 0) first_s = *ts;
    last_s = *ts;
    ++rows;
  }
  if (rows == 0) return bad_input(in + ": no data rows after the header");

  GazeLogHeader header;
  header.rate_hz = rows > 1 && last_s > first_s ? std::round(static_cast<double>(rows - 1) / (last_s - first_s)) : 120.0;
  const auto slash = in.find_last_of('/');
  header.meta["source"] = "pupil:" + (slash == std::string::npos ? in : in.substr(slash + 1));
  auto writer = GazeLogWriter::create(out, header);
  if (!writer) return writer.error();

  table = TableReader::open(in, ',');
  if (!table) return table.error();
  TableReader& t2 = table.value();
  ImportSummary sum;
  sum.format = "pupil";
  sum.rate_hz = header.rate_hz;
  for (;;) {
    auto got = t2.next();
    if (!got) return got.error();
    if (!*got) break;
    auto ts = t2.number<double>(*ts_col);
    if (!ts) return ts.error();
    auto conf = t2.number<double>(*conf_col);
    if (!conf) return conf.error();
    const bool confident = *conf >= kMinConfidence;
    GazeSample s;
    const double ns = (*ts - first_s) * 1e9;
    if (!(ns < static_cast<double>(kMaxGazeLogTimeNs)))
      return t2.field_error(*ts_col, "too far from the first row's time (more than 2^62 ns, 146 years)");
    s.t_ns = static_cast<TimeNs>(std::llround(ns));
    if (Status st = read_eye(t2, *left, confident, s.eye(Eye::left)); !st) return st.error();
    if (Status st = read_eye(t2, *right, confident, s.eye(Eye::right)); !st) return st.error();
    for (int e = 0; e < 2; ++e) sum.invalid[e] += s.eyes[e].has(kValidDirection) ? 0 : 1;
    if (Status st = writer->write(s); !st)
      return t2.field_error(*ts_col, "rounds to the same nanosecond as the previous row");
    ++sum.rows;
  }
  if (Status st = writer->commit(); !st) return st.error();
  return sum;
}

}  // namespace foveal
