#include "record/recording.hpp"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <csignal>
#include <cstdio>
#include <deque>
#include <memory>
#include <optional>
#include <vector>

#include "foveal/core/gaze_log.hpp"
#include "foveal/evaluation/quality_report.hpp"
#include "foveal/quality/quality_targets.hpp"
#include "foveal/runtime/cli.hpp"
#include "foveal/runtime/control_server.hpp"
#include "foveal/runtime/head_tracker.hpp"
#include "foveal/runtime/trace_markers.hpp"

namespace foveal::cmd {

namespace {

std::atomic<bool> g_interrupted{false};
void on_signal(int) { g_interrupted.store(true); }

/// The median sample interval's rate, for devices that do not say theirs.
double estimate_rate(const std::vector<GazeSample>& s) {
  if (s.size() < 3) return 0;
  std::vector<TimeNs> d;
  for (std::size_t i = 1; i < s.size(); ++i) d.push_back(s[i].t_ns - s[i - 1].t_ns);
  std::nth_element(d.begin(), d.begin() + static_cast<std::ptrdiff_t>(d.size() / 2), d.end());
  const TimeNs median = d[d.size() / 2];
  return median > 0 ? 1e9 / static_cast<double>(median) : 0;
}

// The recording's control requests: `mark` (stamped now, on the samples' clock) and
// `status`; replies as foveald's (docs/daemon.md).
nlohmann::json record_request(const nlohmann::json& req, cli::MarkerQueue& markers, std::uint64_t samples,
                              const std::string& out) {
  const std::string cmd = req["cmd"].get<std::string>();
  if (cmd == "status")
    return {{"ok", true}, {"recording", out}, {"samples", samples}, {"markers", markers.pushed()}};
  if (cmd == "mark") {
    const auto text = req.find("text");
    if (text == req.end() || !text->is_string()) return {{"ok", false}, {"error", "mark: expected \"text\": a string"}};
    if (Status st = check_marker_text(text->get<std::string>()); !st) return {{"ok", false}, {"error", st.error().message}};
    const TimeNs now = monotonic_now_ns();
    if (!markers.push({now, text->get<std::string>()}))
      return {{"ok", false}, {"error", "mark: " + std::to_string(cli::MarkerQueue::kMaxWaiting) +
                                           " markers wait for the next sample already; refused"}};
    return {{"ok", true}, {"t_ns", now}, {"markers", markers.pushed()}};
  }
  return {{"ok", false}, {"error", "unknown request '" + cmd + "' (a recording answers status and mark)"}};
}

/// The recording's quality, read back from the committed log; null with the reason when
/// it has none (no valid samples, a target outside it).
nlohmann::json recording_quality(const std::string& path, const std::vector<QualityTarget>& targets, bool print) {
  GazeLogHeader header;
  auto samples = read_gaze_log(path, &header);
  if (!samples) return {{"error", samples.error().message}};
  auto q = compute_gaze_quality(*samples, header.rate_hz, QualityOptions{std::nullopt, std::nullopt, targets});
  if (!q) {
    if (print) std::printf("  no quality figures: %s\n", q.error().message.c_str());
    return {{"error", q.error().message}};
  }
  if (print) evaluation::print_quality_text(path, *q);
  return evaluation::quality_json(path, *q);
}

/// How long a gaze sample waits for the head pose of its time before it is written
/// with the newest one there is (held).
constexpr TimeNs kPoseWaitNs = 100 * kNsPerMs;

/// The head-pose side of a recording: a pose thread on the headset and the samples
/// waiting for their pose.
class HeadRecorder {
 public:
  static Result<std::unique_ptr<HeadRecorder>> create(const std::string& spec_text) {
    auto spec = probe::parse_pose_spec(spec_text);
    if (!spec) return spec.error();
    auto dev = probe::make_pose_device(*spec);
    if (!dev) return dev.error();
    std::unique_ptr<HeadRecorder> h(new HeadRecorder());
    h->device_.emplace(std::move(*dev));
    h->tracker_ = std::make_unique<HeadTracker>(*h->device_->device, /*wait_for_device=*/true);
    h->tracker_->start();
    return h;
  }
  ~HeadRecorder() { tracker_->stop(); }

  void add(const GazeSample& s) { waiting_.push_back(s); }
  std::size_t waiting() const { return waiting_.size(); }
  /// The samples whose pose is in (or that waited long enough), with it; all with `all`.
  std::vector<GazeSample> ready(bool all) {
    std::vector<GazeSample> out;
    const auto newest = tracker_->track().newest();
    const TimeNs now = monotonic_now_ns();
    while (!waiting_.empty()) {
      GazeSample& s = waiting_.front();
      if (!all && !(newest && newest->t_ns >= s.t_ns) && now - s.t_ns < kPoseWaitNs) break;
      const PoseAt p = tracker_->track().pose_at(s.t_ns);
      if (p.valid) s.head = {true, p.pose};
      out.push_back(s);
      waiting_.pop_front();
    }
    return out;
  }
  nlohmann::json json() {
    tracker_->stop();
    const HeadTrackerStats st = tracker_->stats();
    return {{"head", device_->spec.text()},   {"device", st.device.name}, {"poses", st.poses},
            {"imu_samples", st.imu_samples}, {"reconnects", st.reconnects}, {"counters", device_->counters()}};
  }

 private:
  HeadRecorder() = default;
  std::optional<probe::OpenedPoseDevice> device_;
  std::unique_ptr<HeadTracker> tracker_;
  std::deque<GazeSample> waiting_;
};

}  // namespace

Status record_gaze(const probe::SourceSpec& spec, const RecordRequest& rq) {
  probe::SourceOptions so;
  so.synthetic_duration_s = rq.duration_s;
  auto device = probe::make_source(spec, so);
  if (!device) return device.error();
  std::vector<QualityTarget> targets;
  if (!rq.targets.empty()) {
    auto t = read_quality_targets(rq.targets);
    if (!t) return t.error();
    targets = std::move(t.value());
  }
  std::optional<ControlServer> control;
  if (rq.control || !rq.control_socket.empty()) {
    auto c = ControlServer::listen(rq.control_socket.empty() ? default_record_socket_path() : rq.control_socket);
    if (!c) return c.error();
    control.emplace(std::move(c.value()));
    control->set_logger([](const std::string& line) { cli::warn("control: " + line); });
  }
  cli::MarkerQueue markers;
  std::unique_ptr<HeadRecorder> head_rec;
  if (!rq.head.empty()) {
    auto h = HeadRecorder::create(rq.head);
    if (!h) return h.error();
    head_rec = std::move(*h);
  }
  GazeSource& src = *device->source;
  if (Status s = src.open(); !s) return s.error();
  if (Status s = src.start(); !s) return s.error();
  std::signal(SIGINT, on_signal);
  std::signal(SIGTERM, on_signal);
  const SourceInfo info = src.info();
  const TimeNs t_end = monotonic_now_ns() + static_cast<TimeNs>(rq.duration_s * 1e9);
  // The log header needs the rate: buffer the first second in case the device only
  // tells it in a status input report, or not at all.
  std::vector<GazeSample> first_second;
  std::optional<GazeLogWriter> writer;
  TimeNs last_t = 0;
  std::uint64_t reconnects = 0;
  // Markers go in before the first sample stamped later than them: the log stays in
  // time order. One stamped before the last written row (a source's clock running
  // ahead) is moved up to that row's time.
  TimeNs last_row_t = INT64_MIN;
  auto write_markers_until = [&](TimeNs t) -> Status {
    for (GazeMarker m : markers.take_until(t)) {
      m.t_ns = std::max(m.t_ns, last_row_t);
      if (Status st = writer->mark(m); !st) return st;
      last_row_t = m.t_ns;
    }
    return {};
  };
  auto write_sample = [&](const GazeSample& s) -> Status {
    if (Status st = write_markers_until(s.t_ns); !st) return st;
    last_row_t = s.t_ns;
    return writer->write(s);
  };
  auto open_writer = [&]() -> Status {
    GazeLogHeader h;
    if (head_rec) h.version = kGazeLogV2;
    h.rate_hz = src.info().nominal_rate_hz > 0 ? src.info().nominal_rate_hz : estimate_rate(first_second);
    if (!(h.rate_hz > 0)) h.rate_hz = 120;  // nothing to go on: the common tracker rate
    h.meta["driver"] = info.driver;
    h.meta["source"] = info.path;
    h.meta["device"] = info.name;
    if (head_rec) h.meta["head"] = rq.head;
    auto w = GazeLogWriter::create(rq.out, h);
    if (!w) return w.error();
    writer.emplace(std::move(w.value()));
    for (const GazeSample& s : first_second)
      if (Status st = write_sample(s); !st) return st;
    first_second.clear();
    return {};
  };
  // A sample goes to the log, or to the first second's buffer until the rate is known.
  auto take = [&](const GazeSample& s) -> Status {
    if (writer) return write_sample(s);
    first_second.push_back(s);
    return {};
  };
  const TimeNs first_second_until = monotonic_now_ns() + kNsPerSec;
  while (!g_interrupted.load() && monotonic_now_ns() < t_end) {
    if (control)
      control->poll(0, [&](const nlohmann::json& req) {
        return record_request(req, markers,
                              (writer ? writer->samples_written() : 0) + first_second.size() +
                                  (head_rec ? head_rec->waiting() : 0),
                              rq.out);
      });
    const auto r = src.next(std::chrono::milliseconds(control ? 20 : 50));
    if (r.status == ReadStatus::sample && r.sample.t_ns > last_t) {
      last_t = r.sample.t_ns;
      if (head_rec) head_rec->add(r.sample);  // waits for its pose
      else if (Status st = take(r.sample); !st) return st.error();
    } else if (r.status == ReadStatus::disconnected) {
      if (reopen_with_backoff(src, [&] { return g_interrupted.load() || monotonic_now_ns() >= t_end; })) ++reconnects;
    } else if (r.status == ReadStatus::end) {
      break;
    } else if (r.status == ReadStatus::error) {
      return r.error;
    }
    if (head_rec)
      for (const GazeSample& s : head_rec->ready(false))
        if (Status st = take(s); !st) return st.error();
    if (!writer && monotonic_now_ns() >= first_second_until)
      if (Status st = open_writer(); !st) return st.error();
  }
  src.close();
  if (head_rec)
    for (const GazeSample& s : head_rec->ready(true))
      if (Status st = take(s); !st) return st.error();
  if (!writer)
    if (Status st = open_writer(); !st) return st.error();
  control.reset();  // no marks after the end; removes the socket
  Status st = write_markers_until(INT64_MAX);
  if (st) st = writer->commit();
  if (!st) return st.error();
  nlohmann::json j = {{"output", rq.out},  {"driver", info.driver},     {"device", info.path},
                      {"samples", writer->samples_written()}, {"reconnects", reconnects},
                      {"markers", markers.pushed()}, {"driver_counters", device->counters()}};
  if (head_rec) j["head"] = head_rec->json();
  if (!rq.json)
    std::printf("recorded %llu samples, %llu markers from %s %s -> %s (%llu reconnects)\n",
                static_cast<unsigned long long>(writer->samples_written()),
                static_cast<unsigned long long>(markers.pushed()), info.driver.c_str(), info.path.c_str(),
                rq.out.c_str(), static_cast<unsigned long long>(reconnects));
  j["quality"] = recording_quality(rq.out, targets, !rq.json);
  if (rq.json) cli::print_json(j);
  return {};
}

}  // namespace foveal::cmd
