// The fast float parser against std::from_chars, the line reader across its buffer,
// atomic files, and the display model.
#include <gtest/gtest.h>

#include <charconv>
#include <cstring>
#include <filesystem>
#include <random>

#include "foveal/core/atomic_file.hpp"
#include "foveal/core/display_model.hpp"
#include "foveal/core/line_reader.hpp"
#include "foveal/core/text_fields.hpp"
#include "test_support.hpp"

namespace foveal {
namespace {

std::uint32_t bits(float f) {
  std::uint32_t b;
  std::memcpy(&b, &f, 4);
  return b;
}

void expect_same_as_from_chars(const std::string& s) {
  float want = 0, got = 0;
  auto [p, ec] = std::from_chars(s.data(), s.data() + s.size(), want);
  const bool ref_ok = ec == std::errc() && p == s.data() + s.size();
  const bool ok = parse_number(std::string_view(s), got);
  ASSERT_EQ(ok, ref_ok) << s;
  if (ok) {
    ASSERT_EQ(bits(got), bits(want)) << s;
  }
}

TEST(FloatParse, AgreesWithFromCharsOnAMillionShortestForms) {
  std::mt19937 rng(42);
  std::uniform_int_distribution<std::uint32_t> any;
  for (int i = 0; i < 1'000'000; ++i) {
    std::uint32_t b = any(rng);
    float f;
    std::memcpy(&f, &b, 4);
    if (!std::isfinite(f)) continue;
    char buf[64];
    auto [p, ec] = std::to_chars(buf, buf + sizeof buf, f);
    ASSERT_EQ(ec, std::errc());
    expect_same_as_from_chars(std::string(buf, p));
  }
}

TEST(FloatParse, AgreesOnFixedFormsAndMidpoints) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(-100, 100);
  for (int i = 0; i < 200000; ++i) {
    char buf[64];
    const int n = std::snprintf(buf, sizeof buf, "%.*f", i % 12, u(rng));
    expect_same_as_from_chars(std::string(buf, static_cast<std::size_t>(n)));
  }
  // Exact decimal midpoints between neighbouring floats: where double rounding bites.
  for (float f : {0.1f, 1.0f, 3.14159f, 1e-3f, 123.456f, 0.9999999f}) {
    const float g = std::nextafter(f, 10.0f);
    char buf[64];
    const int n = std::snprintf(buf, sizeof buf, "%.25g", (static_cast<double>(f) + static_cast<double>(g)) / 2.0);
    expect_same_as_from_chars(std::string(buf, static_cast<std::size_t>(n)));
  }
  for (const char* s : {"0", "-0", "1.", ".5", "-.5", ".", "-", "", "1e5", "1e-40", "3.4e38", "1e39", "nan", "inf",
                        "12345678901234567890", "0.000000000000000000000000000000000000000000001", "1,5", "--1"})
    expect_same_as_from_chars(s);
}

TEST(LineReader, StreamsLinesAcrossItsBufferAndRewinds) {
  test::TempDir dir;
  std::string content;
  std::vector<std::string> lines;
  std::mt19937 rng(1);
  while (content.size() < 3u * 1024 * 1024) {
    std::string l(rng() % 300, 'a' + static_cast<char>(lines.size() % 26));
    lines.push_back(l);
    content += l + "\n";
  }
  test::write_file(dir.path("f"), content);
  auto r = LineReader::open(dir.path("f"));
  ASSERT_TRUE(r);
  for (int pass = 0; pass < 2; ++pass) {
    LineReader::Line l;
    for (std::size_t i = 0; i < lines.size(); ++i) {
      auto got = r->next(l);
      ASSERT_TRUE(got && *got) << i;
      ASSERT_EQ(l.text, lines[i]) << i;
      ASSERT_EQ(l.number, i + 1);
    }
    auto end = r->next(l);
    ASSERT_TRUE(end);
    EXPECT_FALSE(*end);
    ASSERT_TRUE(r->rewind());
  }
}

TEST(LineReader, ALineLongerThanTheBufferIsAnError) {
  test::TempDir dir;
  test::write_file(dir.path("f"), "short\n" + std::string(2 * 1024 * 1024, 'x') + "\n");
  auto r = LineReader::open(dir.path("f"));
  ASSERT_TRUE(r);
  LineReader::Line l;
  ASSERT_TRUE(*r->next(l));
  auto got = r->next(l);
  ASSERT_FALSE(got);
  EXPECT_NE(got.error().message.find(":2:"), std::string::npos) << got.error().message;
}

TEST(AtomicFile, NothingAppearsUntilCommitAndCommitReplaces) {
  test::TempDir dir;
  const std::string p = dir.path("out.txt");
  {
    auto f = AtomicFile::create(p);
    ASSERT_TRUE(f);
    f->write("partial");
  }  // destroyed without commit
  EXPECT_TRUE(std::filesystem::is_empty(dir.path())) << "no file and no temporary left";
  ASSERT_TRUE(write_file_atomically(p, "one"));
  ASSERT_TRUE(write_file_atomically(p, "two"));
  EXPECT_EQ(test::read_file(p), "two");
  EXPECT_FALSE(write_file_atomically(dir.path("missing/dir/x"), "y"));
}

TEST(DisplayModel, TheShippedFileMatchesTheBuiltInDefault) {
  auto m = DisplayModel::load(test::source_path("data/display/htc_vive_pro_eye.json"));
  ASSERT_TRUE(m) << m.error().message;
  const DisplayModel d = DisplayModel::vive_pro_eye();
  EXPECT_EQ(m->eye_width, d.eye_width);
  EXPECT_EQ(m->eye_height, d.eye_height);
  for (Eye e : kEyes) {
    EXPECT_NEAR(m->eye(e).tan_left, d.eye(e).tan_left, 1e-5);
    EXPECT_NEAR(m->eye(e).tan_top, d.eye(e).tan_top, 1e-5);
  }
  EXPECT_NEAR(d.focal_px(Eye::left).x, 753.6f, 0.01f);
  EXPECT_EQ(m->refresh_hz, 90.0);
  EXPECT_EQ(d.refresh_hz, 90.0);
  EXPECT_EQ(m->edid_vendor, "HVR");
  EXPECT_EQ(d.edid_vendor, "HVR");
}

TEST(DisplayModel, DirectionPixelRoundTripAndCentre) {
  const DisplayModel d = DisplayModel::vive_pro_eye();
  const glm::vec2 c = d.direction_to_pixel(Eye::left, {0, 0, -1});
  EXPECT_FLOAT_EQ(c.x, 720.0f);
  EXPECT_FLOAT_EQ(c.y, 800.0f);
  for (glm::vec2 px : {glm::vec2{0, 0}, glm::vec2{1439.5f, 1599.5f}, glm::vec2{100, 1500}}) {
    const glm::vec2 back = d.direction_to_pixel(Eye::right, d.pixel_to_direction(Eye::right, px));
    EXPECT_NEAR(back.x, px.x, 1e-3f);
    EXPECT_NEAR(back.y, px.y, 1e-3f);
  }
  // Up in the eye frame is up on screen: smaller y.
  EXPECT_LT(d.direction_to_pixel(Eye::left, {0, 0.1f, -1}).y, 800.0f);
  EXPECT_TRUE(std::isnan(d.direction_to_pixel(Eye::left, {0, 0, 1}).x));  // behind the eye
}

TEST(DisplayModel, BadFilesAreRejectedNamingTheFile) {
  test::TempDir dir;
  const std::pair<const char*, const char*> cases[] = {
      {"{ not json", "not valid JSON"},
      {R"({"format":"foveal-display-model v1","eyes":2})", "unknown key 'eyes'"},
      {R"({"format":"foveal-display-model v1","left":{"tangents":{"left":1,"right":-1,"bottom":-1,"top":1}}})", "left < right"},
      {R"({"eye_width":1440})", "format"},
      {R"({"format":"foveal-display-model v1","refresh_hz":-5})", "refresh_hz"},
      {R"({"format":"foveal-display-model v1","edid_vendor":"htc"})", "edid_vendor"},
  };
  for (const auto& [content, expect] : cases) {
    test::write_file(dir.path("m.json"), content);
    auto m = DisplayModel::load(dir.path("m.json"));
    ASSERT_FALSE(m) << content;
    EXPECT_NE(m.error().message.find(dir.path("m.json")), std::string::npos) << m.error().message;
    EXPECT_NE(m.error().message.find(expect), std::string::npos) << m.error().message;
  }
}

TEST(Cli, EveryCommandHasHelp) {
  for (const char* cmd : {"foveal --help", "foveal import --help", "foveal log validate --help", "foveal synth --help",
                          "foveal replay --help", "foveal profile create --help", "foveal ctl --help",
                          "foveal calibrate --help", "foveal filter-chart --help", "foveal hid decode --help",
                          "foveal render --help", "foveal foveate --help", "foveal outputs --help", "foveald --help"}) {
    auto r = test::run(test::bin("") + cmd);
    EXPECT_EQ(r.exit_code, 0) << cmd << r.err;
    EXPECT_NE(r.out.find("--"), std::string::npos) << cmd;
  }
}

}  // namespace
}  // namespace foveal

namespace foveal {
namespace {

TEST(LensDistortion, LoadsAndRoundTripsEveryChannel) {
  auto m = DisplayModel::load(test::source_path("data/display/htc_vive_pro_eye_lens.json"));
  ASSERT_TRUE(m) << m.error().message;
  const LensDistortion& d = m->distortion[0];
  ASSERT_TRUE(d.enabled);
  EXPECT_FLOAT_EQ(d.k1, 0.22f);
  const EyeFrustum& f = m->eye(Eye::left);
  for (int c = 0; c < 3; ++c)
    for (float x = 0.05f; x < 1.0f; x += 0.1f)
      for (float y = 0.05f; y < 1.0f; y += 0.1f) {
        const glm::vec2 src = d.source({x, y}, c, f);
        const glm::vec2 back = d.panel(src, c, f);
        EXPECT_NEAR(back.x, x, 1e-4) << c;
        EXPECT_NEAR(back.y, y, 1e-4) << c;
      }
  // Barrel correction: a panel point off-centre samples farther out, red less than blue.
  EXPECT_GT(d.source({0.9f, 0.5f}, 1, f).x, 0.9f);
  EXPECT_LT(d.source({0.9f, 0.5f}, 0, f).x, d.source({0.9f, 0.5f}, 2, f).x);
  EXPECT_EQ(d.source(d.center, 1, f), d.center);
}

TEST(LensDistortion, BadValuesNameTheFile) {
  test::TempDir dir;
  const std::string good = test::read_file(test::source_path("data/display/htc_vive_pro_eye_lens.json"));
  std::string bad = good;
  bad.replace(bad.find("[0.994"), 6, "[-1.00");
  test::write_file(dir.path("bad.json"), bad);
  auto m = DisplayModel::load(dir.path("bad.json"));
  ASSERT_FALSE(m);
  EXPECT_NE(m.error().message.find("channel_scale"), std::string::npos) << m.error().message;
  std::string missing = good;
  missing.replace(missing.find("\"k\""), 3, "\"q\"");
  test::write_file(dir.path("missing.json"), missing);
  EXPECT_FALSE(DisplayModel::load(dir.path("missing.json")));
}

}  // namespace
}  // namespace foveal
