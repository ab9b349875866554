// vm hmd-probe: the emulated headsets through the kernel's own interfaces, before any
// foveal driver reads them (so a failure of the foveald checks is not the emulation's):
//   hmd_psvr2_usb  libusb: interfaces 3 and 7 claimed, alternate setting 1 on 7, SLAM
//                  transfers of exactly one 512-byte record and status transfers of
//                  IMU records, each decoding (foveal's parsers) to the motion at its
//                  device time
//   hmd_vive_hid   hidraw (the ioctls hidapi uses): the range and configuration feature
//                  reports (the configuration inflated and parsed is the emulated one),
//                  IMU input reports decoding to the motion at their sample times
#include <dirent.h>
#include <fcntl.h>
#include <libusb.h>
#include <linux/hidraw.h>
#include <poll.h>
#include <sys/ioctl.h>
#include <unistd.h>

#include <cmath>
#include <fstream>

#include "foveal/drivers/psvr2/psvr2_pose_records.hpp"
#include "foveal/drivers/vive/vive_config.hpp"
#include "foveal/drivers/vive/vive_reports.hpp"
#include "psvr2_pattern.hpp"
#include "psvr2_pose_pattern.hpp"
#include "vive_pattern.hpp"
#include "vm_guest.hpp"

namespace foveal::vmtest {
namespace {

/// The device time (µs since boot; the guest's uptime is far below the wrap) as ns.
TimeNs us_to_ns(std::uint32_t us) { return static_cast<TimeNs>(us) * 1000; }

double angle_deg(const glm::quat& a, const glm::dquat& b) {
  const glm::dquat d = glm::conjugate(glm::dquat(a)) * b;
  return 2 * std::asin(std::min(1.0, glm::length(glm::dvec3(d.x, d.y, d.z)))) * 180 / M_PI;
}

/// The IN endpoint of `interface` (any alternate setting) and the setting it is in.
bool find_endpoint(libusb_device* dev, int interface, std::uint8_t& ep, int& alt) {
  libusb_config_descriptor* config = nullptr;
  if (libusb_get_active_config_descriptor(dev, &config) != 0) return false;
  bool found = false;
  for (int i = 0; i < config->bNumInterfaces && !found; ++i)
    for (int a = 0; a < config->interface[i].num_altsetting && !found; ++a) {
      const libusb_interface_descriptor& d = config->interface[i].altsetting[a];
      if (d.bInterfaceNumber != interface || d.bNumEndpoints == 0) continue;
      ep = d.endpoint[0].bEndpointAddress;
      alt = d.bAlternateSetting;
      found = true;
    }
  libusb_free_config_descriptor(config);
  return found;
}

int probe_psvr2() {
  libusb_context* ctx = nullptr;
  libusb_device_handle* h = nullptr;
  std::string problem;
  auto done = [&](bool pass, const std::string& details) {
    if (h) libusb_close(h);
    if (ctx) libusb_exit(ctx);
    return verdict("hmd_psvr2_usb", pass, details) ? 0 : 1;
  };
  // Enumeration after the bind takes about half a second here, and its device node
  // follows the sysfs entry: both waited for (60 s each, hang guards), not a time. A fresh
  // libusb context each try, as one made before the node sees no new device without udevd.
  wait_for([] { return usb_device_present(kPsvr2Vendor, kPsvr2Product); }, 60 * kNsPerSec, 20 * kNsPerMs);
  wait_for(
      [&] {
        if (libusb_init(&ctx) != 0) return ctx = nullptr, false;
        if ((h = libusb_open_device_with_vid_pid(ctx, kPsvr2Vendor, kPsvr2Product))) return true;
        libusb_exit(ctx);
        ctx = nullptr;
        return false;
      },
      60 * kNsPerSec, 20 * kNsPerMs);
  if (!h) return done(false, "no 054c:0cde to open");
  std::uint8_t slam_ep = 0, status_ep = 0;
  int slam_alt = -1, status_alt = -1;
  if (!find_endpoint(libusb_get_device(h), usb::psvr2::kSlamInterface, slam_ep, slam_alt) ||
      !find_endpoint(libusb_get_device(h), usb::psvr2::kStatusInterface, status_ep, status_alt))
    return done(false, "no endpoints on interfaces 3 and 7");
  int rc = libusb_claim_interface(h, usb::psvr2::kSlamInterface);
  if (rc == 0) rc = libusb_claim_interface(h, usb::psvr2::kStatusInterface);
  if (rc != 0) return done(false, std::string("claim: ") + libusb_strerror(rc));
  rc = libusb_set_interface_alt_setting(h, usb::psvr2::kStatusInterface, usb::psvr2::kStatusAltSetting);
  if (rc != 0) return done(false, std::string("alternate setting 1 on interface 7: ") + libusb_strerror(rc));
  std::vector<std::uint8_t> buf(1024);
  int slams = 0, statuses = 0, imu = 0, bad = 0, wrong_size = 0;
  double pos = 0, ang = 0, gyro = 0;
  for (int i = 0; i < 40; ++i) {
    int n = 0;
    if ((rc = libusb_bulk_transfer(h, slam_ep, buf.data(), static_cast<int>(buf.size()), &n, 2000)) != 0) {
      problem = std::string("SLAM read: ") + libusb_strerror(rc);
      break;
    }
    if (n != static_cast<int>(usb::psvr2::kSlamRecordBytes)) ++wrong_size;
    const auto r = usb::parse_psvr2_slam(std::span(buf.data(), static_cast<std::size_t>(n)));
    if (!r) {
      ++bad;
      continue;
    }
    ++slams;
    const Pose p = usb::psvr2_slam_to_pose(*r);
    const HeadMotion m = psvr2_motion(us_to_ns(r->vts_us));
    pos = std::max(pos, glm::length(glm::dvec3(p.position_m) - m.position_m));
    ang = std::max(ang, angle_deg(p.orientation, m.orientation));
  }
  for (int i = 0; i < 40 && problem.empty(); ++i) {
    int n = 0;
    if ((rc = libusb_interrupt_transfer(h, status_ep, buf.data(), static_cast<int>(buf.size()), &n, 2000)) != 0) {
      problem = std::string("status read: ") + libusb_strerror(rc);
      break;
    }
    const auto r = usb::parse_psvr2_status(std::span(buf.data(), static_cast<std::size_t>(n)));
    if (!r || r->ipd_mm != kPsvr2IpdDialMm) {
      ++bad;
      continue;
    }
    ++statuses;
    for (const auto& rec : r->imu) {
      ++imu;
      const ImuSample s = usb::psvr2_imu_to_sample(rec);
      gyro = std::max(gyro, glm::length(glm::dvec3(s.gyro_rad_s) - psvr2_motion(us_to_ns(rec.vts_us)).angular_velocity_head));
    }
  }
  char d[400];
  std::snprintf(d, sizeof d,
                "endpoints SLAM 0x%02x status 0x%02x (alt %d) slam=%d status=%d imu=%d bad=%d wrong_size=%d "
                "max_pos_m=%.2g max_deg=%.3f max_gyro=%.2g %s",
                slam_ep, status_ep, status_alt, slams, statuses, imu, bad, wrong_size, pos, ang, gyro, problem.c_str());
  return done(problem.empty() && slams == 40 && statuses == 40 && bad == 0 && wrong_size == 0 && pos < 1e-5 && ang < 0.01 &&
                  gyro < 2e-3,
              d);
}

/// The hidraw node of the emulated Vive (HID_ID in its uevent).
std::string vive_hidraw() {
  char want[40];
  std::snprintf(want, sizeof want, "HID_ID=0003:%08X:%08X", kViveVendor, kViveProduct);
  std::string found;
  if (DIR* d = ::opendir("/sys/class/hidraw")) {
    while (const dirent* e = ::readdir(d)) {
      if (e->d_name[0] == '.') continue;
      std::ifstream f(std::string("/sys/class/hidraw/") + e->d_name + "/device/uevent");
      for (std::string line; std::getline(f, line);)
        if (line == want) found = std::string("/dev/") + e->d_name;
    }
    ::closedir(d);
  }
  return found;
}

int probe_vive() {
  std::string node;
  wait_for([&] { return !(node = vive_hidraw()).empty(); }, 60 * kNsPerSec, 50 * kNsPerMs);
  if (node.empty()) return verdict("hmd_vive_hid", false, "no hidraw node for 28de:2300") ? 0 : 1;
  const int fd = ::open(node.c_str(), O_RDWR);
  if (fd < 0) return verdict("hmd_vive_hid", false, "cannot open " + node) ? 0 : 1;
  auto feature = [&](std::uint8_t id) {
    std::vector<std::uint8_t> r(vive::kConfigReportBytes, 0);
    r[0] = id;
    const int n = ::ioctl(fd, HIDIOCGFEATURE(r.size()), r.data());
    r.resize(n > 0 ? static_cast<std::size_t>(n) : 0);
    return r;
  };
  std::string problem;
  const auto range = vive::parse_range_report(feature(vive::kRangeReportId));
  if (!range) problem = "range report: " + range.error().message;
  feature(vive::kConfigStartReportId);
  vive::ConfigAssembler config;
  for (int i = 0; i < 1000 && problem.empty() && !config.complete(); ++i)
    if (Status s = config.add(feature(vive::kConfigReadReportId)); !s) problem = "config report: " + s.error().message;
  auto json = config.json();
  auto cfg = json ? vive::parse_config(*json) : Result<vive::Config>(json.error());
  if (problem.empty() && !cfg) problem = "config: " + cfg.error().message;
  if (problem.empty() && (cfg->eye_width != vive_config().eye_width || cfg->variant != vive::Variant::vive_pro))
    problem = "the configuration read is not the emulated one";
  int reports = 0, samples = 0, bad = 0;
  double gyro = 0, accel = 0;
  std::optional<std::uint8_t> last;
  for (int i = 0; i < 200 && problem.empty(); ++i) {
    pollfd p{fd, POLLIN, 0};
    if (::poll(&p, 1, 2000) <= 0) {
      problem = "no IMU report within 2 s";
      break;
    }
    std::uint8_t buf[64];
    const ssize_t n = ::read(fd, buf, sizeof buf);
    const auto r = vive::parse_imu_report(std::span(buf, n > 0 ? static_cast<std::size_t>(n) : 0));
    if (!r) {
      ++bad;
      continue;
    }
    ++reports;
    for (const auto& s : vive::new_imu_samples(*r, last)) {
      last = s.seq;
      ++samples;
      // The sample's time (48 MHz ticks of CLOCK_MONOTONIC, unwrapped against now).
      const std::uint64_t now = static_cast<std::uint64_t>(monotonic_now_ns()) * 48 / 1000;
      std::uint64_t ticks = (now & ~0xffffffffULL) | s.time;
      if (ticks > now) ticks -= 1ULL << 32;
      const HeadMotion m = vive_motion(static_cast<TimeNs>(ticks * 1000 / 48));
      const ImuSample v = vive::imu_to_sample(s, *cfg, *range);
      gyro = std::max(gyro, glm::length(glm::dvec3(v.gyro_rad_s) - m.angular_velocity_head));
      accel = std::max(accel, glm::length(glm::dvec3(v.accel_m_s2) - m.specific_force_head));
    }
  }
  ::close(fd);
  char d[400];
  std::snprintf(d, sizeof d, "%s config=%zu bytes compressed, %zu of JSON reports=%d samples=%d bad=%d max_gyro=%.2g max_accel=%.2g %s",
                node.c_str(), config.compressed_bytes(), json ? json->size() : 0, reports, samples, bad, gyro, accel,
                problem.c_str());
  return verdict("hmd_vive_hid", problem.empty() && reports == 200 && bad == 0 && gyro < 2e-3 && accel < 1e-2, d) ? 0 : 1;
}

}  // namespace

int run_hmd_probe(const std::string& kind) { return kind == "vive" ? probe_vive() : probe_psvr2(); }

}  // namespace foveal::vmtest
