#include <cmath>

#include "foveal/core/gaze_log.hpp"
#include "foveal/core/text_fields.hpp"

namespace foveal {

namespace {

constexpr std::size_t kEyeFields = 9;       // valid, dir xyz, origin xyz, pupil, openness
constexpr std::size_t kCombinedFields = 7;  // valid, dir xyz, origin xyz
constexpr std::size_t kRowFields = 1 + 2 * kEyeFields + kCombinedFields;

std::string where(const std::string& path, std::uint64_t line) {
  return path + ":" + std::to_string(line);
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
  if (!*got) return bad_input(where(path(), 1) + ": file is empty; expected '# foveal-gaze-log v1'");
  if (line.text.size() >= 3 && static_cast<unsigned char>(line.text[0]) == 0xEF &&
      static_cast<unsigned char>(line.text[1]) == 0xBB && static_cast<unsigned char>(line.text[2]) == 0xBF)
    return bad_input(where(path(), 1) + ": starts with a UTF-8 byte-order mark; gaze logs have none");
  if (line.text.substr(0, kGazeLogMagic.size()) != kGazeLogMagic)
    return bad_input(where(path(), 1) + ": not a foveal gaze log; expected '# foveal-gaze-log v1'");
  if (Status s = check_line(line); !s) return s;
  {
    const std::string_view v = line.text.substr(kGazeLogMagic.size());
    int version = 0;
    if (!parse_number(v, version))
      return bad_input(where(path(), 1) + ": format version: '" + std::string(v) + "' is not a number");
    if (version != kGazeLogVersion)
      return Error{ErrorKind::unsupported, where(path(), 1) + ": format version: v" + std::to_string(version) +
                                          " is not supported (this build reads v1)"};
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
  const auto& cols = gaze_log_columns();
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
  return read_header();
}

Result<bool> GazeLogReader::next(GazeSample& out) {
  LineReader::Line line;
  auto got = lines_.next(line);
  if (!got) return got.error();
  if (!*got) {
    if (samples_ == 0) return bad_input(path() + ": no samples: the log has a header only");
    return false;
  }
  const auto& cols = gaze_log_columns();
  if (line.crlf) return bad_input(where(path(), line.number) + ": line ends in CRLF; gaze logs use LF line ends");
  split_fields(line.text, ',', fields_);
  if (fields_.size() < kRowFields) {
    const std::string what = line.terminated ? "missing (row has " + std::to_string(fields_.size()) + " of " +
                                                   std::to_string(kRowFields) + " fields)"
                                             : "missing: truncated last row (no line end)";
    return row_error(line.number, cols[fields_.size()], what);
  }
  if (fields_.size() > kRowFields)
    return bad_input(where(path(), line.number) + ": row has " + std::to_string(fields_.size()) +
                     " fields, expected " + std::to_string(kRowFields));
  if (!line.terminated)
    return bad_input(where(path(), line.number) + ": truncated last row (no line end)");

  GazeSample s;
  if (!parse_number(fields_[0], s.t_ns)) return row_error(line.number, cols[0], "'" + std::string(fields_[0]) + "' is not an integer");
  if (samples_ > 0 && s.t_ns <= last_t_)
    return row_error(line.number, cols[0], std::to_string(s.t_ns) + (s.t_ns == last_t_ ? " repeats" : " goes back from ") +
                                               (s.t_ns == last_t_ ? " the previous timestamp" : std::to_string(last_t_)) +
                                               "; timestamps must increase strictly");

  std::size_t col = 1;
  auto read_float = [&](bool present, float& dst) -> Status {
    const std::size_t c = col++;
    const std::string_view f = fields_[c];
    if (!present) {
      if (!f.empty()) return row_error(line.number, cols[c], "has a value but its validity bit is clear");
      dst = 0.0f;
      return {};
    }
    if (f.empty()) return row_error(line.number, cols[c], "empty but its validity bit is set");
    if (!parse_number(f, dst)) return row_error(line.number, cols[c], "'" + std::string(f) + "' is not a number");
    if (!std::isfinite(dst)) return row_error(line.number, cols[c], "'" + std::string(f) + "' is not finite");
    return {};
  };
  auto read_block = [&](EyeSample& e, bool with_pupil) -> Status {
    const std::size_t c = col++;
    if (!parse_number(fields_[c], e.valid) || e.valid > kValidAll || (!with_pupil && (e.valid & ~3u)))
      return row_error(line.number, cols[c], "'" + std::string(fields_[c]) + "' is not a validity mask (0.." +
                                                 std::to_string(with_pupil ? kValidAll : 3u) + ")");
    for (int i = 0; i < 3; ++i)
      if (Status st = read_float(e.has(kValidDirection), e.direction[i]); !st) return st;
    for (int i = 0; i < 3; ++i)
      if (Status st = read_float(e.has(kValidOrigin), e.origin_mm[i]); !st) return st;
    if (with_pupil) {
      if (Status st = read_float(e.has(kValidPupil), e.pupil_mm); !st) return st;
      if (Status st = read_float(e.has(kValidOpenness), e.openness); !st) return st;
    }
    return {};
  };
  for (EyeSample& e : s.eyes)
    if (Status st = read_block(e, true); !st) return st.error();
  if (Status st = read_block(s.combined, false); !st) return st.error();

  last_t_ = s.t_ns;
  ++samples_;
  out = s;
  return true;
}

Result<std::vector<GazeSample>> read_gaze_log(const std::string& path, GazeLogHeader* header) {
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
  return out;
}

}  // namespace foveal
