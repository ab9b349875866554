// The prober: source specs, the sources they make, and the errors for bad ones.
#include <gtest/gtest.h>

#include <filesystem>

#include <nlohmann/json.hpp>

#include "foveal/core/clock.hpp"
#include "foveal/drivers/probe.hpp"
#include "test_support.hpp"

namespace foveal {
namespace {

TEST(SourceSpec, ParsesEveryForm) {
  auto r = probe::parse_source_spec("replay:/tmp/a:b.csv");  // only the first colon splits
  ASSERT_TRUE(r) << r.error().message;
  EXPECT_EQ(r->driver, "replay");
  EXPECT_EQ(r->arg, "/tmp/a:b.csv");
  EXPECT_EQ(r->text(), "replay:/tmp/a:b.csv");
  r = probe::parse_source_spec("synthetic");
  ASSERT_TRUE(r);
  EXPECT_EQ(r->arg, "");
  ASSERT_TRUE(probe::parse_source_spec("synthetic:7"));
  ASSERT_TRUE(probe::parse_source_spec("auto"));
#ifdef FOVEAL_TEST_HAVE_HID
  ASSERT_TRUE(probe::parse_source_spec("hid"));
  ASSERT_TRUE(probe::parse_source_spec("hid:/dev/hidraw3"));
  ASSERT_TRUE(probe::parse_source_spec("hid:0"));
#endif
}

TEST(SourceSpec, BadSpecsAreNamed) {
  auto r = probe::parse_source_spec("bogus:1");
  ASSERT_FALSE(r);
  EXPECT_EQ(r.error().kind, ErrorKind::bad_input);
  EXPECT_NE(r.error().message.find("unknown source 'bogus'"), std::string::npos) << r.error().message;
  EXPECT_NE(r.error().message.find("replay:PATH"), std::string::npos) << "lists the known forms";
  r = probe::parse_source_spec("replay");
  ASSERT_FALSE(r);
  EXPECT_NE(r.error().message.find("expected replay:PATH"), std::string::npos) << r.error().message;
  r = probe::parse_source_spec("auto:3");
  ASSERT_FALSE(r);
  EXPECT_NE(r.error().message.find("takes no argument"), std::string::npos);
  auto s = probe::parse_source_spec("synthetic:x7");
  ASSERT_TRUE(s);  // the seed is checked when the source is made
  auto made = probe::make_source(*s);
  ASSERT_FALSE(made);
  EXPECT_NE(made.error().message.find("whole number"), std::string::npos) << made.error().message;
}

TEST(SourceSpec, HelpNamesEveryDriver) {
  const std::string help = probe::source_spec_help();
  for (const char* form : {"replay:PATH", "synthetic[:SEED]", "auto"}) EXPECT_NE(help.find(form), std::string::npos) << form;
}

TEST(MakeSource, SyntheticIsSeededAndFinite) {
  probe::SourceOptions o;
  o.synthetic_speed = 0;  // as fast as possible
  o.synthetic_duration_s = 0.5;
  auto a = probe::make_source(*probe::parse_source_spec("synthetic:3"), o);
  auto b = probe::make_source(*probe::parse_source_spec("synthetic:3"), o);
  ASSERT_TRUE(a && b);
  EXPECT_FALSE(a->live);
  for (auto* src : {a->source.get(), b->source.get()}) {
    ASSERT_TRUE(src->open());
    ASSERT_TRUE(src->start());
  }
  int n = 0;
  for (;; ++n) {
    const ReadResult ra = a->source->next(std::chrono::milliseconds(100));
    const ReadResult rb = b->source->next(std::chrono::milliseconds(100));
    ASSERT_EQ(ra.status, rb.status);
    if (ra.status != ReadStatus::sample) {
      EXPECT_EQ(ra.status, ReadStatus::end);
      break;
    }
    EXPECT_EQ(ra.sample.eyes[0].direction.x, rb.sample.eyes[0].direction.x) << "same seed, same scanpath";
  }
  EXPECT_EQ(n, 60);  // 0.5 s at 120 Hz
}

TEST(MakeSource, ReplayReadsTheLogAndAMissingFileIsNamed) {
  auto r = probe::make_source(*probe::parse_source_spec("replay:" + test::source_path("data/gaze/vive_pro_eye_TESTNA01.csv")));
  ASSERT_TRUE(r) << r.error().message;
  ASSERT_TRUE(r->source->open());
  EXPECT_EQ(r->source->info().driver, "replay");
  auto missing = probe::make_source(*probe::parse_source_spec("replay:/nonexistent/log.csv"));
  ASSERT_TRUE(missing);
  Status s = missing->source->open();
  ASSERT_FALSE(s);
  EXPECT_NE(s.error().message.find("/nonexistent/log.csv"), std::string::npos) << s.error().message;
}

#ifdef FOVEAL_TEST_HAVE_HID
TEST(MakeSource, DevicesAreLiveAndAnUnknownIdIsNamed) {
  auto hid = probe::make_source(*probe::parse_source_spec("hid:/dev/hidraw-not-here"));
  ASSERT_TRUE(hid) << hid.error().message;
  EXPECT_TRUE(hid->live);
  EXPECT_FALSE(hid->source->open()) << "no such node: the caller waits for it";
  auto rows = probe::list_devices(false);
  ASSERT_TRUE(rows) << rows.error().message;
  auto bad = probe::make_source(*probe::parse_source_spec("hid:" + std::to_string(rows->size() + 5)));
  ASSERT_FALSE(bad);
  EXPECT_NE(bad.error().message.find("no such tracker"), std::string::npos) << bad.error().message;
  auto a = probe::make_source(*probe::parse_source_spec("auto"));
  ASSERT_TRUE(a);
  EXPECT_TRUE(a->live);
  if (rows->empty()) {
    Status s = a->source->open();
    ASSERT_FALSE(s);
    EXPECT_NE(s.error().message.find("no eye tracker"), std::string::npos) << s.error().message;
  }
}
#endif

TEST(DeviceSpec, TheOlderDeviceFormsMapToSpecs) {
  EXPECT_EQ(probe::device_spec(""), "auto");
  EXPECT_EQ(probe::device_spec("auto"), "auto");
  EXPECT_EQ(probe::device_spec("/dev/hidraw2"), "hid:/dev/hidraw2");
  EXPECT_EQ(probe::device_spec("hid:/dev/hidraw2"), "hid:/dev/hidraw2");
}

}  // namespace
}  // namespace foveal

namespace foveal {
namespace {

TEST(RecordCli, RecordsAnySourceTheProberKnows) {
  test::TempDir d;
  const auto r = test::run(test::bin("foveal") + " record --source synthetic:5 --duration 1 --json --out " + d.path("s.csv"));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  EXPECT_EQ(j["driver"], "synthetic");
  EXPECT_GE(j["samples"].get<int>(), 100);  // 1 s at 120 Hz, in real time
  EXPECT_LE(j["samples"].get<int>(), 121);
  const auto v = test::run(test::bin("foveal") + " log validate --json " + d.path("s.csv"));
  ASSERT_EQ(v.exit_code, 0) << v.err;
  const auto bad = test::run(test::bin("foveal") + " record --source nope --out " + d.path("n.csv"));
  EXPECT_EQ(bad.exit_code, 2);
  EXPECT_NE(bad.err.find("unknown source 'nope'"), std::string::npos) << bad.err;
  EXPECT_FALSE(std::filesystem::exists(d.path("n.csv")));
}

TEST(RecordCli, RecordsTheHeadPoseColumnsWithHead) {
  // No headset here: the log is v2, its head columns empty (waiting for the headset).
  test::TempDir d;
  const auto r = test::run(test::bin("foveal") + " record --source synthetic:5 --head auto --duration 1 --json --out " +
                           d.path("h.csv"));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  EXPECT_EQ(j["head"]["head"], "auto");
  EXPECT_EQ(j["head"]["poses"], 0);
  const std::string log = test::read_file(d.path("h.csv"));
  EXPECT_EQ(log.rfind("# foveal-gaze-log v2", 0), 0u) << log.substr(0, 40);
  EXPECT_NE(log.find("head=auto"), std::string::npos);
  const auto v = test::run(test::bin("foveal") + " log validate --json " + d.path("h.csv"));
  ASSERT_EQ(v.exit_code, 0) << v.err;
  const auto bad = test::run(test::bin("foveal") + " record --source synthetic --head oculus --out " + d.path("n.csv"));
  EXPECT_EQ(bad.exit_code, 2);
  EXPECT_NE(bad.err.find("unknown head-pose source 'oculus'"), std::string::npos) << bad.err;
  EXPECT_FALSE(std::filesystem::exists(d.path("n.csv")));
}

TEST(PoseSpec, ParsesEveryFormAndNamesTheKnownOnes) {
  ASSERT_TRUE(probe::parse_pose_spec("auto"));
  EXPECT_FALSE(probe::parse_pose_spec("auto:1"));
  ASSERT_TRUE(probe::parse_pose_spec("psvr2"));
  EXPECT_FALSE(probe::parse_pose_spec("psvr2:x"));
#ifdef FOVEAL_TEST_HAVE_HID
  auto v = probe::parse_pose_spec("vive:/dev/hidraw7");
  ASSERT_TRUE(v) << v.error().message;
  EXPECT_EQ(v->driver, "vive");
  EXPECT_EQ(v->arg, "/dev/hidraw7");
  EXPECT_EQ(v->text(), "vive:/dev/hidraw7");
#endif
  auto bad = probe::parse_pose_spec("oculus");
  ASSERT_FALSE(bad);
  EXPECT_EQ(bad.error().kind, ErrorKind::bad_input);
  EXPECT_NE(bad.error().message.find("psvr2"), std::string::npos) << bad.error().message;
  EXPECT_NE(probe::pose_spec_help().find("auto"), std::string::npos);
}

TEST(PoseSpec, AbsentHeadsetsFailToOpenWithAMessage) {
  // No headset on this machine: opening says so (the pose thread would wait and retry).
  for (const char* text : {"psvr2", "auto"}) {
    auto spec = probe::parse_pose_spec(text);
    ASSERT_TRUE(spec);
    auto dev = probe::make_pose_device(*spec);
    ASSERT_TRUE(dev) << dev.error().message;
    Status s = dev->device->open();
    EXPECT_FALSE(s) << text;
    EXPECT_FALSE(s.error().message.empty());
  }
  auto rows = probe::list_hmds();
  ASSERT_TRUE(rows) << rows.error().message;
  EXPECT_TRUE(rows->empty());
}

}  // namespace
}  // namespace foveal
