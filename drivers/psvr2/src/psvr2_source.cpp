#include "foveal/drivers/psvr2/psvr2_source.hpp"

#include <libusb-1.0/libusb.h>

#include <cstdio>

namespace foveal::usb {
namespace {

constexpr std::size_t kTransferBytes = 32 * 1024;  // what the headset's own driver asks for
constexpr TimeNs kKeepAliveNs = 1 * kNsPerSec;
constexpr std::uint8_t kGazeStreamReport = 0x0C;
constexpr std::uint8_t kEnable = 0x01, kDisable = 0x02;

Error usb_error(const std::string& where, int rc) {
  return Error{ErrorKind::device, "psvr2: " + where + ": " + libusb_strerror(rc)};
}

/// The first bulk IN endpoint of the gaze interface as the device describes it; the
/// headset says 0x85, an emulated one may differ.
std::uint8_t find_gaze_endpoint(libusb_device* dev) {
  libusb_config_descriptor* config = nullptr;
  if (libusb_get_active_config_descriptor(dev, &config) != 0 || config == nullptr) return kPsvr2GazeEndpoint;
  std::uint8_t found = kPsvr2GazeEndpoint;
  for (int i = 0; i < config->bNumInterfaces; ++i) {
    const libusb_interface& itf = config->interface[i];
    for (int a = 0; a < itf.num_altsetting && a < 1; ++a) {
      const libusb_interface_descriptor& d = itf.altsetting[a];
      if (d.bInterfaceNumber != kPsvr2GazeInterface) continue;
      for (int e = 0; e < d.bNumEndpoints; ++e) {
        const libusb_endpoint_descriptor& ep = d.endpoint[e];
        if ((ep.bEndpointAddress & LIBUSB_ENDPOINT_IN) && (ep.bmAttributes & 3) == LIBUSB_TRANSFER_TYPE_BULK) {
          found = ep.bEndpointAddress;
          e = d.bNumEndpoints;
        }
      }
    }
  }
  libusb_free_config_descriptor(config);
  return found;
}

}  // namespace

Psvr2Source::Psvr2Source(Psvr2Options opts) : opts_(std::move(opts)), buffer_(kTransferBytes) {
  if (!opts_.log) opts_.log = [](const std::string& m) { std::fprintf(stderr, "foveal: %s\n", m.c_str()); };
}

Psvr2Source::~Psvr2Source() {
  close();
  if (ctx_) libusb_exit(ctx_);
}

void Psvr2Source::problem(std::string message) {
  if (problems_.count()) opts_.log("psvr2: " + message);
  counters_.last_problem = std::move(message);
}

Status Psvr2Source::open() {
  close();
  // A fresh context at every open: it enumerates the bus anew. A kept one only learns
  // of devices through hotplug events, which libusb takes from the udev daemon; where
  // none runs (containers, minimal systems, the VM tests) a headset plugged in after
  // the first open, or back after an unplug, would never be found.
  if (ctx_) libusb_exit(ctx_);
  if (int rc = libusb_init(&ctx_); rc != 0) {
    ctx_ = nullptr;
    return usb_error("libusb_init", rc);
  }
  handle_ = libusb_open_device_with_vid_pid(ctx_, kPsvr2Vendor, kPsvr2Product);
  if (!handle_) return Error{ErrorKind::device, "psvr2: no PlayStation VR2 (054c:0cde) found, or no permission (udev/70-foveal.rules)"};
  libusb_device* dev = libusb_get_device(handle_);
  path_ = "usb:" + std::to_string(libusb_get_bus_number(dev)) + ":" + std::to_string(libusb_get_device_address(dev));
  endpoint_ = find_gaze_endpoint(dev);
  libusb_set_auto_detach_kernel_driver(handle_, 1);
  if (int rc = libusb_claim_interface(handle_, kPsvr2GazeInterface); rc != 0) {
    close();
    return usb_error("claim interface 5", rc);
  }
  claimed_ = true;
  anchored_ = false;
  return {};
}

void Psvr2Source::close() {
  if (started_) stop();
  if (handle_) {
    if (claimed_) libusb_release_interface(handle_, kPsvr2GazeInterface);
    libusb_close(handle_);
  }
  handle_ = nullptr;
  claimed_ = false;
}

Status Psvr2Source::send_gaze_stream(bool enable) {
  // HID-class SET_REPORT (feature) on the gaze interface: report 0x0C, subcommand.
  unsigned char report[2] = {kGazeStreamReport, enable ? kEnable : kDisable};
  const int rc = libusb_control_transfer(handle_, 0x21, 0x09, static_cast<std::uint16_t>(0x0300 | kGazeStreamReport),
                                         kPsvr2GazeInterface, report, sizeof report, 500);
  if (rc < 0) return usb_error(enable ? "enable gaze stream" : "disable gaze stream", rc);
  return {};
}

Status Psvr2Source::start() {
  if (!handle_) return Error{ErrorKind::internal, "psvr2: start() before open()"};
  if (Status s = send_gaze_stream(true); !s) return s;
  last_keepalive_ = monotonic_now_ns();
  started_ = true;
  return {};
}

void Psvr2Source::stop() {
  if (!handle_ || !started_) return;
  started_ = false;
  (void)send_gaze_stream(false);  // best effort: the headset may be gone
}

ReadResult Psvr2Source::next(std::chrono::nanoseconds timeout) {
  ReadResult r;
  if (!handle_ || !started_) {
    r.status = ReadStatus::error;
    r.error = {ErrorKind::internal, "psvr2: next() before open() and start()"};
    return r;
  }
  const TimeNs deadline = monotonic_now_ns() + timeout.count();
  for (;;) {
    if (monotonic_now_ns() - last_keepalive_ > kKeepAliveNs) {  // the stream stops without it
      (void)send_gaze_stream(true);
      last_keepalive_ = monotonic_now_ns();
    }
    const TimeNs left = deadline - monotonic_now_ns();
    const auto wait_ms = static_cast<unsigned>(std::max<TimeNs>(1, (left + kNsPerMs - 1) / kNsPerMs));
    int got = 0;
    const int rc = libusb_bulk_transfer(handle_, endpoint_, buffer_.data(), static_cast<int>(buffer_.size()),
                                        &got, wait_ms);
    if (rc == LIBUSB_ERROR_NO_DEVICE || rc == LIBUSB_ERROR_IO || rc == LIBUSB_ERROR_PIPE) {
      ++counters_.disconnects;
      problem("disconnected: " + std::string(libusb_strerror(rc)));
      started_ = false;
      close();
      r.status = ReadStatus::disconnected;
      r.error = usb_error("read", rc);
      return r;
    }
    if (rc == 0 && got > 0) {
      ++counters_.transfers;
      auto rec = parse_psvr2_gaze(std::span<const std::uint8_t>(buffer_.data(), static_cast<std::size_t>(got)));
      if (!rec) {
        ++counters_.malformed;
        problem(rec.error().message);
      } else {
        const TimeNs arrival = monotonic_now_ns();
        const std::int64_t device_ns = clock_.unwrap_ns(rec->timestamp_us);
        // Device time on the runtime clock, anchored at the first record; never backwards.
        if (!anchored_ || arrival - (device_ns + offset_ns_) > 50 * kNsPerMs || device_ns + offset_ns_ > arrival) {
          offset_ns_ = arrival - device_ns;
          anchored_ = true;
        }
        r.sample = psvr2_to_sample(*rec);
        r.sample.t_ns = std::max(device_ns + offset_ns_, last_t_ + 1);
        r.device_t_ns = device_ns;
        last_t_ = r.sample.t_ns;
        ++counters_.samples;
        r.status = ReadStatus::sample;
        return r;
      }
    }
    if (monotonic_now_ns() >= deadline) {
      r.status = ReadStatus::timeout;
      return r;
    }
  }
}

SourceInfo Psvr2Source::info() const {
  SourceInfo i;
  i.driver = "usb";
  i.name = "PlayStation VR2 gaze";
  i.path = path_;
  i.nominal_rate_hz = 0;  // not published; a recording estimates it from the timestamps
  i.vendor_id = kPsvr2Vendor;
  i.product_id = kPsvr2Product;
  return i;
}

}  // namespace foveal::usb
