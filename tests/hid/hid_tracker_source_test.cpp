#include <gtest/gtest.h>

#include "fake_hid_backend.hpp"
#include "foveal/drivers/hid/hid_tracker_source.hpp"
#include "hid_test_data.hpp"
#include "hutrr74_reports.hpp"

namespace foveal::hid {
namespace {

namespace h = test::hutrr74;
using namespace std::chrono_literals;

struct Rig {
  std::shared_ptr<test::FakeHidBackend> backend = std::make_shared<test::FakeHidBackend>();
  std::shared_ptr<test::FakeHidState> tracker;
  std::vector<std::string> logged;

  Rig() {
    HidDeviceEntry mouse{"/dev/hidraw0", 0x046d, 0xc077, "Logi", "Mouse", "", {0x05, 0x01, 0x09, 0x02, 0xa1, 0x01, 0xc0}};
    backend->add(mouse);
    tracker = backend->add(tracker_entry("/dev/hidraw1"));
    tracker->features[0x11] = h::capabilities_report(1, 400000, 650000, 900000, 600000, 340000);
    tracker->features[0x12] = h::configuration_report(527000, 296000);
    tracker->features[0x13] = h::status_report(1, 120);
  }
  static HidDeviceEntry tracker_entry(std::string path) {
    return {std::move(path), 0x1209, 0x0001, "Acme", "Gaze", "SN1", test::eye_tracker_descriptor_bytes()};
  }
  HidTrackerSource source(std::string device = "") {
    HidTrackerOptions o;
    o.device = std::move(device);
    o.log = [this](const std::string& m) { logged.push_back(m); };
    return HidTrackerSource(o, backend);
  }
};

h::Tracking sample_values(std::uint64_t k) {
  h::Tracking t;
  t.timestamp_us = 1000 + k * 8333;
  t.gaze_x_um = 263500;
  t.gaze_y_um = 148000;
  t.left_um = {231500, 148000, 650000};
  t.right_um = {295500, 148000, 650000};
  return t;
}

TEST(HidTrackerSource, FindsTrackerByUsagePageReadsFeaturesAndEnablesGaze) {
  Rig rig;
  auto src = rig.source();
  ASSERT_TRUE(src.open());
  const SourceInfo info = src.info();
  EXPECT_EQ(info.driver, "hid");
  EXPECT_EQ(info.path, "/dev/hidraw1");  // not the mouse
  EXPECT_EQ(info.vendor_id, 0x1209);
  EXPECT_EQ(info.name, "Acme Gaze");
  EXPECT_DOUBLE_EQ(info.nominal_rate_hz, 120.0);
  EXPECT_DOUBLE_EQ(src.screen().width_mm, 527.0);
  EXPECT_DOUBLE_EQ(src.screen().viewing_distance_mm, 650.0);
  EXPECT_EQ(src.status().configuration_status, 1);
  ASSERT_TRUE(src.start());
  ASSERT_EQ(rig.tracker->sent.size(), 1u);
  EXPECT_EQ(rig.tracker->sent[0], (std::vector<std::uint8_t>{0x14, 0x03}));
  src.stop();
  EXPECT_EQ(rig.tracker->sent.back(), (std::vector<std::uint8_t>{0x14, 0x00}));
}

TEST(HidTrackerSource, DeliversSamplesAndCountsMalformedReports) {
  Rig rig;
  auto src = rig.source("/dev/hidraw1");
  ASSERT_TRUE(src.open());
  ASSERT_TRUE(src.start());
  rig.tracker->inputs.push_back(h::tracking_report(sample_values(0)));
  auto truncated = h::tracking_report(sample_values(1));
  truncated.resize(30);
  rig.tracker->inputs.push_back(truncated);
  rig.tracker->inputs.push_back({0x77, 1, 2, 3});         // unknown report ID
  rig.tracker->inputs.push_back(h::status_report(1, 90));  // status input: new rate
  rig.tracker->inputs.push_back(h::tracking_report(sample_values(2)));

  auto a = src.next(10ms);
  ASSERT_EQ(a.status, ReadStatus::sample);
  auto b = src.next(10ms);
  ASSERT_EQ(b.status, ReadStatus::sample);
  EXPECT_GT(b.sample.t_ns, a.sample.t_ns);
  EXPECT_LE(b.sample.t_ns - a.sample.t_ns, 2 * 8'333'000);  // never more than the device spacing
  EXPECT_EQ(a.sample.eyes[0].valid, kValidDirection | kValidOrigin);
  EXPECT_GT(a.sample.eyes[0].direction.x, 0);
  EXPECT_NEAR(a.sample.eyes[0].origin_mm.x, -32.0f, 1e-4f);
  EXPECT_DOUBLE_EQ(src.last_tracking().gaze_x_mm, 263.5);
  EXPECT_EQ(src.next(1ms).status, ReadStatus::timeout);

  const HidTrackerCounters& c = src.counters();
  EXPECT_EQ(c.reports, 5u);
  EXPECT_EQ(c.samples, 2u);
  EXPECT_EQ(c.malformed, 1u);
  EXPECT_EQ(c.truncated, 1u);
  EXPECT_EQ(c.unknown_reports, 1u);
  EXPECT_EQ(c.status_reports, 1u);
  EXPECT_DOUBLE_EQ(src.info().nominal_rate_hz, 90.0);
  ASSERT_EQ(rig.logged.size(), 2u);
  EXPECT_NE(rig.logged[0].find("truncated"), std::string::npos) << rig.logged[0];
  EXPECT_NE(rig.logged[1].find("unknown ID 119"), std::string::npos) << rig.logged[1];
}

TEST(HidTrackerSource, UnreadableFeatureReportsAreCountedNotFatal) {
  Rig rig;
  rig.tracker->features.erase(0x11);
  rig.tracker->features[0x12] = std::vector<std::uint8_t>(19, 0);  // zeros: no report ID
  auto src = rig.source();
  ASSERT_TRUE(src.open());
  EXPECT_EQ(src.counters().feature_errors, 2u);
  EXPECT_DOUBLE_EQ(src.screen().width_mm, 0.0);
  EXPECT_DOUBLE_EQ(src.screen().viewing_distance_mm, 600.0);  // default
  EXPECT_TRUE(src.start());
}

TEST(HidTrackerSource, NoTrackerOrWrongPathIsADeviceError) {
  test::FakeHidBackend empty;
  HidTrackerSource none(HidTrackerOptions{}, std::make_shared<test::FakeHidBackend>());
  auto s = none.open();
  ASSERT_FALSE(s);
  EXPECT_EQ(s.error().kind, ErrorKind::device);
  EXPECT_NE(s.error().message.find("no HID eye tracker"), std::string::npos);
  Rig rig;
  auto mouse = rig.source("/dev/hidraw0");
  auto m = mouse.open();
  ASSERT_FALSE(m);
  EXPECT_NE(m.error().message.find("/dev/hidraw0"), std::string::npos);
}

TEST(HidTrackerSource, DisconnectReportedAndReopenFindsTheDeviceOnANewNode) {
  Rig rig;
  auto src = rig.source("/dev/hidraw1");
  ASSERT_TRUE(src.open());
  ASSERT_TRUE(src.start());
  rig.tracker->present = false;
  auto r = src.next(10ms);
  EXPECT_EQ(r.status, ReadStatus::disconnected);
  EXPECT_EQ(rig.tracker->open_handles, 0);  // released at once
  EXPECT_EQ(src.counters().disconnects, 1u);
  src.close();
  EXPECT_FALSE(src.open());  // still unplugged
  // Back, on another node, with the same identity.
  auto back = rig.backend->add(Rig::tracker_entry("/dev/hidraw5"));
  back->features = rig.tracker->features;
  ASSERT_TRUE(src.open());
  ASSERT_TRUE(src.start());
  EXPECT_EQ(src.info().path, "/dev/hidraw5");
  back->inputs.push_back(h::tracking_report(sample_values(0)));
  EXPECT_EQ(src.next(10ms).status, ReadStatus::sample);
  EXPECT_EQ(back->open_handles, 1);
  src.close();
  EXPECT_EQ(back->open_handles, 0);
}

TEST(HidTrackerSource, NextBeforeStartIsAnError) {
  Rig rig;
  auto src = rig.source();
  EXPECT_EQ(src.next(1ms).status, ReadStatus::error);
}

}  // namespace
}  // namespace foveal::hid
