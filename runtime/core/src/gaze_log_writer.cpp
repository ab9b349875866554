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
  auto f = AtomicFile::create(path);
  if (!f) return f.error();
  GazeLogWriter w(std::move(f.value()));
  std::string head = std::string(kGazeLogMagic) + std::to_string(kGazeLogVersion) + "\n";
  char rate[32];
  auto [p, ec] = std::to_chars(rate, rate + sizeof rate, header.rate_hz);
  (void)ec;
  head += "# rate_hz=" + std::string(rate, p) + "\n";
  for (const auto& [k, v] : header.meta) head += "# " + k + "=" + v + "\n";
  const auto& cols = gaze_log_columns();
  for (std::size_t i = 0; i < cols.size(); ++i) head += (i ? "," : "") + cols[i];
  head += "\n";
  w.file_.write(head);
  return w;
}

Status GazeLogWriter::write(const GazeSample& s) {
  if (samples_ > 0 && s.t_ns <= last_t_)
    return bad_input(file_.path() + ": sample " + std::to_string(samples_ + 1) + ": timestamp " +
                     std::to_string(s.t_ns) + " does not increase");
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
  row_ += '\n';
  file_.write(row_);
  last_t_ = s.t_ns;
  ++samples_;
  return {};
}

}  // namespace foveal
