#include "render/render_head.hpp"

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <vector>

#include "foveal/bench/gaze_timeline.hpp"
#include "foveal/core/gaze_log.hpp"
#include "foveal/runtime/filter_config.hpp"

namespace foveal::cmd {

namespace {

std::string num(double v) {
  char b[32];
  std::snprintf(b, sizeof b, "%.6g", v);
  return b;
}

double seconds(TimeNs ns) { return static_cast<double>(ns) * 1e-9; }

}  // namespace

Result<Pose> parse_head_pose(const std::string& s, const std::string& what) {
  static const char* const names[7] = {"x", "y", "z", "qw", "qx", "qy", "qz"};
  std::vector<std::string> parts;
  for (std::size_t from = 0;;) {
    const std::size_t comma = s.find(',', from);
    parts.push_back(s.substr(from, comma == std::string::npos ? std::string::npos : comma - from));
    if (comma == std::string::npos) break;
    from = comma + 1;
  }
  if (parts.size() != 7)
    return bad_input(what + ": expected X,Y,Z,QW,QX,QY,QZ (seven numbers: metres, then a unit quaternion), got " +
                     std::to_string(parts.size()) + " in '" + s + "'");
  double v[7];
  for (std::size_t i = 0; i < 7; ++i) {
    char* end = nullptr;
    errno = 0;
    v[i] = std::strtod(parts[i].c_str(), &end);
    if (parts[i].empty() || *end != '\0') return bad_input(what + ": " + names[i] + ": '" + parts[i] + "' is not a number");
    if (errno == ERANGE && std::abs(v[i]) > 1) return bad_input(what + ": " + names[i] + ": '" + parts[i] + "' is out of range");
    if (!std::isfinite(v[i])) return bad_input(what + ": " + names[i] + ": '" + parts[i] + "' is not finite");
  }
  Pose p;
  p.position_m = glm::vec3(static_cast<float>(v[0]), static_cast<float>(v[1]), static_cast<float>(v[2]));
  p.orientation = glm::quat(static_cast<float>(v[3]), static_cast<float>(v[4]), static_cast<float>(v[5]), static_cast<float>(v[6]));
  if (!is_finite(p)) return bad_input(what + ": '" + s + "' does not fit single precision");
  if (!is_unit(p.orientation))
    return bad_input(what + ": qw..qz: quaternion norm " + num(quaternion_norm(p.orientation)) + " is not 1 (tolerance " +
                     num(kUnitQuaternionTolerance) + "): not a head orientation");
  p.orientation = renormalized(p.orientation);
  return p;
}

Result<LogFrame> log_frame_at(const std::string& path, double at_s, const DisplayModel& model) {
  auto samples = read_gaze_log(path);
  if (!samples) return samples.error();
  if (!std::any_of(samples->begin(), samples->end(), [](const GazeSample& g) { return g.head.valid; }))
    return bad_input("--log: " + path + " carries no head pose (a native log v2 with head columns has one)");
  LogFrame out;
  const TimeNs first = samples->front().t_ns;
  out.duration_s = seconds(samples->back().t_ns - first);
  if (std::isfinite(at_s) && at_s > 1e7)  // a bound of its own, whatever the log spans
    return bad_input("--at " + num(at_s) + ": more than the 1e7 s (about 116 days) that --at accepts");
  if (!std::isfinite(at_s) || at_s < 0 || first + static_cast<TimeNs>(std::llround(at_s * 1e9)) > samples->back().t_ns)
    return bad_input("--at " + num(at_s) + ": outside " + path + ", whose samples span 0 to " + num(out.duration_s) +
                     " s from its first");

  // One frame of bench --gaze's stream starting at at_s: the same filter, fovea and pose.
  bench::GazeTimelineOptions o;
  o.start_s = at_s;
  o.latency_ms = 0;
  o.frames = 1;
  o.head_recorded = true;
  auto tl = bench::build_gaze_timeline(*samples, model, FilterConfig{}, o);
  if (!tl) return Error{tl.error().kind, path + ": " + tl.error().message};
  if (tl->frames.empty()) return bad_input(path + ": no frame at " + num(at_s) + " s");
  const bench::GazeFrame& f = tl->frames.front();
  out.sample_s = seconds(f.t_sample - first);
  if (!f.head.valid) {
    const auto with_pose = std::find_if(samples->begin(), samples->end(), [](const GazeSample& g) { return g.head.valid; });
    return bad_input("--at " + num(at_s) + ": " + path + " has no head pose at or before then (its first is at " +
                     num(seconds(with_pose->t_ns - first)) + " s)");
  }
  out.relative = f.head.relative;
  out.fovea = {f.fovea[0], f.fovea[1]};
  return out;
}

}  // namespace foveal::cmd
