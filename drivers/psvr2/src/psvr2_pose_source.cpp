#include "foveal/drivers/psvr2/psvr2_pose_source.hpp"

#include <libusb-1.0/libusb.h>

#include <cstdio>

namespace foveal::usb {

namespace {

constexpr std::size_t kQueueMax = 8192;  // ~4 s of IMU: a reader that stalls loses the oldest

Error usb_error(const std::string& where, int rc) {
  return Error{ErrorKind::device, "psvr2 pose: " + where + ": " + libusb_strerror(rc)};
}

/// The first IN endpoint of `interface` (any alternate setting) as the device describes
/// it, and whether it is an interrupt endpoint; the defaults when not found.
void find_endpoint(libusb_device* dev, int interface, std::uint8_t& ep, bool& interrupt) {
  libusb_config_descriptor* config = nullptr;
  if (libusb_get_active_config_descriptor(dev, &config) != 0 || config == nullptr) return;
  for (int i = 0; i < config->bNumInterfaces; ++i) {
    const libusb_interface& itf = config->interface[i];
    for (int a = 0; a < itf.num_altsetting; ++a) {
      const libusb_interface_descriptor& d = itf.altsetting[a];
      if (d.bInterfaceNumber != interface) continue;
      for (int e = 0; e < d.bNumEndpoints; ++e) {
        const libusb_endpoint_descriptor& x = d.endpoint[e];
        const int type = x.bmAttributes & 3;
        if ((x.bEndpointAddress & LIBUSB_ENDPOINT_IN) &&
            (type == LIBUSB_TRANSFER_TYPE_BULK || type == LIBUSB_TRANSFER_TYPE_INTERRUPT)) {
          ep = x.bEndpointAddress;
          interrupt = type == LIBUSB_TRANSFER_TYPE_INTERRUPT;
          libusb_free_config_descriptor(config);
          return;
        }
      }
    }
  }
  libusb_free_config_descriptor(config);
}

}  // namespace

struct Psvr2PoseSource::Transfer {
  Transfer(Psvr2PoseSource* o, bool s) : owner(o), slam(s) {}
  Psvr2PoseSource* owner;
  bool slam;
  libusb_transfer* xfer = nullptr;
  std::vector<std::uint8_t> buffer;
  bool in_flight = false;
};

Psvr2PoseSource::Psvr2PoseSource(Psvr2PoseOptions opts) : opts_(std::move(opts)) {
  if (!opts_.log) opts_.log = [](const std::string& m) { std::fprintf(stderr, "foveal: %s\n", m.c_str()); };
}

Psvr2PoseSource::~Psvr2PoseSource() {
  close();
  if (ctx_) libusb_exit(ctx_);
}

void Psvr2PoseSource::problem(std::string message) {
  if (problems_.count()) opts_.log("psvr2 pose: " + message);
  counters_.last_problem = std::move(message);
}

Status Psvr2PoseSource::open() {
  close();
  // A fresh context at every open, as the gaze driver does: it enumerates the bus anew.
  if (ctx_) libusb_exit(ctx_);
  ctx_ = nullptr;
  if (int rc = libusb_init(&ctx_); rc != 0) {
    ctx_ = nullptr;
    return usb_error("libusb_init", rc);
  }
  handle_ = libusb_open_device_with_vid_pid(ctx_, kPsvr2Vendor, kPsvr2Product);
  if (!handle_)
    return Error{ErrorKind::device, "psvr2 pose: no PlayStation VR2 (054c:0cde) found, or no permission (udev/70-foveal.rules)"};
  libusb_device* dev = libusb_get_device(handle_);
  path_ = "usb:" + std::to_string(libusb_get_bus_number(dev)) + ":" + std::to_string(libusb_get_device_address(dev));
  status_ep_ = psvr2::kStatusEndpoint, status_interrupt_ = true;
  slam_ep_ = psvr2::kSlamEndpoint, slam_interrupt_ = false;
  find_endpoint(dev, psvr2::kStatusInterface, status_ep_, status_interrupt_);
  find_endpoint(dev, psvr2::kSlamInterface, slam_ep_, slam_interrupt_);
  libusb_set_auto_detach_kernel_driver(handle_, 1);
  if (int rc = libusb_claim_interface(handle_, psvr2::kStatusInterface); rc != 0) {
    close();
    return usb_error("claim interface 7 (status)", rc);
  }
  claimed_status_ = true;
  // The headset streams status on alternate setting 1 (Monado); a device without it
  // (an emulation) streams on its only one.
  if (int rc = libusb_set_interface_alt_setting(handle_, psvr2::kStatusInterface, psvr2::kStatusAltSetting); rc != 0)
    problem(std::string("interface 7 alternate setting 1: ") + libusb_strerror(rc) + "; reading setting 0");
  if (int rc = libusb_claim_interface(handle_, psvr2::kSlamInterface); rc != 0) {
    close();
    return usb_error("claim interface 3 (SLAM)", rc);
  }
  claimed_slam_ = true;
  gone_ = false;
  clock_.reset();
  wrap_ = WrapCounter{};
  queue_.clear();
  return {};
}

void Psvr2PoseSource::callback(libusb_transfer* t) {
  auto* tr = static_cast<Transfer*>(t->user_data);
  Psvr2PoseSource& self = *tr->owner;
  tr->in_flight = false;
  if (t->status == LIBUSB_TRANSFER_COMPLETED) {
    const TimeNs arrival = monotonic_now_ns();
    if (t->actual_length > 0) {
      if (tr->slam) self.on_slam(t->buffer, t->actual_length, arrival);
      else self.on_status(t->buffer, t->actual_length, arrival);
    }
  } else if (t->status == LIBUSB_TRANSFER_NO_DEVICE || t->status == LIBUSB_TRANSFER_ERROR ||
             t->status == LIBUSB_TRANSFER_STALL) {
    self.gone_ = true;
    return;
  } else if (t->status == LIBUSB_TRANSFER_CANCELLED) {
    return;
  }
  // Completed or timed out: read on.
  if (self.started_ && !self.gone_) {
    if (libusb_submit_transfer(t) == 0) tr->in_flight = true;
    else self.gone_ = true;
  }
}

void Psvr2PoseSource::on_status(const std::uint8_t* data, int length, TimeNs arrival) {
  ++counters_.status_transfers;
  auto rep = parse_psvr2_status(std::span<const std::uint8_t>(data, static_cast<std::size_t>(length)));
  if (!rep) {
    ++counters_.malformed;
    problem(rep.error().message);
    return;
  }
  if (rep->ipd_mm) counters_.ipd_mm = rep->ipd_mm;
  for (const Psvr2ImuRecord& m : rep->imu) {
    PoseReading r;
    r.status = ReadStatus::sample;
    r.has_imu = true;
    r.imu = psvr2_imu_to_sample(m);
    r.imu.device_t_ns = wrap_.unwrap_ns(m.vts_us);
    r.imu.has_device_time = true;
    r.imu.t_ns = clock_.map(arrival, r.imu.device_t_ns);
    if (queue_.size() >= kQueueMax) queue_.pop_front();
    queue_.push_back(r);
    ++counters_.imu_samples;
  }
}

void Psvr2PoseSource::on_slam(const std::uint8_t* data, int length, TimeNs arrival) {
  ++counters_.slam_transfers;
  // One record per transfer on the headset; a bulk endpoint whose packets are smaller
  // than a record (512 bytes at high speed) can deliver two back to back.
  const auto n = static_cast<std::size_t>(length);
  for (std::size_t at = 0; at < n; at += psvr2::kSlamRecordBytes) {
    const std::size_t size = std::min(psvr2::kSlamRecordBytes, n - at);
    auto rec = parse_psvr2_slam(std::span<const std::uint8_t>(data + at, size));
    if (!rec) {
      ++counters_.malformed;
      problem(rec.error().message);
      return;
    }
    PoseReading r;
    r.status = ReadStatus::sample;
    r.has_pose = true;
    r.pose.pose = psvr2_slam_to_pose(*rec);
    // The SLAM timestamp is on the IMU's clock; before the first IMU record, on arrival.
    const std::int64_t device_ns = wrap_.unwrap_ns(rec->vts_us);
    r.pose.t_ns = clock_.anchored() ? std::min<TimeNs>(clock_.to_runtime(device_ns), arrival) : arrival;
    r.pose_has_device_time = true;
    r.pose_device_t_ns = device_ns;
    if (queue_.size() >= kQueueMax) queue_.pop_front();
    queue_.push_back(r);
    ++counters_.poses;
  }
}

Status Psvr2PoseSource::start() {
  if (!handle_) return Error{ErrorKind::internal, "psvr2 pose: start() before open()"};
  started_ = true;
  for (bool slam : {false, true}) {
    transfers_.push_back(std::make_unique<Transfer>(this, slam));
    Transfer* tr = transfers_.back().get();
    tr->buffer.resize(slam ? psvr2::kSlamRecordBytes * 2 : psvr2::kStatusTransferBytes);
    tr->xfer = libusb_alloc_transfer(0);
    const std::uint8_t ep = slam ? slam_ep_ : status_ep_;
    if (slam ? slam_interrupt_ : status_interrupt_)
      libusb_fill_interrupt_transfer(tr->xfer, handle_, ep, tr->buffer.data(), static_cast<int>(tr->buffer.size()), callback, tr, 0);
    else
      libusb_fill_bulk_transfer(tr->xfer, handle_, ep, tr->buffer.data(), static_cast<int>(tr->buffer.size()), callback, tr, 0);
    if (int rc = libusb_submit_transfer(tr->xfer); rc != 0) {
      stop();
      return usb_error(slam ? "submit SLAM transfer" : "submit status transfer", rc);
    }
    tr->in_flight = true;
  }
  return {};
}

void Psvr2PoseSource::stop() {
  started_ = false;
  for (const auto& tr : transfers_)
    if (tr->in_flight) libusb_cancel_transfer(tr->xfer);
  // Let the cancellations complete before the transfers are freed (bounded: a vanished
  // device completes them at once).
  for (int i = 0; i < 50; ++i) {
    bool any = false;
    for (const auto& tr : transfers_) any |= tr->in_flight;
    if (!any) break;
    timeval tv{0, 10'000};
    libusb_handle_events_timeout(ctx_, &tv);
  }
  for (auto& tr : transfers_) {
    if (tr->in_flight) {
      tr.release();  // still in flight after 0.5 s: leaked rather than freed under libusb
      continue;
    }
    libusb_free_transfer(tr->xfer);
  }
  transfers_.clear();
}

void Psvr2PoseSource::close() {
  if (!transfers_.empty() || started_) stop();
  if (handle_) {
    if (claimed_slam_) libusb_release_interface(handle_, psvr2::kSlamInterface);
    if (claimed_status_) libusb_release_interface(handle_, psvr2::kStatusInterface);
    libusb_close(handle_);
  }
  handle_ = nullptr;
  claimed_status_ = claimed_slam_ = false;
}

PoseReading Psvr2PoseSource::next(std::chrono::nanoseconds timeout) {
  PoseReading r;
  if (!handle_ || !started_) {
    r.status = ReadStatus::error;
    r.error = {ErrorKind::internal, "psvr2 pose: next() before open() and start()"};
    return r;
  }
  const TimeNs deadline = monotonic_now_ns() + timeout.count();
  while (queue_.empty() && !gone_) {
    const TimeNs left = deadline - monotonic_now_ns();
    if (left <= 0) {
      r.status = ReadStatus::timeout;
      return r;
    }
    timeval tv{static_cast<time_t>(left / kNsPerSec), static_cast<suseconds_t>((left % kNsPerSec) / 1000)};
    if (int rc = libusb_handle_events_timeout(ctx_, &tv); rc != 0 && rc != LIBUSB_ERROR_INTERRUPTED) gone_ = true;
  }
  if (!queue_.empty()) {
    r = queue_.front();
    queue_.pop_front();
    return r;
  }
  ++counters_.disconnects;
  problem("disconnected");
  close();
  r.status = ReadStatus::disconnected;
  r.error = {ErrorKind::device, "psvr2 pose: the headset went away"};
  return r;
}

PoseDeviceInfo Psvr2PoseSource::info() const {
  PoseDeviceInfo i;
  i.driver = "psvr2";
  i.name = "PlayStation VR2 head tracking";
  i.path = path_;
  i.vendor_id = kPsvr2Vendor;
  i.product_id = kPsvr2Product;
  i.position = i.orientation = i.imu = true;
  i.imu_rate_hz = psvr2::kImuRateHz;
  return i;
}

}  // namespace foveal::usb
