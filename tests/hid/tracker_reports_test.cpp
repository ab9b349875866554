#include <gtest/gtest.h>

#include "foveal/drivers/hid/tracker_reports.hpp"
#include "hid_test_data.hpp"
#include "hutrr74_reports.hpp"

namespace foveal::hid {
namespace {

namespace h = test::hutrr74;

TrackerLayout real_layout() {
  auto l = make_tracker_layout(test::eye_tracker_descriptor_bytes());
  EXPECT_TRUE(l) << (l ? "" : l.error().message);
  return l ? *l : TrackerLayout{};
}

TEST(HidTrackerLayout, RealDescriptorReportsFoundByCollection) {
  const TrackerLayout l = real_layout();
  EXPECT_TRUE(l.tracking.present);
  EXPECT_EQ(l.tracking.id, 0x10);
  EXPECT_EQ(l.tracking.bytes, 65u);
  EXPECT_EQ(l.capabilities.id, 0x11);
  EXPECT_EQ(l.capabilities.bytes, 22u);
  EXPECT_EQ(l.configuration.id, 0x12);
  EXPECT_EQ(l.configuration.bytes, 19u);
  EXPECT_TRUE(l.status_feature.present);
  EXPECT_TRUE(l.status_input.present);
  EXPECT_EQ(l.status_feature.id, 0x13);
  EXPECT_EQ(l.status_input.id, 0x13);
  EXPECT_EQ(l.control.id, 0x14);
  EXPECT_EQ(l.control.bytes, 2u);
}

TEST(HidTrackerLayout, NonTrackerAndIncompleteTrackerRejected) {
  // A mouse: generic desktop page, no eye tracker.
  const std::vector<std::uint8_t> mouse = {0x05, 0x01, 0x09, 0x02, 0xa1, 0x01, 0x09, 0x30, 0x15, 0x81, 0x25, 0x7f,
                                           0x75, 0x08, 0x95, 0x01, 0x81, 0x06, 0xc0};
  auto m = make_tracker_layout(mouse);
  ASSERT_FALSE(m);
  EXPECT_NE(m.error().message.find("no Eye Tracker"), std::string::npos);
  // An eye tracker application with tracking data but no Tracker Control.
  const std::vector<std::uint8_t> no_control = {0x05, 0x12, 0x09, 0x01, 0xa1, 0x01, 0x09, 0x10, 0xa1, 0x02, 0x85, 0x10,
                                                0x09, 0x21, 0x75, 0x20, 0x95, 0x01, 0x81, 0x02, 0xc0, 0xc0};
  auto n = make_tracker_layout(no_control);
  ASSERT_FALSE(n);
  EXPECT_NE(n.error().message.find("Mode Request"), std::string::npos);
}

TEST(HidTrackerReports, TrackingDataDecodesToMillimetres) {
  const TrackerLayout l = real_layout();
  h::Tracking t;
  t.timestamp_us = 0x0000'0102'0304'0506ull;
  t.gaze_x_um = 150000;
  t.gaze_y_um = -25000;
  t.left_um = {-32000, 1000, 600000};
  t.right_um = {32000, -1000, 610000};
  auto d = decode_tracking_data(l, h::tracking_report(t));
  ASSERT_TRUE(d) << d.error().message;
  ASSERT_TRUE(d->device_time_ns.has_value());
  EXPECT_EQ(*d->device_time_ns, static_cast<std::int64_t>(t.timestamp_us) * 1000);
  EXPECT_TRUE(d->gaze_valid);
  EXPECT_DOUBLE_EQ(d->gaze_x_mm, 150.0);
  EXPECT_DOUBLE_EQ(d->gaze_y_mm, -25.0);
  EXPECT_TRUE(d->left_valid);
  EXPECT_TRUE(d->right_valid);
  EXPECT_DOUBLE_EQ(d->left_eye_mm.x, -32.0);
  EXPECT_DOUBLE_EQ(d->left_eye_mm.y, 1.0);
  EXPECT_DOUBLE_EQ(d->left_eye_mm.z, 600.0);
  EXPECT_DOUBLE_EQ(d->right_eye_mm.z, 610.0);
}

TEST(HidTrackerReports, OutOfRangeGazeAndZeroEyesAreInvalid) {
  const TrackerLayout l = real_layout();
  h::Tracking t;
  t.gaze_x_um = 2'000'001;  // logical maximum is 2,000,000
  auto d = decode_tracking_data(l, h::tracking_report(t));
  ASSERT_TRUE(d);
  EXPECT_FALSE(d->gaze_valid);
  EXPECT_FALSE(d->left_valid);   // all zero: not reported
  EXPECT_FALSE(d->right_valid);
}

TEST(HidTrackerReports, TruncatedAndWrongIdRejectedWithMessage) {
  const TrackerLayout l = real_layout();
  auto r = h::tracking_report({});
  r.resize(40);
  auto d = decode_tracking_data(l, r);
  ASSERT_FALSE(d);
  EXPECT_NE(d.error().message.find("truncated"), std::string::npos) << d.error().message;
  auto s = decode_tracking_data(l, h::status_report(1, 120));
  ASSERT_FALSE(s);
  EXPECT_NE(s.error().message.find("expected report ID 16"), std::string::npos) << s.error().message;
  EXPECT_FALSE(decode_tracking_data(l, std::vector<std::uint8_t>{}));
}

TEST(HidTrackerReports, StatusCapabilitiesConfiguration) {
  const TrackerLayout l = real_layout();
  auto s = decode_status(l, ReportType::feature, h::status_report(1, 120));
  ASSERT_TRUE(s) << s.error().message;
  EXPECT_EQ(s->configuration_status, 1);
  EXPECT_DOUBLE_EQ(s->sampling_frequency_hz, 120.0);
  auto si = decode_status(l, ReportType::input, h::status_report(4, 90));
  ASSERT_TRUE(si);
  EXPECT_EQ(si->configuration_status, 4);
  EXPECT_DOUBLE_EQ(si->sampling_frequency_hz, 90.0);
  EXPECT_STREQ(configuration_status_name(4), "user calibration needed");

  auto c = decode_capabilities(l, h::capabilities_report(1, 450000, 650000, 950000, 600000, 340000));
  ASSERT_TRUE(c) << c.error().message;
  EXPECT_EQ(c->tracker_quality, 1);
  EXPECT_DOUBLE_EQ(c->minimum_distance_mm, 450.0);
  EXPECT_DOUBLE_EQ(c->optimum_distance_mm, 650.0);
  EXPECT_DOUBLE_EQ(c->maximum_distance_mm, 950.0);
  EXPECT_DOUBLE_EQ(c->max_screen_width_mm, 600.0);
  EXPECT_DOUBLE_EQ(c->max_screen_height_mm, 340.0);

  auto g = decode_configuration(l, h::configuration_report(527000, 296000));
  ASSERT_TRUE(g) << g.error().message;
  EXPECT_EQ(g->display_manufacturer_id, 0x1234u);
  EXPECT_EQ(g->display_product_id, 0x5678u);
  EXPECT_EQ(g->display_serial, 42u);
  EXPECT_EQ(g->display_date, 2024u);
  EXPECT_DOUBLE_EQ(g->screen_width_mm, 527.0);
  EXPECT_DOUBLE_EQ(g->screen_height_mm, 296.0);
  // A zero-filled reply (what a USB gadget without GET_REPORT support sends) is no report.
  EXPECT_FALSE(decode_configuration(l, std::vector<std::uint8_t>(19, 0)));
}

TEST(HidTrackerReports, ModeRequestEncodes) {
  const TrackerLayout l = real_layout();
  auto m = encode_mode_request(l, kModeGazePoint | kModeEyePosition);
  ASSERT_TRUE(m) << m.error().message;
  EXPECT_EQ(*m, (std::vector<std::uint8_t>{0x14, 0x03}));
  EXPECT_FALSE(encode_mode_request(l, 8));  // logical maximum 7
}

}  // namespace
}  // namespace foveal::hid
