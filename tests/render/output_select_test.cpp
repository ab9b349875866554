// Direct mode's choices without a device: EDID identity, connector and mode selection,
// --mode parsing, and the frame-pacing counts. The real kernel path runs in the VM test
// (tests/vm/run_drm_vm_test.py).
#include <gtest/gtest.h>

#include <cstdint>
#include <string>
#include <vector>

#include "foveal/render/kms_select.hpp"
#include "foveal/render/present_stats.hpp"

using namespace foveal::render;

namespace {

// An EDID base block with the given manufacturer, product code and monitor name.
std::vector<std::uint8_t> edid(const char vendor[3], std::uint16_t product, const std::string& name) {
  std::vector<std::uint8_t> e(128, 0);
  const std::uint8_t header[8] = {0x00, 0xff, 0xff, 0xff, 0xff, 0xff, 0xff, 0x00};
  std::copy(header, header + 8, e.begin());
  const unsigned m = unsigned(vendor[0] - 'A' + 1) << 10 | unsigned(vendor[1] - 'A' + 1) << 5 | unsigned(vendor[2] - 'A' + 1);
  e[8] = std::uint8_t(m >> 8);
  e[9] = std::uint8_t(m & 0xff);
  e[10] = std::uint8_t(product & 0xff);
  e[11] = std::uint8_t(product >> 8);
  e[54] = 0x3a;  // a detailed timing first (pixel clock != 0), then the name descriptor
  e[75] = 0xfc;
  std::string text = name.substr(0, 13);
  if (text.size() < 13) text += '\n';
  text.resize(13, ' ');
  std::copy(text.begin(), text.end(), e.begin() + 77);
  return e;
}

KmsConnector conn(std::string name, bool connected, std::vector<KmsMode> modes, bool non_desktop = false,
                  std::string vendor = "") {
  KmsConnector c;
  c.name = std::move(name);
  c.connected = connected;
  c.modes = std::move(modes);
  c.non_desktop = non_desktop;
  c.edid_vendor = std::move(vendor);
  return c;
}

KmsWanted vive() {
  KmsWanted w;
  w.width = 2880;
  w.height = 1600;
  w.refresh_hz = 90;
  w.edid_vendor = "HVR";
  return w;
}

}  // namespace

TEST(Edid, IdentityFromTheBaseBlock) {
  auto id = parse_edid_identity(edid("HVR", 0xaa02, "VIVE Pro"));
  ASSERT_TRUE(id);
  EXPECT_EQ(id->vendor, "HVR");
  EXPECT_EQ(id->product, 0xaa02);
  EXPECT_EQ(id->name, "VIVE Pro");
  auto full = parse_edid_identity(edid("RHT", 0x1234, "QEMU Monitor1"));  // 13 characters, no newline
  ASSERT_TRUE(full);
  EXPECT_EQ(full->name, "QEMU Monitor1");
}

TEST(Edid, ShortOrHeaderlessBlocksAreNotEdid) {
  auto e = edid("HVR", 1, "x");
  EXPECT_FALSE(parse_edid_identity(std::span(e).first(127)));
  e[0] = 0x01;
  EXPECT_FALSE(parse_edid_identity(e));
  EXPECT_FALSE(parse_edid_identity({}));
}

TEST(KmsSelect, TheHeadsetWinsOverADesktopMonitorListedFirst) {
  const std::vector<KmsConnector> cs = {
      conn("DP-1", true, {{2880, 1600, 60, true}}),
      conn("DP-2", true, {{2880, 1600, 90, true}}, /*non_desktop=*/true),
  };
  auto c = choose_output(cs, vive());
  ASSERT_TRUE(c) << c.error().message;
  EXPECT_EQ(c->connector, 1u);
  // The EDID vendor marks it as well as the non-desktop property does.
  const std::vector<KmsConnector> by_vendor = {conn("DP-1", true, {{2880, 1600, 60, true}}),
                                               conn("HDMI-A-1", true, {{2880, 1600, 90, false}}, false, "HVR")};
  EXPECT_EQ(choose_output(by_vendor, vive())->connector, 1u);
  // Without either, the first connected connector with the size.
  const std::vector<KmsConnector> plain = {conn("DP-1", false, {{2880, 1600, 90, true}}),
                                           conn("Virtual-1", true, {{1024, 768, 60, false}, {2880, 1600, 60, false}})};
  auto p = choose_output(plain, vive());
  ASSERT_TRUE(p);
  EXPECT_EQ(p->connector, 1u);
  EXPECT_EQ(p->mode, 1u);
}

TEST(KmsSelect, TheModeNearestTheWantedRateElsePreferredElseFastest) {
  const std::vector<KmsConnector> cs = {
      conn("DP-1", true, {{2880, 1600, 60, true}, {2880, 1600, 89.53, false}, {2880, 1600, 144, false}, {1920, 1080, 90, false}})};
  KmsWanted w = vive();
  EXPECT_EQ(choose_output(cs, w)->mode, 1u);
  w.refresh_hz = 0;
  EXPECT_EQ(choose_output(cs, w)->mode, 0u);  // the preferred one
  auto none_preferred = cs;
  none_preferred[0].modes[0].preferred = false;
  EXPECT_EQ(choose_output(none_preferred, w)->mode, 2u);  // the fastest
}

TEST(KmsSelect, ErrorsSayWhyAndListEveryConnector) {
  const std::vector<KmsConnector> cs = {conn("DP-1", false, {}),
                                        conn("HDMI-A-1", true, {{1920, 1080, 60, true}}, false, "DEL")};
  auto none = choose_output(cs, vive());
  ASSERT_FALSE(none);
  for (const char* part : {"2880x1600", "DP-1 disconnected", "HDMI-A-1 connected", "EDID DEL", "1920x1080@60.00*"})
    EXPECT_NE(none.error().message.find(part), std::string::npos) << part << " in " << none.error().message;
  KmsWanted w = vive();
  w.connector = "DP-1";
  EXPECT_NE(choose_output(cs, w).error().message.find("DP-1 is disconnected"), std::string::npos);
  w.connector = "HDMI-A-1";
  EXPECT_NE(choose_output(cs, w).error().message.find("HDMI-A-1 has no 2880x1600 mode"), std::string::npos);
  w.connector = "DP-9";
  EXPECT_NE(choose_output(cs, w).error().message.find("no connector named DP-9"), std::string::npos);
}

TEST(KmsSelect, ModeArgument) {
  KmsWanted w;
  ASSERT_TRUE(parse_mode("1920x1080", w));
  EXPECT_EQ(w.width, 1920);
  EXPECT_EQ(w.refresh_hz, 0);
  ASSERT_TRUE(parse_mode("2880x1600@89.5", w));
  EXPECT_EQ(w.height, 1600);
  EXPECT_DOUBLE_EQ(w.refresh_hz, 89.5);
  for (const char* bad : {"", "2880", "2880x", "2880x1600@", "2880x1600@0", "2880x1600@90Hz", "0x10", "-5x5", "2880x1600 "}) {
    auto s = parse_mode(bad, w);
    EXPECT_FALSE(s) << bad;
  }
}

TEST(PresentStats, MissedRefreshesFromTheVblankCounter) {
  PresentStats s(90);
  const std::int64_t period = 11111111;
  for (std::uint64_t seq : {100u, 101u, 102u, 105u, 106u}) s.record(std::int64_t(seq) * period, seq);
  EXPECT_EQ(s.presented(), 5u);
  EXPECT_EQ(s.missed(), 2u);
  const auto j = s.json();
  EXPECT_EQ(j["missed_from"], "vblank");
  EXPECT_NEAR(j["interval_ms"]["median"].get<double>(), 11.11, 0.01);
  EXPECT_NEAR(j["interval_ms"]["max"].get<double>(), 33.33, 0.01);
}

TEST(PresentStats, AStuckCounterFallsBackToTheClock) {
  // Drivers without vblank interrupts (bochs, virtual outputs) send sequence 0 always.
  PresentStats s(60);
  const std::int64_t ms = 1000000;
  for (std::int64_t t : {0, 17, 33, 84, 100}) s.record(t * ms, 0);
  EXPECT_EQ(s.missed(), 2u);  // 51 ms is three periods: two refreshes without a frame
  EXPECT_EQ(s.json()["missed_from"], "clock");
}

TEST(PresentStats, UnknownWithoutRateOrCounter) {
  PresentStats s(0);
  s.record(0);
  EXPECT_EQ(s.missed(), 0u);  // one frame: nothing to miss yet
  s.record(50000000);
  EXPECT_FALSE(s.missed());
  EXPECT_TRUE(s.json()["missed"].is_null());
  EXPECT_EQ(s.json()["presented"], 2);
}

TEST(KmsSelect, TheDisplayModelAsksForItsSizeRateAndVendor) {
  const KmsWanted w = headset_output(foveal::DisplayModel::vive_pro_eye());
  EXPECT_EQ(w.width, 2880);
  EXPECT_EQ(w.height, 1600);
  EXPECT_EQ(w.refresh_hz, 90.0);
  EXPECT_EQ(w.edid_vendor, "HVR");
  EXPECT_TRUE(w.connector.empty());
  const auto j = connector_json(conn("DP-2", true, {{2880, 1600, 90, true}}, true, "HVR"));
  EXPECT_EQ(j["edid"]["vendor"], "HVR");
  EXPECT_EQ(j["modes"][0]["refresh_hz"], 90.0);
  EXPECT_TRUE(connector_json(conn("DP-1", false, {}))["edid"].is_null());
}
