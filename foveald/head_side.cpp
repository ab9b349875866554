#include "head_side.hpp"

#include "foveal/runtime/log.hpp"

namespace foveal::daemon {

namespace {

nlohmann::json figures_json(const PredictionErrors::Figures& f) {
  return {{"p50", f.p50}, {"p99", f.p99}, {"max", f.max}};
}

}  // namespace

Result<std::unique_ptr<HeadSide>> HeadSide::create(const std::string& head, bool source_has_pose,
                                                   const std::string& source_text, const probe::SourceOptions& options) {
  std::unique_ptr<HeadSide> h(new HeadSide());
  if (head.empty() || head == "recorded" || head == "static") {
    if (head == "recorded" && !source_has_pose)
      return bad_input("--head recorded: " + source_text + " carries no head pose (a native log v2 with head columns has one)");
    h->mode_ = head.empty() ? (source_has_pose ? "recorded" : "static") : head;
    return h;
  }
  auto spec = probe::parse_pose_spec(head);
  if (!spec) return bad_input(spec.error().message + "; or recorded, static");
  auto dev = probe::make_pose_device(*spec, options);
  if (!dev) return dev.error();
  h->mode_ = spec->text();
  h->device_.emplace(std::move(*dev));
  // Once now, for the headset's own display model; a headset that is not there yet is
  // waited for by the pose thread (and the display model stays the profile's).
  PoseDevice& d = *h->device_->device;
  bool opened = false;
  if (Status s = d.open(); s) {
    opened = true;
    if (h->device_->display) h->display_ = h->device_->display();
    if (Status st = d.start(); !st) {
      log::warn("--head " + h->mode_ + ": " + st.error().message + "; retrying");
      d.close();
      opened = false;
    }
  } else {
    log::info("--head " + h->mode_ + ": " + s.error().message + "; waiting for the headset");
  }
  h->tracker_ = std::make_unique<HeadTracker>(d, /*wait_for_device=*/!opened);
  return h;
}

HeadSide::~HeadSide() { stop(); }

void HeadSide::start() {
  if (tracker_) tracker_->start();
}

void HeadSide::stop() {
  if (tracker_ && !stopped_) {
    state_at_stop_ = tracker_->stats().state;  // what the summary reports, not "stopped"
    tracker_->stop();
    stopped_ = true;
  }
}

void HeadSide::push_recorded(const GazeSample& s) {
  if (recorded() && s.head.valid) recorded_.push({s.t_ns, s.head.pose});
}

PoseAt HeadSide::for_frame(TimeNs gaze_t_ns, double refresh_hz) {
  if (recorded()) return recorded_.pose_at(gaze_t_ns);  // where the head was when the gaze was
  if (!tracker_) return {};
  // The frame reaches the eyes about one refresh after it starts.
  const TimeNs now = monotonic_now_ns();
  const TimeNs display_t = now + static_cast<TimeNs>(1e9 / refresh_hz);
  const PoseAt p = tracker_->predicted(display_t);
  const bool tracking = tracker_->stats().state == HeadState::tracking;
  std::lock_guard lock(prediction_mutex_);
  refresh_hz_ = refresh_hz;
  prediction_.resolve(tracker_->track());
  // Only live predictions are scored: a held pose is no prediction, and the poses
  // measured across a gap are interpolated over it.
  if (!tracking) prediction_.drop_pending();
  else if (p.valid) prediction_.add(display_t, p.pose, tracker_->motion().pose.pose);
  return p;
}

nlohmann::json HeadSide::json() const {
  if (!tracker_) {
    const PoseTrack& t = recorded_;
    return {{"mode", mode_}, {"poses", t.accepted()}, {"poses_dropped", t.dropped()}};
  }
  HeadTrackerStats st = tracker_->stats();
  if (stopped_) st.state = state_at_stop_;
  const TimeNs now = monotonic_now_ns();
  nlohmann::json j = {
      {"mode", mode_},
      {"state", head_state_name(st.state)},
      {"held", st.state == HeadState::held || st.state == HeadState::reconnecting},
      {"device", {{"driver", st.device.driver}, {"name", st.device.name}, {"path", st.device.path}}},
      {"poses", st.poses},
      {"poses_dropped", tracker_->track().dropped()},
      {"imu_samples", st.imu_samples},
      {"disconnects", st.disconnects},
      {"reconnects", st.reconnects},
      {"last_reading_age_ms", st.last_reading_ns ? static_cast<double>(now - st.last_reading_ns) / 1e6 : -1.0},
      {"gyro_bias_rad_s", {st.gyro_bias.x, st.gyro_bias.y, st.gyro_bias.z}}};
  if (!st.last_error.empty()) j["last_error"] = st.last_error;
  if (display_) j["display_model"] = display_->model.name;
  {
    std::lock_guard lock(prediction_mutex_);
    j["prediction"] = {{"refresh_hz", refresh_hz_},
                       {"horizon_ms", refresh_hz_ > 0 ? 1000.0 / refresh_hz_ : 0.0},
                       {"frames", prediction_.angle_deg().count},
                       {"error_deg", figures_json(prediction_.angle_deg())},
                       {"error_mm", figures_json(prediction_.position_mm())},
                       {"unpredicted_error_deg", figures_json(prediction_.held_angle_deg())}};
  }
  if (stopped_ && device_ && device_->counters) j["counters"] = device_->counters();
  return j;
}

}  // namespace foveal::daemon
