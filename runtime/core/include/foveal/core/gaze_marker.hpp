#pragma once
// Event markers: a timestamped text (`foveal ctl mark`), carried by the native gaze log
// and foveald's trace as rows of their own, `#mark,T_NS,TEXT` (docs/gaze-log.md).
#include <string>
#include <string_view>

#include "foveal/core/clock.hpp"
#include "foveal/core/error.hpp"

namespace foveal {

struct GazeMarker {
  TimeNs t_ns = 0;  ///< on the time base of the file's samples
  std::string text;
  bool operator==(const GazeMarker&) const = default;
};

constexpr std::string_view kMarkerRowPrefix = "#mark,";
constexpr std::size_t kMaxMarkerBytes = 256;
/// A reader keeps at most this many markers of a log (about 26 MB): a crafted file of
/// marker rows cannot make a streaming reader grow without bound.
constexpr std::size_t kMaxGazeLogMarkers = 100'000;

/// 1 to kMaxMarkerBytes bytes, no control characters (the text is the rest of a CSV row:
/// commas are fine, line ends are not). The message starts "mark: ".
Status check_marker_text(std::string_view text);

/// "#mark,T_NS,TEXT\n".
std::string marker_row(const GazeMarker& m);

/// Parses a row that starts with kMarkerRowPrefix (the line without its end). Errors
/// start with the column at fault ("t_ns: ...", "text: ...") for the caller to place.
Result<GazeMarker> parse_marker_row(std::string_view row);

}  // namespace foveal
