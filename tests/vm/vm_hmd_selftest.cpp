// foveal_vm_guest hmd-selftest, on the host (ctest vm_hmd_patterns, milliseconds): the
// emulated headsets' bytes (psvr2_pose_pattern.hpp, vive_pattern.hpp) decode through
// foveal's own parsers to the motion script they were made from, and the checks of
// vm_hmd_check.hpp pass on poses of the motion and fail on poses of another one. So a
// failing VM test (minutes) is about the runtime, not about the emulation's bytes.
#include <cmath>
#include <cstdio>

#include "foveal/drivers/psvr2/psvr2_pose_records.hpp"
#include "foveal/drivers/vive/vive_config.hpp"
#include "foveal/drivers/vive/vive_display_model.hpp"
#include "foveal/drivers/vive/vive_reports.hpp"
#include "psvr2_pose_pattern.hpp"
#include "vive_pattern.hpp"
#include "vm_guest.hpp"
#include "vm_hmd_check.hpp"

namespace foveal::vmtest {
namespace {

int g_failures = 0;

void expect(bool ok, const std::string& what) {
  if (!ok) ++g_failures;
  std::printf("%s %s\n", ok ? "ok  " : "FAIL", what.c_str());
}

double angle_deg(const glm::quat& a, const glm::dquat& b) {
  const glm::dquat d = glm::conjugate(glm::dquat(a)) * b;
  return 2 * std::asin(std::min(1.0, glm::length(glm::dvec3(d.x, d.y, d.z)))) * 180 / M_PI;
}

void psvr2_bytes() {
  double pos = 0, ang = 0, gyro = 0, accel = 0;
  bool parsed = true;
  for (TimeNs t = 5 * kNsPerSec; t < 40 * kNsPerSec; t += 317 * kNsPerMs) {
    const auto slam = usb::parse_psvr2_slam(psvr2_slam_record(t));
    const auto status = usb::parse_psvr2_status(psvr2_status_transfer(t, kPsvr2ImuPerTransfer));
    if (!slam || !status || status->imu.size() != kPsvr2ImuPerTransfer || status->ipd_mm != kPsvr2IpdDialMm ||
        slam->vts_us != psvr2_device_us(t)) {
      parsed = false;
      continue;
    }
    const HeadMotion m = psvr2_motion(t);
    const Pose p = usb::psvr2_slam_to_pose(*slam);
    pos = std::max(pos, glm::length(glm::dvec3(p.position_m) - m.position_m));
    ang = std::max(ang, angle_deg(p.orientation, m.orientation));
    for (int i = 0; i < kPsvr2ImuPerTransfer; ++i) {
      const HeadMotion mi = psvr2_motion(t + i * kPsvr2ImuPeriodNs);
      const ImuSample s = usb::psvr2_imu_to_sample(status->imu[static_cast<std::size_t>(i)]);
      gyro = std::max(gyro, glm::length(glm::dvec3(s.gyro_rad_s) - mi.angular_velocity_head));
      accel = std::max(accel, glm::length(glm::dvec3(s.accel_m_s2) - mi.specific_force_head));
    }
  }
  char b[200];
  std::snprintf(b, sizeof b, "psvr2: SLAM and IMU bytes decode to the motion (pos %.2g m, %.2g deg, gyro %.2g rad/s, accel %.2g m/s2)",
                pos, ang, gyro, accel);
  expect(parsed && pos < 1e-5 && ang < 0.01 && gyro < 2e-3 && accel < 5e-3, b);
}

void vive_bytes() {
  const auto cfg = vive::parse_config(vive_config_json(vive_config()));
  expect(static_cast<bool>(cfg), "vive: the emulated configuration parses" + (cfg ? std::string() : ": " + cfg.error().message));
  if (!cfg) return;
  const ViveConfig& c = vive_config();
  expect(cfg->variant == vive::Variant::vive_pro && cfg->eye_width == c.eye_width && cfg->eye_height == c.eye_height &&
             std::abs(cfg->ipd_m - c.lens_separation_m) < 1e-9 && std::abs(cfg->eyes[1].fx - c.fx) < 1e-9 &&
             std::abs(cfg->eyes[0].rgb[2].coeffs[1] - c.coeffs[2][1]) < 1e-9 && std::abs(cfg->gyro_scale.y - c.gyro_scale.y) < 1e-6,
         "vive: the configuration's values as emulated (Vive Pro axes, size, IPD, intrinsics, distortion, calibration)");
  std::vector<std::uint8_t> range(vive::kRangeReportBytes, 0);
  range[0] = vive::kRangeReportId, range[1] = kViveGyroRangeCode, range[2] = kViveAccelRangeCode;
  const auto r = vive::parse_range_report(range);
  expect(r && std::abs(r->gyro_rad_s - vive_gyro_range()) < 1e-5 && std::abs(r->accel_m_s2 - vive_accel_range()) < 1e-3,
         "vive: the range report decodes to the emulated ranges");
  if (!r) return;
  double gyro = 0, accel = 0;
  std::size_t samples = 0;
  std::optional<std::uint8_t> last;
  bool parsed = true, ticks = true;
  for (std::uint64_t s = 20000; s < 21000; s += 3) {
    const auto rep = vive::parse_imu_report(vive_imu_report(s));
    if (!rep) {
      parsed = false;
      continue;
    }
    for (const vive::ImuRawSample& raw : vive::new_imu_samples(*rep, last)) {
      const std::uint64_t k = s - 2 + (static_cast<std::uint8_t>(raw.seq - static_cast<std::uint8_t>(s - 2)));
      const HeadMotion m = vive_motion(static_cast<TimeNs>(k) * kViveSamplePeriodNs);
      const ImuSample v = vive::imu_to_sample(raw, *cfg, *r);
      gyro = std::max(gyro, glm::length(glm::dvec3(v.gyro_rad_s) - m.angular_velocity_head));
      accel = std::max(accel, glm::length(glm::dvec3(v.accel_m_s2) - m.specific_force_head));
      ticks = ticks && raw.time == vive_ticks(static_cast<TimeNs>(k) * kViveSamplePeriodNs);
      last = raw.seq;
      ++samples;
    }
  }
  // The display model foveal makes of the configuration passes the VM test's check of
  // the written file, and a model from another configuration does not.
  vive::DistortionFit fit;
  const auto model = vive::vive_display_model(*cfg, &fit);
  const ModelCheck good = model ? check_vive_model(nlohmann::json::parse(model->to_json_text()))
                                : ModelCheck{false, model.error().message};
  expect(good.pass, "vive: the display model converted from the configuration matches it: " + good.details +
                        "(the conversion's own fit: " + vive::vive_model_source(*cfg, fit) + ")");
  auto other = *cfg;
  other.eyes[0].rgb[1].coeffs[0] += 0.05;
  other.ipd_m += 0.001;
  const auto wrong = vive::vive_display_model(other);
  const ModelCheck bad = wrong ? check_vive_model(nlohmann::json::parse(wrong->to_json_text())) : ModelCheck{};
  expect(wrong && !bad.pass && bad.details.find("left eye shows") != std::string::npos,
         "vive: a model of another lens (k1 + 0.05 on the left) and IPD does not: " + bad.details);
  char b[200];
  std::snprintf(b, sizeof b, "vive: %zu IMU samples decode to the motion through the calibration (gyro %.2g rad/s, accel %.2g m/s2)",
                samples, gyro, accel);
  expect(parsed && ticks && samples == 1002 && gyro < 1e-3 && accel < 5e-3, b);
}

/// Frames of the motion at 10 Hz from t0 (pose times `lag` after the fovea times).
std::vector<HeadRow> rows_of(HeadMotion (*motion)(TimeNs), TimeNs t0, double heading_offset, double rate_factor) {
  std::vector<HeadRow> rows;
  for (int i = 0; i < 60; ++i) {
    HeadRow r;
    r.frame = static_cast<std::uint64_t>(i);
    r.t_ns = t0 + i * 100 * kNsPerMs;
    r.pose_t_ns = r.t_ns + 15 * kNsPerMs;
    HeadMotion m = motion(r.t_ns + 15 * kNsPerMs);
    const double extra = heading_offset + (rate_factor - 1) * kViveYawRate * seconds(r.pose_t_ns);
    m.orientation = glm::angleAxis(extra, glm::dvec3(0, 1, 0)) * m.orientation;
    r.pose.position_m = glm::vec3(m.position_m);
    r.pose.orientation = glm::quat(glm::dquat(m.orientation));
    rows.push_back(r);
  }
  return rows;
}

void checks_can_fail() {
  const TimeNs t0 = 30 * kNsPerSec;
  const std::vector<Window> all{{0, 100 * kNsPerSec}};
  const auto good = check_psvr2_rows(rows_of(psvr2_motion, t0, 0, 1), all);
  expect(good.bad == 0 && good.checked == 60, "psvr2 check passes on the motion: " + good.summary());
  const auto turned = check_psvr2_rows(rows_of(psvr2_motion, t0, 0.3, 1), all);
  expect(turned.bad > 0, "psvr2 check fails on a pose turned by 0.3 rad: " + turned.summary());
  const auto vgood = check_vive_rows(rows_of(vive_motion, t0, 1.234, 1), all);
  expect(vgood.bad == 0 && vgood.checked == 60, "vive check passes on the motion, any heading: " + vgood.summary());
  const auto slow = check_vive_rows(rows_of(vive_motion, t0, 0, 0.96), all);
  expect(slow.bad > 0, "vive check fails on a yaw rate 4% off (an uncalibrated gyro): " + slow.summary());
}

}  // namespace

int run_hmd_selftest() {
  psvr2_bytes();
  vive_bytes();
  checks_can_fail();
  std::printf("hmd-selftest: %s\n", g_failures ? "FAILED" : "passed");
  return g_failures ? 1 : 0;
}

}  // namespace foveal::vmtest
