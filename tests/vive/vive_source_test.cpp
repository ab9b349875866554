// The Vive driver against a scripted HID backend: it finds the sensor device by its IDs,
// reads the IMU ranges and the configuration through feature reports, turns IMU
// reports into calibrated samples once each, counts what it skips, and rides out an
// unplug; the pose thread fuses them into an orientation.
#include <gtest/gtest.h>

#include <array>
#include <fstream>
#include <sstream>
#include <thread>

#include "../hid/fake_hid_backend.hpp"
#include "foveal/drivers/vive/vive_source.hpp"
#include "foveal/runtime/head_tracker.hpp"
#include "test_support.hpp"
#include "vive_report_builders.hpp"

namespace foveal::vive {
namespace {

std::string example_config() {
  std::ifstream in(FOVEAL_SOURCE_DIR "/data/headset/vive_pro_config_example.json");
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

struct Rig {
  std::shared_ptr<test::FakeHidBackend> backend = std::make_shared<test::FakeHidBackend>();
  std::shared_ptr<test::FakeHidState> vive;
  std::vector<std::string> logged;
  std::uint8_t seq = 2;  // the first report's slots hold 0, 1, 2
  std::uint32_t ticks = 96000;

  Rig() {
    backend->add({"/dev/hidraw0", 0x046d, 0xc077, "Logi", "Mouse", "", {}});
    vive = backend->add({"/dev/hidraw5", kValveVendor, kViveProSensorProduct, "Valve", "Lighthouse FPGA RX", "LHR-1", {}});
    std::vector<std::uint8_t> range(kRangeReportBytes, 0);
    range[0] = kRangeReportId, range[1] = 1, range[2] = 1;  // ±500 °/s, ±4 g
    vive->features[kRangeReportId] = range;
    vive->features[kConfigStartReportId] = std::vector<std::uint8_t>(kConfigReportBytes, 0);
    load_config();
  }
  void load_config() {
    auto reports = test::vive_config_reports(example_config());
    vive->feature_sequences[kConfigReadReportId] = {reports.begin(), reports.end()};
  }
  ViveSource source() {
    ViveOptions o;
    o.log = [this](const std::string& m) { logged.push_back(m); };
    return ViveSource(o, backend);
  }
  /// One more IMU sample (1 ms later; `gyro` counts about the sensor's x, y, z). The report
  /// carries it and the two before it (same values) in rotating slots, as the headset
  /// sends them: the first report brings three new samples, every later one one.
  void imu(std::array<std::int16_t, 3> gyro, std::int16_t accel_y = 8192) {
    ticks += 48000;
    const std::uint8_t newest = seq++;
    test::ViveImuBuilder r;
    for (std::uint8_t back = 0; back < 3; ++back) {
      const std::uint8_t q = static_cast<std::uint8_t>(newest - back);
      const std::int16_t a[3] = {0, accel_y, 0}, g[3] = {gyro[0], gyro[1], gyro[2]};
      r.sample(q % 3, a, g, ticks - back * 48000u, q);
    }
    vive->push_input(r.b);
  }
};

TEST(ViveSource, ReadsRangesConfigAndCalibratedSamplesOnce) {
  Rig rig;
  auto src = rig.source();
  ASSERT_TRUE(src.open());
  ASSERT_TRUE(src.start());
  EXPECT_EQ(src.info().driver, "vive");
  EXPECT_EQ(src.info().path, "/dev/hidraw5");  // not the mouse
  EXPECT_TRUE(src.info().imu);
  EXPECT_FALSE(src.info().orientation);
  ASSERT_TRUE(src.config());
  EXPECT_EQ(src.config()->model_number, "VIVE_Pro MV");
  for (int i = 0; i < 3; ++i) rig.imu({0, 0, static_cast<std::int16_t>(1000 * (i + 1))});
  // Three reports: 3 + 1 + 1 samples (the repeats skipped), in order and calibrated.
  TimeNs last = 0;
  for (int i = 0; i < 5; ++i) {
    const PoseReading r = src.next(std::chrono::milliseconds(20));
    ASSERT_EQ(r.status, ReadStatus::sample) << i;
    ASSERT_TRUE(r.has_imu);
    const int counts = 1000 * std::max(1, i - 1);
    const double want = 500.0 * 3.14159265358979 / 180.0 / 32768.0 * counts - 0.001;  // minus gyro_bias.z
    EXPECT_NEAR(r.imu.gyro_rad_s.z, -want, 1e-5) << i;  // Vive Pro: z flips
    EXPECT_NEAR(r.imu.accel_m_s2.y, 4 * 9.80665 / 4 * 0.998 + 0.1, 1e-3);
    EXPECT_GT(r.imu.t_ns, last);
    last = r.imu.t_ns;
  }
  EXPECT_EQ(src.next(std::chrono::milliseconds(5)).status, ReadStatus::timeout);
  EXPECT_EQ(src.counters().samples, 5u);
}

TEST(ViveSource, CountsMalformedAndOtherReportsAndSurvivesAnUnplug) {
  Rig rig;
  auto src = rig.source();
  ASSERT_TRUE(src.open());
  ASSERT_TRUE(src.start());
  rig.vive->inputs.push_back(std::vector<std::uint8_t>(30, 0x20));  // truncated IMU report
  rig.vive->inputs.push_back({0x21, 1, 2, 3});                     // a lighthouse pulse report
  rig.imu({0, 0, 5});
  const PoseReading r = src.next(std::chrono::milliseconds(20));
  ASSERT_EQ(r.status, ReadStatus::sample);
  EXPECT_EQ(src.counters().malformed, 1u);
  EXPECT_EQ(src.counters().other_reports, 1u);
  EXPECT_FALSE(rig.logged.empty());
  while (src.next(std::chrono::milliseconds(2)).status == ReadStatus::sample) {
  }

  rig.vive->present = false;
  EXPECT_EQ(src.next(std::chrono::milliseconds(5)).status, ReadStatus::disconnected);
  EXPECT_FALSE(src.open());
  rig.vive->present = true;
  rig.load_config();
  ASSERT_TRUE(src.open());  // the configuration is read again
  ASSERT_TRUE(src.start());
  ASSERT_TRUE(src.config());
  rig.imu({0, 0, 6});
  EXPECT_EQ(src.next(std::chrono::milliseconds(20)).status, ReadStatus::sample);
  EXPECT_EQ(src.counters().opens, 2u);
  EXPECT_EQ(src.counters().disconnects, 1u);
}

TEST(ViveSource, WithoutItsConfigurationTheImuStillStreamsUncalibrated) {
  Rig rig;
  rig.vive->feature_sequences.clear();  // 0x11 stalls
  auto src = rig.source();
  ASSERT_TRUE(src.open());
  EXPECT_FALSE(src.config());
  EXPECT_EQ(src.counters().config_errors, 1u);
  ASSERT_TRUE(src.start());
  rig.imu({0, 0, 100});
  EXPECT_EQ(src.next(std::chrono::milliseconds(20)).status, ReadStatus::sample);
}

TEST(ViveSource, ThePoseThreadFusesItsImuIntoATurningHead) {
  Rig rig;
  auto src = rig.source();
  // 0.5 rad/s about the head's up axis (sensor y on the Vive Pro, not flipped), level.
  const auto counts = static_cast<std::int16_t>(0.5 / (500.0 * 3.14159265358979 / 180.0 / 32768.0));
  HeadTracker t(src);
  t.start();
  // 300 reports 1 ms apart (302 samples: the first report brings three); their reading
  // is waited for, not expected by the time the last one is sent.
  for (int i = 0; i < 300; ++i) {
    rig.imu({0, counts, 0});
    std::this_thread::sleep_for(std::chrono::milliseconds(1));
  }
  EXPECT_TRUE(test::eventually([&] { return t.stats().imu_samples >= 302; })) << t.stats().imu_samples;
  t.stop();
  const auto last = t.track().newest();
  ASSERT_TRUE(last);
  // The fused yaw over the samples read, against 0.5 rad/s times the device time that passed.
  const HeadTrackerStats st = t.stats();
  EXPECT_GE(st.poses, 200u);
  const double turned = angle_between(t.track().anchor()->orientation, last->pose.orientation);
  const double expected = 0.5 * 1e-3 * static_cast<double>(st.imu_samples - 1);
  EXPECT_NEAR(turned, expected, 0.1 * expected + 0.01);
}

}  // namespace
}  // namespace foveal::vive
