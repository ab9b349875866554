#pragma once
// The native gaze log, formats v1 and v2 (docs/gaze-log.md): versioned, human-readable
// CSV. v2 is v1 plus the head-pose columns.
#include <cstdint>
#include <map>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "foveal/core/atomic_file.hpp"
#include "foveal/core/error.hpp"
#include "foveal/core/gaze_marker.hpp"
#include "foveal/core/gaze_sample.hpp"
#include "foveal/core/line_reader.hpp"

namespace foveal {

constexpr int kGazeLogV1 = 1;  ///< gaze only
constexpr int kGazeLogV2 = 2;  ///< gaze and the head pose (head_valid, head_x_m, ..., head_qz)
/// Timestamps are in [-2^62, 2^62) ns (±146 years), so the difference of any two of
/// them (durations, gaps, replay offsets) fits in an int64 without wrapping.
constexpr std::int64_t kMaxGazeLogTimeNs = std::int64_t{1} << 62;
/// A head position further than this from the tracking origin on any axis (metres) is
/// not a room-scale pose: refused by the reader, as the SRanipal importer refuses it
/// (a float of 3e38 m would otherwise overflow the camera's arithmetic).
constexpr float kMaxHeadPositionM = 1000.0f;
constexpr std::string_view kGazeLogMagic = "# foveal-gaze-log v";

struct GazeLogHeader {
  /// What the reader found; what the writer writes. A writer writes v2 only when asked
  /// (a source with head poses), so pose-free logs stay v1, readable by older builds.
  int version = kGazeLogV1;
  double rate_hz = 0;  ///< nominal sample rate, > 0
  /// Further "# key=value" lines (source, device, start_utc, ...), kept in order of key.
  std::map<std::string, std::string> meta;

  bool has_head_pose() const { return version >= kGazeLogV2; }
};

/// The column names of format `version` (1 or 2), in file order: v2 appends the eight
/// head-pose columns to v1's 26.
const std::vector<std::string>& gaze_log_columns(int version = kGazeLogV1);

/// Streams a native gaze log, v1 or v2. Every row is checked: field count, numbers,
/// NaN/Inf, validity bits against empty fields, strictly increasing timestamps, and (v2)
/// a unit head quaternion (is_unit). Errors name file:line: column. Samples of a v1 log
/// have `head.valid == false`; stored head values are returned exactly as written.
class GazeLogReader {
 public:
  static Result<GazeLogReader> open(const std::string& path);

  const GazeLogHeader& header() const { return header_; }
  const std::string& path() const { return lines_.path(); }
  /// Next sample into `out`; false at the end of the file (an error if it held none).
  /// After an error `out` holds an unspecified, partly parsed sample.
  /// Marker rows on the way are checked and kept (markers()), never returned as samples.
  Result<bool> next(GazeSample& out);
  /// Back to the first sample.
  Status rewind();
  std::uint64_t samples_read() const { return samples_; }
  /// The marker rows read so far (since open or the last rewind), in file order.
  const std::vector<GazeMarker>& markers() const { return markers_; }

 private:
  GazeLogReader(LineReader lines) : lines_(std::move(lines)) {}
  Status read_header();
  Error row_error(std::uint64_t line, std::string_view column, const std::string& what) const;
  Error describe_row_error(const LineReader::Line& line);
  Status read_marker(const LineReader::Line& line);

  LineReader lines_;
  GazeLogHeader header_;
  std::vector<std::string_view> fields_;
  std::uint64_t samples_ = 0;
  TimeNs last_t_ = 0;
  std::vector<GazeMarker> markers_;
};

/// Reads a whole log into memory (tests and small tools; replay streams instead).
Result<std::vector<GazeSample>> read_gaze_log(const std::string& path, GazeLogHeader* header = nullptr,
                                              std::vector<GazeMarker>* markers = nullptr);

/// Writes a native gaze log atomically: nothing appears at `path` until commit().
/// Values are written in their shortest round-trip form, so reading back is bit-exact.
/// The format is `header.version`: v2 writes each sample's head pose, v1 refuses a
/// sample that carries one (rather than dropping it silently).
class GazeLogWriter {
 public:
  static Result<GazeLogWriter> create(const std::string& path, const GazeLogHeader& header);
  /// Rejects non-increasing timestamps, non-finite valid fields, a valid head pose whose
  /// orientation is not a unit quaternion, and (v1) any valid head pose.
  Status write(const GazeSample& s);
  /// A marker row: its time may not be earlier than the row before it (sample or marker).
  Status mark(const GazeMarker& m);
  Status commit() { return file_.commit(); }
  std::uint64_t samples_written() const { return samples_; }

 private:
  GazeLogWriter(AtomicFile f, bool head) : file_(std::move(f)), head_(head) {}
  AtomicFile file_;
  bool head_ = false;
  std::string row_;
  std::uint64_t samples_ = 0;
  TimeNs last_t_ = 0;
  bool any_row_ = false;  // a sample or a marker is written: last_row_t_ holds its time
  TimeNs last_row_t_ = 0;
};

}  // namespace foveal
