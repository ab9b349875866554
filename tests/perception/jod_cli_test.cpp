// foveal metrics --jod from the command line: stills, stereo, frame folders, refusals.
#include <gtest/gtest.h>
#include <sys/stat.h>

#include <cstdint>
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

// foveal with a guard that only ends a hang (the old code blocked on a FIFO for ever):
// every case here exits at once.
std::string guarded(const std::string& cmd) { return "timeout -s KILL 120 " + cmd; }

// A PNG of only its signature and header (IHDR: 8-bit RGBA, CRC unchecked by stb_image):
// as large as it says, with nothing to decode.
std::string png_header(std::uint32_t w, std::uint32_t h) {
  std::string s = "\x89PNG\r\n\x1a\n";
  s += std::string("\0\0\0\x0d", 4) + "IHDR";
  for (std::uint32_t v : {w, h})
    for (int shift = 24; shift >= 0; shift -= 8) s += static_cast<char>((v >> shift) & 0xff);
  s += std::string("\x08\x06\0\0\0", 5);
  s += std::string(4, '\0');  // CRC
  return s;
}

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

// Issue 38, item 9: the work is sized from the headers and options before anything is
// decoded, and refused past the bound naming what it needs and how to raise it (two
// 16384² images needed ~11 GB and aborted on bad_alloc under a 4 GB cap).
TEST(JodCli, WorkPastTheMemoryBoundIsRefusedFromTheHeadersBeforeDecoding) {
  test::TempDir d;
  test::write_file(d.path("big.png"), png_header(16384, 16384));
  const std::string big = "--ref " + d.path("big.png") + " --test " + d.path("big.png");
  auto r = test::run(guarded("env FOVEAL_MEMORY_LIMIT_GB=8 " + jod(big)));
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_NE(r.err.find("metrics --jod: needs about 11.3 GB for JOD of two 16384x16384 images; the bound is 8.0 GB "
                       "(FOVEAL_MEMORY_LIMIT_GB=13 raises it)"),
            std::string::npos)
      << r.err;
  // The default bound (8 GB, or half the machine's memory) says the same.
  auto dflt = test::run(guarded("env -u FOVEAL_MEMORY_LIMIT_GB " + jod(big)));
  EXPECT_EQ(dflt.exit_code, 2) << dflt.err;
  EXPECT_NE(dflt.err.find("needs about 11.3 GB"), std::string::npos) << dflt.err;
  EXPECT_NE(dflt.err.find("FOVEAL_MEMORY_LIMIT_GB="), std::string::npos) << dflt.err;
  // PSNR/SSIM/FPSNR of the pair: both decoded, 12 bytes a pixel.
  auto plain = test::run(guarded("env FOVEAL_MEMORY_LIMIT_GB=2 " + test::bin("foveal") + " metrics " + big + " --fovea 0.5,0.5"));
  EXPECT_EQ(plain.exit_code, 2) << plain.err;
  EXPECT_NE(plain.err.find("metrics: needs about 3.2 GB for two 16384x16384 images"), std::string::npos) << plain.err;
  auto bad = test::run(guarded("env FOVEAL_MEMORY_LIMIT_GB=lots " + jod(big)));
  EXPECT_EQ(bad.exit_code, 2) << bad.err;
  EXPECT_NE(bad.err.find("FOVEAL_MEMORY_LIMIT_GB: 'lots' is not a number of GB"), std::string::npos) << bad.err;
}

// A video keeps ceil(fps/4) frames of both videos per eye (at most its frame count): at
// 1000 fps 250 of them.
TEST(JodCli, AVideosRingIsCountedInTheBound) {
  test::TempDir d;
  ASSERT_TRUE(image::save_png(d.path("r.png"), pattern(64, 48, 0)));
  ASSERT_TRUE(image::save_png(d.path("t.png"), pattern(64, 48, 3)));
  std::string refs, tests;  // 300 frames: lists may name a file again
  for (int k = 0; k < 300; ++k) refs += "r.png\n", tests += "t.png\n";
  test::write_file(d.path("ref.txt"), refs);
  test::write_file(d.path("test.txt"), tests);
  const std::string io = "--ref " + d.path("ref.txt") + " --test " + d.path("test.txt");
  auto fast = test::run(guarded("env FOVEAL_MEMORY_LIMIT_GB=0.002 " + jod(io + " --fps 1000")));
  EXPECT_EQ(fast.exit_code, 2) << fast.err;
  EXPECT_NE(fast.err.find("JOD of two videos of 300 64x48 frames at 1000 fps (each eye keeps 250 frames of both)"), std::string::npos)
      << fast.err;
  EXPECT_NE(fast.err.find("the bound is 2 MB"), std::string::npos) << fast.err;
  auto slow = test::run(guarded("env FOVEAL_MEMORY_LIMIT_GB=0.002 " + jod(io + " --fps 90 --json")));
  EXPECT_EQ(slow.exit_code, 0) << slow.err;
}

// Issue 38, item 10: the fovea list and .txt frame lists go through the project's file
// entry point: a FIFO was waited on for ever, a link to /dev/zero read as one huge line.
TEST(JodCli, ListsThatAreFifosOrDevicesAreRefusedWithoutBlocking) {
  test::TempDir d;
  ASSERT_TRUE(image::save_png(d.path("a.png"), pattern(64, 48, 0)));
  const std::string a = d.path("a.png");
  ASSERT_EQ(::mkfifo(d.path("fovea.fifo").c_str(), 0600), 0);
  ASSERT_EQ(::mkfifo(d.path("frames.txt").c_str(), 0600), 0);
  std::filesystem::create_symlink("/dev/zero", d.path("zero.txt"));
  std::filesystem::create_symlink("/dev/zero", d.path("fovea.zero"));
  struct Case {
    std::string args, expect;
  } cases[] = {
      {"--ref " + a + " --test " + a + " --fovea-list " + d.path("fovea.fifo"),
       "--fovea-list " + d.path("fovea.fifo") + ": fovea list is a FIFO; foveal reads only regular files"},
      {"--ref " + a + " --test " + a + " --fovea-list " + d.path("fovea.zero"),
       "--fovea-list " + d.path("fovea.zero") + ": fovea list is a character device"},
      {"--ref " + d.path("frames.txt") + " --test " + a, "--ref " + d.path("frames.txt") + ": frame list is a FIFO"},
      {"--ref " + a + " --test " + d.path("zero.txt"), "--test " + d.path("zero.txt") + ": frame list is a character device"},
  };
  for (const Case& c : cases) {
    SCOPED_TRACE(c.args);
    auto r = test::run(guarded(jod(c.args)));
    EXPECT_EQ(r.exit_code, 2) << r.err;
    EXPECT_NE(r.err.find(c.expect), std::string::npos) << r.err.substr(0, 2000);
    EXPECT_LT(r.err.size(), 1000u);
  }
}

// Issue 38, item 14: physical parameters are bounded, naming the option (peak 1e300 gave
// "jod": null with exit 0, --ppd 1e308 an FPSNR of "inf").
TEST(JodCli, PhysicalParametersOutsideTheirRangesAreRefusedNamingTheOption) {
  test::TempDir d;
  ASSERT_TRUE(image::save_png(d.path("a.png"), pattern(64, 48, 0)));
  ASSERT_TRUE(image::save_png(d.path("b.png"), pattern(64, 48, 7)));
  std::filesystem::create_directories(d.path("ref"));
  for (int k = 0; k < 2; ++k) ASSERT_TRUE(image::save_png(d.path("ref/f" + std::to_string(k) + ".png"), pattern(64, 48, k)));
  const std::string ab = "--ref " + d.path("a.png") + " --test " + d.path("b.png");
  const std::string video = "--ref " + d.path("ref") + " --test " + d.path("ref");
  const std::string metrics = test::bin("foveal") + " metrics ";
  struct Case {
    std::string cmd, expect;
  } cases[] = {
      {jod(ab + " --peak 1e300 --json"), "--peak: must lie in (0.001, 10000] cd/m², got 1e+300"},
      {jod(ab + " --peak nan --json"), "--peak: must lie in"},
      {jod(ab + " --black 0 --json"), "--black: must lie in [0.001, 10000] cd/m², got 0"},
      {jod(ab + " --black 1e-300 --json"), "--black: must lie in"},
      {jod(video + " --fps 5000"), "--fps: must lie in (0, 1000] frames per second, got 5000"},
      {jod(video + " --fps 0"), "--fps: must lie in (0, 1000]"},
      {metrics + ab + " --fovea 0.5,0.5 --ppd 1e308 --json", "--ppd: must lie in [0.1, 1000] pixels per degree, got 1e+308"},
      {metrics + ab + " --fovea 0.5,0.5 --ppd 1e-300 --json", "--ppd: must lie in"},
  };
  for (const Case& c : cases) {
    SCOPED_TRACE(c.cmd);
    auto r = test::run(guarded(c.cmd));
    EXPECT_EQ(r.exit_code, 2) << r.out << r.err;
    EXPECT_TRUE(r.out.empty()) << r.out;
    EXPECT_NE(r.err.find(c.expect), std::string::npos) << r.err;
  }
  // The ends of the ranges score, with finite figures.
  auto hdr = test::run(guarded(jod(ab + " --peak 10000 --black 0.001 --json")));
  ASSERT_EQ(hdr.exit_code, 0) << hdr.err;
  EXPECT_TRUE(nlohmann::json::parse(hdr.out)["jod"].is_number()) << hdr.out;
  auto dense = test::run(guarded(metrics + ab + " --fovea 0.5,0.5 --ppd 1000 --json"));
  ASSERT_EQ(dense.exit_code, 0) << dense.err;
  EXPECT_TRUE(nlohmann::json::parse(dense.out)["fpsnr_db"].is_number()) << dense.out;
}
