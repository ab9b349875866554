#pragma once
// The native gaze log, format v1 (docs/gaze-log.md): versioned, human-readable CSV.
#include <cstdint>
#include <map>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "foveal/core/atomic_file.hpp"
#include "foveal/core/error.hpp"
#include "foveal/core/gaze_sample.hpp"
#include "foveal/core/line_reader.hpp"

namespace foveal {

constexpr int kGazeLogVersion = 1;
/// Timestamps are in [-2^62, 2^62) ns (±146 years), so the difference of any two of
/// them (durations, gaps, replay offsets) fits in an int64 without wrapping.
constexpr std::int64_t kMaxGazeLogTimeNs = std::int64_t{1} << 62;
constexpr std::string_view kGazeLogMagic = "# foveal-gaze-log v";

struct GazeLogHeader {
  int version = kGazeLogVersion;
  double rate_hz = 0;  ///< nominal sample rate, > 0
  /// Further "# key=value" lines (source, device, start_utc, ...), kept in order of key.
  std::map<std::string, std::string> meta;
};

/// The v1 column names, in file order.
const std::vector<std::string>& gaze_log_columns();

/// Streams a native gaze log. Every row is checked: field count, numbers, NaN/Inf,
/// validity bits against empty fields, strictly increasing timestamps. Errors name
/// file:line: column.
class GazeLogReader {
 public:
  static Result<GazeLogReader> open(const std::string& path);

  const GazeLogHeader& header() const { return header_; }
  const std::string& path() const { return lines_.path(); }
  /// Next sample into `out`; false at the end of the file (an error if it held none).
  /// After an error `out` holds an unspecified, partly parsed sample.
  Result<bool> next(GazeSample& out);
  /// Back to the first sample.
  Status rewind();
  std::uint64_t samples_read() const { return samples_; }

 private:
  GazeLogReader(LineReader lines) : lines_(std::move(lines)) {}
  Status read_header();
  Error row_error(std::uint64_t line, std::string_view column, const std::string& what) const;
  Error describe_row_error(const LineReader::Line& line);

  LineReader lines_;
  GazeLogHeader header_;
  std::vector<std::string_view> fields_;
  std::uint64_t samples_ = 0;
  TimeNs last_t_ = 0;
};

/// Reads a whole log into memory (tests and small tools; replay streams instead).
Result<std::vector<GazeSample>> read_gaze_log(const std::string& path, GazeLogHeader* header = nullptr);

/// Writes a native gaze log atomically: nothing appears at `path` until commit().
/// Values are written in their shortest round-trip form, so reading back is bit-exact.
class GazeLogWriter {
 public:
  static Result<GazeLogWriter> create(const std::string& path, const GazeLogHeader& header);
  /// Rejects non-increasing timestamps and non-finite valid fields.
  Status write(const GazeSample& s);
  Status commit() { return file_.commit(); }
  std::uint64_t samples_written() const { return samples_; }

 private:
  explicit GazeLogWriter(AtomicFile f) : file_(std::move(f)) {}
  AtomicFile file_;
  std::string row_;
  std::uint64_t samples_ = 0;
  TimeNs last_t_ = 0;
};

}  // namespace foveal
