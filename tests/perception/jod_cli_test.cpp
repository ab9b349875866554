// foveal metrics --jod from the command line: stills, stereo, frame folders, refusals.
#include <gtest/gtest.h>

#include <filesystem>
#include <nlohmann/json.hpp>

#include "foveal/image/image.hpp"
#include "test_support.hpp"

using namespace foveal;

namespace {

image::Image pattern(int w, int h, int offset) {
  image::Image img(w, h);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      std::uint8_t* p = img.at(x, y);
      p[0] = static_cast<std::uint8_t>((x * 5 + offset) % 256);
      p[1] = static_cast<std::uint8_t>((y * 7) % 256);
      p[2] = static_cast<std::uint8_t>(((x ^ y) * 3 + offset) % 256);
      p[3] = 255;
    }
  return img;
}

std::string jod(const std::string& args) { return test::bin("foveal") + " metrics --jod " + args; }

}  // namespace

TEST(JodCli, StillsStereoAndNoFovea) {
  test::TempDir d;
  ASSERT_TRUE(image::save_png(d.path("a.png"), pattern(128, 64, 0)));
  ASSERT_TRUE(image::save_png(d.path("b.png"), pattern(128, 64, 9)));
  auto same = test::run(jod("--ref " + d.path("a.png") + " --test " + d.path("a.png") + " --json"));
  ASSERT_EQ(same.exit_code, 0) << same.err;
  auto js = nlohmann::json::parse(same.out);
  EXPECT_DOUBLE_EQ(js["jod"].get<double>(), 10.0);
  EXPECT_EQ(js["foveated"].get<bool>(), false);
  EXPECT_NEAR(js["ppd"].get<double>(), 13.15 * 128 / 1440, 0.01);  // the Vive's field on 128 px
  auto st = test::run(jod("--ref " + d.path("a.png") + " --test " + d.path("b.png") +
                          " --stereo --fovea 0.2,0.5 --fovea-right none --json"));
  ASSERT_EQ(st.exit_code, 0) << st.err;
  auto j = nlohmann::json::parse(st.out);
  EXPECT_LT(j["left"]["jod"].get<double>(), 10.0);
  EXPECT_EQ(j["left"]["foveated"].get<bool>(), true);
  EXPECT_EQ(j["right"]["foveated"].get<bool>(), false);
  EXPECT_LT(j["jod"].get<double>(), 10.0);
  EXPECT_EQ(j["size"][0].get<int>(), 64);
  auto r10 = test::run(jod("--ref " + d.path("a.png") + " --test " + d.path("b.png") +
                           " --stereo --fovea 0.2,0.5 --fovea-right none --jod-release 1.0 --json"));
  ASSERT_EQ(r10.exit_code, 0) << r10.err;
  auto j10 = nlohmann::json::parse(r10.out);
  EXPECT_EQ(j10["release"].get<std::string>(), "1.0");
  EXPECT_NE(j10["jod"].get<double>(), j["jod"].get<double>());
}

TEST(JodCli, FrameFoldersNeedAFrameRate) {
  test::TempDir d;
  std::filesystem::create_directories(d.path("ref"));
  std::filesystem::create_directories(d.path("test"));
  for (int k = 0; k < 3; ++k) {
    ASSERT_TRUE(image::save_png(d.path("ref/f" + std::to_string(k) + ".png"), pattern(64, 48, k)));
    ASSERT_TRUE(image::save_png(d.path("test/f" + std::to_string(k) + ".png"), pattern(64, 48, k + (k % 2) * 5)));
  }
  const std::string io = "--ref " + d.path("ref") + " --test " + d.path("test");
  auto no_fps = test::run(jod(io));
  EXPECT_EQ(no_fps.exit_code, 2);
  EXPECT_NE(no_fps.err.find("--fps"), std::string::npos) << no_fps.err;
  auto v = test::run(jod(io + " --fps 90 --fovea 0.5,0.5 --json"));
  ASSERT_EQ(v.exit_code, 0) << v.err;
  auto j = nlohmann::json::parse(v.out);
  EXPECT_EQ(j["frames"].get<int>(), 3);
  EXPECT_LT(j["jod"].get<double>(), 10.0);
  test::write_file(d.path("fovea.txt"), "0.5,0.5\n0.1,0.1\n");
  auto short_list = test::run(jod(io + " --fps 90 --fovea-list " + d.path("fovea.txt")));
  EXPECT_EQ(short_list.exit_code, 2);
  EXPECT_NE(short_list.err.find("2 foveae for 3 frames"), std::string::npos) << short_list.err;
  test::write_file(d.path("per_frame.txt"), "# x,y per frame\n0.5,0.5\nnone\n0.1,0.2,0.3,0.4\n");
  auto per_frame = test::run(jod(io + " --fps 90 --fovea-list " + d.path("per_frame.txt") + " --json"));
  ASSERT_EQ(per_frame.exit_code, 0) << per_frame.err;
  EXPECT_EQ(nlohmann::json::parse(per_frame.out)["foveated"].get<std::string>(), "per frame");
  test::write_file(d.path("bad.txt"), "0.5,0.5\n0.5;0.5\n0.1,0.1\n");
  auto bad = test::run(jod(io + " --fps 90 --fovea-list " + d.path("bad.txt")));
  EXPECT_EQ(bad.exit_code, 2);
  EXPECT_NE(bad.err.find("bad.txt:2: '0.5;0.5'"), std::string::npos) << bad.err;
}

TEST(JodCli, BadInputNamesWhatAndWhere) {
  test::TempDir d;
  ASSERT_TRUE(image::save_png(d.path("a.png"), pattern(64, 48, 0)));
  ASSERT_TRUE(image::save_png(d.path("c.png"), pattern(66, 48, 0)));
  const std::string a = d.path("a.png");
  auto size = test::run(jod("--ref " + a + " --test " + d.path("c.png")));
  EXPECT_EQ(size.exit_code, 2);
  EXPECT_NE(size.err.find("differs from the reference"), std::string::npos) << size.err;
  auto lum = test::run(jod("--ref " + a + " --test " + a + " --peak 50 --black 60"));
  EXPECT_EQ(lum.exit_code, 2);
  EXPECT_NE(lum.err.find("black < peak"), std::string::npos) << lum.err;
  auto disp = test::run(jod("--ref " + a + " --test " + a + " --display " + d.path("none.json")));
  EXPECT_EQ(disp.exit_code, 2);
  EXPECT_NE(disp.err.find("none.json"), std::string::npos) << disp.err;
  auto fov = test::run(jod("--ref " + a + " --test " + a + " --fovea 1.5,0"));
  EXPECT_EQ(fov.exit_code, 2);
  EXPECT_NE(fov.err.find("--fovea"), std::string::npos) << fov.err;
}
