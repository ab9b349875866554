#include "foveal/core/gaze_marker.hpp"

#include "foveal/core/gaze_log.hpp"
#include "foveal/core/shown_text.hpp"
#include "foveal/core/text_fields.hpp"

namespace foveal {

Status check_marker_text(std::string_view text) {
  if (text.empty()) return bad_input("mark: the text is empty");
  if (text.size() > kMaxMarkerBytes)
    return bad_input("mark: the text has " + std::to_string(text.size()) + " bytes; at most " +
                     std::to_string(kMaxMarkerBytes));
  for (std::size_t i = 0; i < text.size(); ++i) {
    const auto c = static_cast<unsigned char>(text[i]);
    if (c < 0x20 || c == 0x7f)
      return bad_input("mark: byte " + std::to_string(i + 1) + " of the text is a control character");
  }
  return {};
}

std::string marker_row(const GazeMarker& m) {
  return std::string(kMarkerRowPrefix) + std::to_string(m.t_ns) + "," + m.text + "\n";
}

Result<GazeMarker> parse_marker_row(std::string_view row) {
  row.remove_prefix(kMarkerRowPrefix.size());
  const auto comma = row.find(',');
  if (comma == std::string_view::npos) return bad_input("t_ns: the marker row has no text (expected #mark,T_NS,TEXT)");
  GazeMarker m;
  const std::string_view t = row.substr(0, comma);
  if (!parse_number(t, m.t_ns)) return bad_input("t_ns: '" + shown_text(t) + "' is not an integer");
  // The samples' range, so a marker minus a sample cannot overflow either.
  if (m.t_ns < -kMaxGazeLogTimeNs || m.t_ns >= kMaxGazeLogTimeNs)
    return bad_input("t_ns: marker time " + std::to_string(m.t_ns) +
                     " is out of range (timestamps are in [-2^62, 2^62) ns, ±146 years)");
  m.text = std::string(row.substr(comma + 1));
  if (Status s = check_marker_text(m.text); !s) return bad_input("text: " + s.error().message.substr(6));
  return m;
}

}  // namespace foveal
