#pragma once
// The fuzz targets' bodies: called by the libFuzzer entry points (fuzz_*.cpp) and by
// the regression test, which replays every saved crash input in the normal build.
#include <cmath>
#include <cstdlib>
#include <unistd.h>

#include "foveal/core/gaze_log.hpp"
#include "foveal/core/gaze_log_stats.hpp"
#ifdef FOVEAL_HAVE_HID
#include "foveal/drivers/hid/report_decoder.hpp"
#endif
#include "foveal/import/importers.hpp"
#include "foveal/runtime/profile.hpp"
#include "fuzz_file.hpp"

namespace foveal::fuzz {

// Native gaze-log reader: any bytes must give samples or a clean error, never a crash.
inline int gaze_log(const std::uint8_t* data, std::size_t size) {
  MemFile f(data, size);
  auto r = foveal::GazeLogReader::open(f.path());
  if (!r) return 0;
  foveal::GazeSample s;
  for (int i = 0; i < 100000; ++i) {
    auto got = r->next(s);
    if (!got || !*got) break;
    for (const auto& e : s.eyes)
      if (e.has(foveal::kValidDirection) && !std::isfinite(e.direction.x)) std::abort();  // never NaN
  }
  (void)foveal::compute_gaze_log_stats(f.path());
  return 0;
}

// SRanipal and Pupil importers: clean error or a valid log, never a crash; a failed
// import leaves no output file.
inline int import(const std::uint8_t* data, std::size_t size) {
  if (size == 0) return 0;
  MemFile f(data + 1, size - 1);
  const std::string out = scratch_output();
  auto r = (data[0] & 1) ? foveal::import_pupil(f.path(), out) : foveal::import_sranipal(f.path(), out);
  if (!r && ::access(out.c_str(), F_OK) == 0) std::abort();  // partial output left behind
  ::unlink(out.c_str());
  return 0;
}

#ifdef FOVEAL_HAVE_HID
// HID report-descriptor parser and report decoder on arbitrary bytes.
inline int hid(const std::uint8_t* data, std::size_t size) {
  if (size < 2) return 0;
  // First byte: how much of the rest is the descriptor; the remainder is a report.
  const std::size_t desc_len = std::min<std::size_t>(size - 1, static_cast<std::size_t>(data[0]) * 4);
  std::span<const std::uint8_t> desc(data + 1, desc_len), report(data + 1 + desc_len, size - 1 - desc_len);
  auto d = foveal::hid::parse_report_descriptor(desc);
  if (!d) return 0;
  for (auto type : {foveal::hid::ReportType::input, foveal::hid::ReportType::feature})
    (void)foveal::hid::decode_report(*d, type, report);
  return 0;
}
#endif

// Profile reader: a hand-broken profile is an error, never a crash or a half-load.
inline int profile(const std::uint8_t* data, std::size_t size) {
  MemFile f(data, size);
  auto p = foveal::ProfileStore::load_file(f.path(), "fuzz");
  if (p && !p->validate("fuzz")) std::abort();  // loaded means valid
  return 0;
}

}  // namespace foveal::fuzz
