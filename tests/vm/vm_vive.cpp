// vm vive-gadget: an emulated Vive Pro's sensor device (28de:2300) as a USB HID
// function through FunctionFS, so the host sees it the way it sees the headset: usbhid,
// a hidraw node, feature reports as GET_REPORT control requests. (The kernel's own HID
// gadget, usb_f_hid, answers GET_REPORT with zeros in Linux 6.1: no configuration could
// be read through it.) The device answers the report descriptor request, the feature
// reports of vive_pattern.hpp (the configuration zlib-compressed, in 62-byte pieces)
// and streams IMU reports while configured.
#include <unistd.h>

#include <atomic>
#include <csignal>
#include <cstdio>
#include <thread>

#include <nlohmann/json.hpp>

#include "vive_pattern.hpp"
#include "vm_ffs.hpp"
#include "vm_guest.hpp"

namespace foveal::vmtest {
namespace {

std::atomic<bool> g_stop{false};
void on_term(int) { g_stop.store(true); }

constexpr std::uint8_t kHidRequestGetReport = 0x01, kHidReportFeature = 3, kHidDescriptorHid = 0x21,
                       kHidDescriptorReport = 0x22;
constexpr std::uint8_t kFirmwareReportId = 0x05;  // answered, not read by foveal

/// The HID class descriptor for a report descriptor of `length` bytes.
std::vector<std::uint8_t> hid_descriptor(std::size_t length) {
  return {9, kHidDescriptorHid, 0x11, 0x01, 0, 1, kHidDescriptorReport, static_cast<std::uint8_t>(length),
          static_cast<std::uint8_t>(length >> 8)};
}

}  // namespace

std::string vive_config_json(const ViveConfig& c) {
  using nlohmann::json;
  auto vec = [](const glm::dvec3& v) { return json::array({v.x, v.y, v.z}); };
  json eyes = json::array();
  for (int e = 0; e < 2; ++e) {
    json eye;
    eye["eye_to_head"] = {{1, 0, 0, c.eye_x_m[e]}, {0, 1, 0, 0}, {0, 0, 1, 0}};
    eye["intrinsics"] = {{c.fx, 0, c.cx[e]}, {0, c.fy, c.cy}, {0, 0, -1}};
    const char* names[3] = {"distortion_red", "distortion", "distortion_blue"};
    for (int ch = 0; ch < 3; ++ch)
      eye[names[ch]] = {{"center_x", c.center_x[e]},
                        {"center_y", c.center_y},
                        {"coeffs", {c.coeffs[ch][0], c.coeffs[ch][1], c.coeffs[ch][2], 0.0}},
                        {"type", "DISTORT_DPOLY3"}};
    eye["grow_for_undistort"] = c.grow_for_undistort;
    eye["undistort_r2_cutoff"] = c.undistort_r2_cutoff;
    eyes.push_back(eye);
  }
  json j;
  j["model_number"] = "VIVE_Pro MV";
  j["device_serial_number"] = "VMVIVE0001";
  j["mb_serial_number"] = "VMMB0001";
  j["lens_separation"] = c.lens_separation_m;
  j["device"] = {{"eye_target_width_in_pixels", c.eye_width},
                 {"eye_target_height_in_pixels", c.eye_height},
                 {"physical_aspect_x_over_y", c.aspect_x_over_y},
                 {"persistence", 0.0116}};
  j["imu"] = {{"acc_bias", vec(c.acc_bias)},   {"acc_scale", vec(c.acc_scale)},
              {"gyro_bias", vec(c.gyro_bias)}, {"gyro_scale", vec(c.gyro_scale)},
              {"plus_x", {-1.0, 0.0, 0.0}},    {"plus_z", {0.0, 0.0, -1.0}},
              {"position", {0.0, 0.02, -0.05}}};
  j["tracking_to_eye_transform"] = eyes;
  return j.dump(2);
}

std::vector<std::uint8_t> vive_report_descriptor() {
  std::vector<std::uint8_t> d = {0x06, 0x00, 0xff,  // Usage Page (vendor 0xff00)
                                 0x09, 0x01,        // Usage (1)
                                 0xa1, 0x01,        // Collection (Application)
                                 0x15, 0x00,        //   Logical Minimum (0)
                                 0x26, 0xff, 0x00,  //   Logical Maximum (255)
                                 0x75, 0x08,        //   Report Size (8)
                                 0x85, vive::kImuReportId, 0x95, static_cast<std::uint8_t>(vive::kImuReportBytes - 1),
                                 0x09, vive::kImuReportId, 0x81, 0x02};  // the IMU input report
  for (std::uint8_t id : {vive::kRangeReportId, kFirmwareReportId, vive::kConfigStartReportId, vive::kConfigReadReportId}) {
    const std::uint8_t item[] = {0x85, id, 0x95, static_cast<std::uint8_t>(vive::kConfigReportBytes - 1), 0x09, id, 0xb1, 0x02};
    d.insert(d.end(), std::begin(item), std::end(item));  // a feature report
  }
  d.push_back(0xc0);  // End Collection
  return d;
}

int run_vive_gadget(const std::string& dir) {
  const auto report_desc = vive_report_descriptor();
  const std::string config_text = vive_config_json(vive_config());
  const auto config = test::vive_config_reports(config_text);
  ffs::Interface hid;
  hid.cls = 3;  // HID, no boot protocol
  hid.class_descriptor = hid_descriptor(report_desc.size());
  hid.endpoints.push_back({true, USB_ENDPOINT_XFER_INT, 64, 64, 1, 1});
  const int ep0 = ffs::open_ep0(dir, {hid}, "Lighthouse FPGA RX");
  if (ep0 < 0) return 1;
  std::printf("vive-gadget: config %zu bytes of JSON in %zu feature reports\n", config_text.size(), config.size());
  std::fflush(stdout);
  std::signal(SIGTERM, on_term);
  std::atomic<bool> configured{false};
  std::atomic<std::uint64_t> imu_written{0};
  std::thread writer([&] {
    // A report every fourth sample (what dummy_hcd delivers with the kernel's 250 Hz
    // tick), its newest sample the one of now; the filter sees steps of 1, 1 and 2 ms,
    // at most 20 ms after a stall.
    ffs::stream(g_stop, dir + "/ep1", configured, 4 * kViveSamplePeriodNs, 20 * kNsPerMs, imu_written, [](TimeNs t, int fd) {
      return ffs::write_all(fd, vive_imu_report(static_cast<std::uint64_t>(t / kViveSamplePeriodNs)));
    });
  });
  std::size_t config_at = 0;
  std::uint64_t config_reads = 0, config_starts = 0;
  ffs::Handlers h;
  h.enabled = [&](bool on) { configured = on; };
  h.in = [&](const usb_ctrlrequest& c) -> std::optional<std::vector<std::uint8_t>> {
    const auto type = static_cast<std::uint8_t>(c.wValue >> 8), id = static_cast<std::uint8_t>(c.wValue & 0xff);
    if (c.bRequest == USB_REQ_GET_DESCRIPTOR && type == kHidDescriptorReport) return report_desc;
    if (c.bRequest == USB_REQ_GET_DESCRIPTOR && type == kHidDescriptorHid) return hid_descriptor(report_desc.size());
    if (c.bRequest != kHidRequestGetReport) return std::vector<std::uint8_t>(c.wLength, 0);  // GET_IDLE and such
    if (type != kHidReportFeature) return vive_imu_report(static_cast<std::uint64_t>(monotonic_now_ns() / kViveSamplePeriodNs));
    if (id == vive::kConfigReadReportId) {
      // The next piece; past the end, the empty one that ends the read again.
      ++config_reads;
      return config[std::min(config_at++, config.size() - 1)];
    }
    std::vector<std::uint8_t> r(vive::kConfigReportBytes, 0);
    r[0] = id;
    if (id == vive::kRangeReportId) {
      r[1] = kViveGyroRangeCode;
      r[2] = kViveAccelRangeCode;
    } else if (id == kFirmwareReportId) {
      r[1] = 0x2a;  // firmware version 1578 (little-endian uint32)
      r[2] = 0x06;
    } else if (id == vive::kConfigStartReportId) {
      config_at = 0;
      ++config_starts;
    } else {
      return std::nullopt;  // no such report: stall
    }
    return r;
  };
  h.out = [](const usb_ctrlrequest& c, const std::vector<std::uint8_t>& data) {
    std::printf("vive-gadget: host request type=%02x req=%02x value=%04x (%zu bytes)\n", c.bRequestType, c.bRequest,
                c.wValue, data.size());
    std::fflush(stdout);
  };
  ffs::serve_ep0(ep0, g_stop, h);
  std::printf("vive-gadget: %llu IMU reports written, config read %llu times (%llu pieces)\n",
              static_cast<unsigned long long>(imu_written.load()), static_cast<unsigned long long>(config_starts),
              static_cast<unsigned long long>(config_reads));
  std::fflush(stdout);
  _exit(0);  // the writer may be blocked in a write nobody reads any more
}

}  // namespace foveal::vmtest
