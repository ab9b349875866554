#include "foveal/drivers/vive/vive_source.hpp"

#include <array>
#include <cstdio>

namespace foveal::vive {

Result<std::vector<ViveDeviceEntry>> find_vive_devices(hid::HidBackend& backend) {
  auto all = backend.enumerate();
  if (!all) return all.error();
  std::vector<ViveDeviceEntry> out;
  for (const hid::HidDeviceEntry& d : *all) {
    if (d.vendor_id != kValveVendor || (d.product_id != kViveSensorProduct && d.product_id != kViveProSensorProduct))
      continue;
    const std::string model = d.product_id == kViveProSensorProduct ? "HTC Vive Pro" : "HTC Vive";
    out.push_back({d.path, model + " (" + (d.product.empty() ? "sensors" : d.product) + ")", d.serial, d.vendor_id,
                   d.product_id});
  }
  return out;
}

Result<std::string> read_config_json(hid::HidDevice& dev) {
  if (auto start = dev.get_feature(kConfigStartReportId, kConfigReportBytes); !start)
    return Error{start.error().kind, "vive config: start report 0x10: " + start.error().message};
  ConfigAssembler a;
  // At most 64 KiB / 62 bytes per report, plus the empty one that ends it.
  for (std::size_t i = 0; !a.complete() && i <= kConfigCompressedMax / kConfigPayloadMax + 1; ++i) {
    auto rep = dev.get_feature(kConfigReadReportId, kConfigReportBytes);
    if (!rep) return Error{rep.error().kind, "vive config: read report 0x11 #" + std::to_string(i) + ": " + rep.error().message};
    if (Status s = a.add(*rep); !s) return s.error();
  }
  return a.json();
}

ViveSource::ViveSource(ViveOptions opts, std::shared_ptr<hid::HidBackend> backend)
    : opts_(std::move(opts)), backend_(backend ? std::move(backend) : hid::make_hidapi_backend()) {
  if (!opts_.log) opts_.log = [](const std::string& m) { std::fprintf(stderr, "foveal: %s\n", m.c_str()); };
}

void ViveSource::problem(std::string message) {
  if (problems_.count()) opts_.log("vive: " + message);
  counters_.last_problem = std::move(message);
}

Status ViveSource::open() {
  close();
  auto found = find_vive_devices(*backend_);
  if (!found) return found.error();
  const ViveDeviceEntry* pick = nullptr;
  for (const ViveDeviceEntry& e : *found)
    if (opts_.device.empty() || e.path == opts_.device) {
      pick = &e;
      break;
    }
  if (!pick)
    return Error{ErrorKind::device, opts_.device.empty()
                                        ? "vive: no HTC Vive sensor device (28de:2000 or 28de:2300) found, or no permission (udev/70-foveal.rules)"
                                        : "vive: " + opts_.device + " is not a Vive sensor device present"};
  entry_ = *pick;
  auto dev = backend_->open(entry_.path);
  if (!dev) return dev.error();
  dev_ = std::move(*dev);
  ++counters_.opens;
  // The IMU ranges; the defaults when unreadable (as Monado does).
  range_ = ImuRange{};
  if (auto rep = dev_->get_feature(kRangeReportId, kRangeReportBytes); rep) {
    if (auto r = parse_range_report(*rep); r) range_ = *r;
    else problem(r.error().message + "; assuming ±500 °/s, ±4 g");
  } else {
    problem("IMU range report: " + rep.error().message + "; assuming ±500 °/s, ±4 g");
  }
  // The configuration: IMU calibration and lens data. Without it the IMU still works
  // uncalibrated, and the display model stays the profile's.
  config_.reset();
  calibration_ = Config{};
  calibration_.variant = entry_.product_id == kViveProSensorProduct ? Variant::vive_pro : Variant::vive;
  if (auto text = read_config_json(*dev_); !text) {
    ++counters_.config_errors;
    problem(text.error().message + "; the IMU is read uncalibrated");
  } else if (auto c = parse_config(*text); !c) {
    ++counters_.config_errors;
    problem(c.error().message + "; the IMU is read uncalibrated");
  } else {
    config_json_ = *text;
    config_ = *c;
    calibration_ = *c;
  }
  last_seq_.reset();
  last_ticks_.reset();
  ticks_high_ = 0;
  clock_.reset();
  queue_.clear();
  return {};
}

void ViveSource::close() {
  dev_.reset();
  queue_.clear();
}

Status ViveSource::start() {
  if (!dev_) return Error{ErrorKind::internal, "vive: start() before open()"};
  return {};  // the IMU streams once the headset is powered
}

PoseReading ViveSource::next(std::chrono::nanoseconds timeout) {
  PoseReading r;
  if (!dev_) {
    r.status = ReadStatus::error;
    r.error = {ErrorKind::internal, "vive: next() before open()"};
    return r;
  }
  const TimeNs deadline = monotonic_now_ns() + timeout.count();
  std::array<std::uint8_t, 64> buf{};
  while (queue_.empty()) {
    const TimeNs left = deadline - monotonic_now_ns();
    if (left <= 0) {
      r.status = ReadStatus::timeout;
      return r;
    }
    auto n = dev_->read(buf, static_cast<int>(std::max<TimeNs>(1, left / kNsPerMs)));
    if (!n) {
      ++counters_.disconnects;
      problem("disconnected: " + n.error().message);
      close();
      r.status = ReadStatus::disconnected;
      r.error = n.error();
      return r;
    }
    if (*n == 0) continue;
    const TimeNs arrival = monotonic_now_ns();
    if (buf[0] != kImuReportId) {  // light-house pulses and others: not ours
      ++counters_.other_reports;
      continue;
    }
    ++counters_.reports;
    auto rep = parse_imu_report(std::span<const std::uint8_t>(buf.data(), *n));
    if (!rep) {
      ++counters_.malformed;
      problem(rep.error().message);
      continue;
    }
    for (const ImuRawSample& raw : new_imu_samples(*rep, last_seq_)) {
      last_seq_ = raw.seq;
      if (last_ticks_ && raw.time < *last_ticks_ && *last_ticks_ - raw.time > 0x8000'0000u) ticks_high_ += std::int64_t{1} << 32;
      last_ticks_ = raw.time;
      const std::int64_t ticks = ticks_high_ + raw.time;
      const std::int64_t device_ns = static_cast<std::int64_t>(static_cast<double>(ticks) * (1e9 / kImuClockHz));
      ImuSample s = imu_to_sample(raw, calibration_, range_);
      s.t_ns = clock_.map(arrival, device_ns);
      s.has_device_time = true;
      s.device_t_ns = device_ns;
      queue_.push_back(s);
      ++counters_.samples;
    }
  }
  r.status = ReadStatus::sample;
  r.has_imu = true;
  r.imu = queue_.front();
  queue_.pop_front();
  return r;
}

PoseDeviceInfo ViveSource::info() const {
  PoseDeviceInfo i;
  i.driver = "vive";
  i.name = entry_.name.empty() ? "HTC Vive" : entry_.name;
  i.path = entry_.path;
  i.vendor_id = entry_.vendor_id;
  i.product_id = entry_.product_id;
  i.imu = true;
  i.imu_rate_hz = kImuRateHz;
  return i;
}

}  // namespace foveal::vive
