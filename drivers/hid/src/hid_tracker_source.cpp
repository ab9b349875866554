#include "foveal/drivers/hid/hid_tracker_source.hpp"

#include <cstdio>

namespace foveal::hid {
namespace {

constexpr std::size_t kMaxReportBytes = 4096;  // hidraw's HID_MAX_BUFFER_SIZE

bool same_identity(const HidDeviceEntry& a, const HidDeviceEntry& b) {
  return a.vendor_id == b.vendor_id && a.product_id == b.product_id && a.serial == b.serial;
}

}  // namespace

HidTrackerSource::HidTrackerSource(HidTrackerOptions opts, std::shared_ptr<HidBackend> backend)
    : opts_(std::move(opts)), backend_(std::move(backend)), buffer_(kMaxReportBytes) {
  if (!opts_.log) opts_.log = [](const std::string& m) { std::fprintf(stderr, "foveal: %s\n", m.c_str()); };
}

HidTrackerSource::~HidTrackerSource() { close(); }

void HidTrackerSource::problem(std::string message) {
  if (problems_.count()) opts_.log("hid: " + message + " (problem " + std::to_string(problems_.problems()) + ")");
  counters_.last_problem = std::move(message);
}

Result<TrackerEntry> HidTrackerSource::choose_device(HidBackend& backend) {
  auto trackers = find_eye_trackers(backend);
  if (!trackers) return trackers.error();
  // A reconnecting device may come back on another hidraw node: match it by identity.
  const TrackerEntry* by_path = nullptr;
  const TrackerEntry* by_identity = nullptr;
  for (const TrackerEntry& t : *trackers) {
    if (!opts_.device.empty() && t.device.path == opts_.device && !by_path) by_path = &t;
    if (entry_ && same_identity(t.device, entry_->device) && !by_identity) by_identity = &t;
  }
  if (by_path) return *by_path;
  if (by_identity) return *by_identity;
  if (opts_.device.empty() && !entry_ && !trackers->empty()) return trackers->front();
  if (!opts_.device.empty())
    return Error{ErrorKind::device, opts_.device + ": no HID eye tracker (usage page 0x12) at this path"};
  return Error{ErrorKind::device, "hid: no HID eye tracker (usage page 0x12) found"};
}

Status HidTrackerSource::open() {
  close();
  auto chosen = choose_device(*backend_);
  if (!chosen) return chosen.error();
  auto dev = backend_->open(chosen->device.path);
  if (!dev) return dev.error();
  device_ = std::move(dev.value());
  entry_ = std::move(chosen.value());
  ++counters_.opens;
  clock_.reset();
  read_features();
  return {};
}

void HidTrackerSource::read_features() {
  const TrackerLayout& l = entry_->layout;
  const std::string& path = entry_->device.path;
  // Each feature report is optional: a device that cannot answer keeps the defaults.
  auto fetch = [&](const ReportRef& ref, const char* what) -> std::optional<std::vector<std::uint8_t>> {
    if (!ref.present) return std::nullopt;
    auto r = device_->get_feature(ref.id, ref.bytes);
    if (!r) {
      ++counters_.feature_errors;
      problem(path + ": " + what + " feature report: " + r.error().message);
      return std::nullopt;
    }
    return std::move(r.value());
  };
  auto note = [&](const Error& e) {
    ++counters_.feature_errors;
    problem(path + ": " + e.message);
  };
  caps_ = {};
  config_ = {};
  if (auto bytes = fetch(l.capabilities, "Capabilities")) {
    if (auto c = decode_capabilities(l, *bytes)) caps_ = *c;
    else note(c.error());
  }
  if (auto bytes = fetch(l.configuration, "Configuration")) {
    if (auto c = decode_configuration(l, *bytes)) config_ = *c;
    else note(c.error());
  }
  if (auto bytes = fetch(l.status_feature, "Tracker Status")) {
    if (auto s = decode_status(l, ReportType::feature, *bytes)) status_ = *s;
    else note(s.error());
  }
  plane_ = ScreenPlane::from(config_, caps_);
  plane_.ipd_mm = opts_.ipd_mm;
}

void HidTrackerSource::close() {
  if (device_ && started_) stop();
  device_.reset();
  started_ = false;
}

Status HidTrackerSource::start() {
  if (!device_) return Error{ErrorKind::internal, "hid: start() before open()"};
  auto request = encode_mode_request(entry_->layout, opts_.mode);
  if (!request) return request.error();
  if (Status s = device_->send_feature(*request); !s)
    return Error{ErrorKind::device, "hid: enabling gaze (Mode Request " + std::to_string(opts_.mode) + "): " + s.error().message};
  started_ = true;
  return {};
}

void HidTrackerSource::stop() {
  if (!device_ || !started_) return;
  started_ = false;
  // Best effort: the device may already be gone.
  if (auto request = encode_mode_request(entry_->layout, 0)) (void)device_->send_feature(*request);
}

bool HidTrackerSource::handle_report(std::span<const std::uint8_t> report, TimeNs arrival, GazeSample& out) {
  const TrackerLayout& l = entry_->layout;
  const std::uint8_t id = l.descriptor.uses_report_ids && !report.empty() ? report[0] : 0;
  const ReportRef* ref = l.tracking.id == id ? &l.tracking : l.status_input.present && l.status_input.id == id ? &l.status_input : nullptr;
  if (report.empty() || !ref) {
    ++counters_.unknown_reports;
    problem(entry_->device.path + ": input report with unknown ID " + std::to_string(id) + " (" +
            std::to_string(report.size()) + " bytes)");
    return false;
  }
  if (report.size() < ref->bytes) ++counters_.truncated;
  if (ref == &l.status_input) {
    auto s = decode_status(l, ReportType::input, report);
    if (!s) {
      ++counters_.malformed;
      problem(entry_->device.path + ": " + s.error().message);
      return false;
    }
    ++counters_.status_reports;
    status_.configuration_status = s->configuration_status;
    if (s->sampling_frequency_hz > 0) status_.sampling_frequency_hz = s->sampling_frequency_hz;
    return false;
  }
  auto t = decode_tracking_data(l, report);
  if (!t) {
    ++counters_.malformed;
    problem(entry_->device.path + ": " + t.error().message);
    return false;
  }
  last_ = *t;
  if (!t->gaze_valid) ++counters_.invalid_gaze;
  out = screen_gaze_to_sample(*t, plane_);
  out.t_ns = clock_.map(arrival, t->device_time_ns);
  last_device_t_ns_ = t->device_time_ns.value_or(0);
  return true;
}

ReadResult HidTrackerSource::next(std::chrono::nanoseconds timeout) {
  ReadResult r;
  if (!device_ || !started_) {
    r.status = ReadStatus::error;
    r.error = {ErrorKind::internal, "hid: next() before open() and start()"};
    return r;
  }
  const TimeNs deadline = monotonic_now_ns() + timeout.count();
  for (;;) {
    const TimeNs left = deadline - monotonic_now_ns();
    const int wait_ms = left <= 0 ? 0 : static_cast<int>(std::min<TimeNs>((left + kNsPerMs - 1) / kNsPerMs, 1000));
    auto got = device_->read(buffer_, wait_ms);
    if (!got) {
      // The device is gone (hidraw reports removal as a read error): release it now so
      // the caller's close/open/start cycle finds the new node.
      ++counters_.disconnects;
      problem("disconnected: " + got.error().message);
      device_.reset();
      started_ = false;
      r.status = ReadStatus::disconnected;
      r.error = got.error();
      return r;
    }
    if (*got == 0) {
      if (monotonic_now_ns() >= deadline) {
        r.status = ReadStatus::timeout;
        return r;
      }
      continue;
    }
    ++counters_.reports;
    const TimeNs arrival = monotonic_now_ns();
    if (handle_report(std::span<const std::uint8_t>(buffer_.data(), *got), arrival, r.sample)) {
      r.device_t_ns = last_device_t_ns_;
      ++counters_.samples;
      r.status = ReadStatus::sample;
      return r;
    }
    if (monotonic_now_ns() >= deadline) {
      r.status = ReadStatus::timeout;
      return r;
    }
  }
}

bool HidTrackerSource::wait_for_rate(std::chrono::nanoseconds timeout) {
  if (status_.sampling_frequency_hz > 0) return true;
  if (!device_) return false;
  const TimeNs deadline = monotonic_now_ns() + timeout.count();
  GazeSample ignored;
  for (TimeNs left = timeout.count(); left > 0 && status_.sampling_frequency_hz <= 0; left = deadline - monotonic_now_ns()) {
    auto got = device_->read(buffer_, static_cast<int>(std::min<TimeNs>((left + kNsPerMs - 1) / kNsPerMs, 1000)));
    if (!got) return false;
    if (*got > 0) handle_report(std::span<const std::uint8_t>(buffer_.data(), *got), monotonic_now_ns(), ignored);
  }
  return status_.sampling_frequency_hz > 0;
}

SourceInfo HidTrackerSource::info() const {
  SourceInfo i;
  i.driver = "hid";
  if (!entry_) {
    i.path = opts_.device;
    return i;
  }
  i.path = entry_->device.path;
  i.name = entry_->device.manufacturer.empty() ? entry_->device.product
                                                : entry_->device.manufacturer + " " + entry_->device.product;
  i.vendor_id = entry_->device.vendor_id;
  i.product_id = entry_->device.product_id;
  i.nominal_rate_hz = status_.sampling_frequency_hz;
  return i;
}

}  // namespace foveal::hid
