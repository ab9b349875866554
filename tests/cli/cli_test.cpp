// foveal render / foveate / foveald from the command line: outputs, JSON, exit codes.
#include <gtest/gtest.h>

#include <filesystem>

#include <nlohmann/json.hpp>

#include "foveal/image/image.hpp"
#include "gltf_test_models.hpp"
#include "test_support.hpp"

using namespace foveal;

TEST(RenderCli, WritesAPngAndReportsPassesAsJson) {
  test::TempDir d;
  auto r = test::run(test::bin("foveal") + " render --scene pattern:checker --size 160x90 --frames 3 --fovea-left 0,0 "
                     "--fovea-right 1,1 --json --out " + d.path("f.png"));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  EXPECT_EQ(j["method"], "rmfr");
  EXPECT_EQ(j["eyes"]["right"]["buffer"][0].get<int>(), 40);  // 80 / sigma_d 2
  EXPECT_EQ(j["eyes"]["left"]["buffer"][0].get<int>(), 27);   // 80 / sigma_nd 3
  // The default pipeline's passes (the visibility pipeline: docs/rmfr.md, "Which pipeline by default").
  EXPECT_EQ(j["pipeline"], "visibility");
  for (const char* pass : {"visibility", "material", "lighting", "inverse", "blend", "gpu_total", "cpu_frame"})
    EXPECT_GE(j["passes_ms"].value(pass, -1.0), 0.0) << pass << " in " << j["passes_ms"].dump();
  EXPECT_GT(j["targets_mb"]["total"].get<double>(), 0.0);
  EXPECT_EQ(j["targets_mb"]["temporal"].get<double>(), 0.0);  // no history without --temporal on
  auto img = image::load(d.path("f.png"));
  ASSERT_TRUE(img) << img.error().message;
  EXPECT_EQ(img->width, 160);
}

// --temporal on's histories are counted in the targets' memory.
TEST(RenderCli, TemporalAccumulationReportsItsHistoriesMemory) {
  test::TempDir d;
  auto r = test::run(test::bin("foveal") + " render --scene pattern:checker --size 160x90 --frames 2 --warmup 0 --temporal on "
                     "--json --out " + d.path("t.png"));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  const double temporal = j["targets_mb"]["temporal"].get<double>();
  EXPECT_GT(temporal, 0.0);
  EXPECT_LT(temporal, j["targets_mb"]["total"].get<double>());
}

// --display takes a bundled model's name as well as a file, as bench and metrics do.
TEST(RenderCli, DisplayTakesABundledModelsNameOrAFileAndNamesAnUnknownOne) {
  test::TempDir d;
  const std::string base = test::bin("foveal") + " render --scene pattern:checker --size 160x90 --frames 1 --warmup 0 --json --out ";
  auto by_name = test::run(base + d.path("n.png") + " --display hires_3800_35ppd");
  ASSERT_EQ(by_name.exit_code, 0) << by_name.err;
  auto by_file = test::run(base + d.path("f.png") + " --display " + test::source_path("data/display/hires_3800_35ppd.json"));
  ASSERT_EQ(by_file.exit_code, 0) << by_file.err;
  EXPECT_EQ(test::read_file(d.path("n.png")), test::read_file(d.path("f.png"))) << "the name and the file are one model";
  auto unknown = test::run(base + d.path("u.png") + " --display no_such_headset");
  EXPECT_EQ(unknown.exit_code, 2);
  EXPECT_NE(unknown.err.find("no_such_headset"), std::string::npos) << unknown.err;
  EXPECT_FALSE(std::filesystem::exists(d.path("u.png")));
}

// --fill-view moves the viewer in until an object fills the view (the benchmarks' framing
// of the object scenes); --compare-pipelines adds both pipelines' full and foveated frames.
TEST(RenderCli, FillViewMovesTheViewerInAndComparePipelinesReportsBoth) {
  test::TempDir d;
  const std::string base = test::bin("foveal") + " render --scene " + test::source_path("data/scenes/WaterBottle/WaterBottle.gltf") +
                           " --size 160x90 --frames 1 --warmup 0 --pipeline visibility --json";
  auto framed = test::run(base + " --out " + d.path("framed.png"));
  auto filled = test::run(base + " --fill-view --compare-pipelines --out " + d.path("filled.png"));
  ASSERT_EQ(framed.exit_code, 0) << framed.err;
  ASSERT_EQ(filled.exit_code, 0) << filled.err;
  const auto j = nlohmann::json::parse(filled.out);
  EXPECT_NE(j["view"].get<std::string>().find("filled"), std::string::npos) << j["view"];
  for (const char* p : {"gbuffer", "visibility"}) {
    EXPECT_GT(j["pipelines"][p]["speedup"].get<double>(), 0.0) << p;
    EXPECT_GT(j["pipelines"][p]["foveated_ms"]["gpu_total"].get<double>(), 0.0) << p;
  }
  auto a = image::load(d.path("framed.png")), b = image::load(d.path("filled.png"));
  ASSERT_TRUE(a && b);
  EXPECT_LT(image::psnr(*a, *b), 25.0) << "the filled view is another picture";
}

TEST(RenderCli, BadInputsExitTwoWithAClearMessageAndNoOutput) {
  test::TempDir d;
  const std::string out = " --out " + d.path("x.png");
  auto missing = test::run(test::bin("foveal") + " render --scene " + d.path("nope.gltf") + out);
  EXPECT_EQ(missing.exit_code, 2);
  EXPECT_NE(missing.err.find("nope.gltf"), std::string::npos) << missing.err;
  auto sigma = test::run(test::bin("foveal") + " render --scene pattern:checker --sigma-d 3 --sigma-nd 2" + out);
  EXPECT_EQ(sigma.exit_code, 2);
  EXPECT_NE(sigma.err.find("--sigma-nd"), std::string::npos) << sigma.err;
  auto fovea = test::run(test::bin("foveal") + " render --scene pattern:checker --fovea-left 1.5,0" + out);
  EXPECT_EQ(fovea.exit_code, 2);
  auto size = test::run(test::bin("foveal") + " render --scene pattern:checker --size 161x90" + out);
  EXPECT_EQ(size.exit_code, 2);
  // No shaders where the data directory says: the message names the missing file.
  std::filesystem::create_directories(d.path("data"));
  auto shaders = test::run("FOVEAL_DATA_DIR=" + d.path("data") + " " + test::bin("foveal") +
                           " render --scene pattern:checker --size 160x90" + out);
  EXPECT_NE(shaders.exit_code, 0);
  EXPECT_NE(shaders.err.find("shaders/"), std::string::npos) << shaders.err;
  EXPECT_FALSE(std::filesystem::exists(d.path("x.png")));
}

// Crafted glTF files (docs/bad-input.md, "Crafted data") through the real compositor:
// exit 2 naming the file and what is wrong, no PNG, no crash.
TEST(RenderCli, CraftedGltfExitsTwoNamingTheFileAndPath) {
  test::TempDir d;
  image::Image wide(40000, 2);
  ASSERT_TRUE(image::save_png(d.path("wide.png"), wide));
  struct Case {
    const char* file;
    void (*edit)(nlohmann::json&);
    const char* message;
  };
  const Case cases[] = {
      {"deep.gltf", nullptr, "deep.gltf: JSON nested deeper than 64 levels"},
      {"count.gltf", [](nlohmann::json& j) { j["accessors"][0]["count"] = 4000000000ull; },
       "count.gltf: accessors[0]: count 4000000000 × stride 12"},
      {"material.gltf", [](nlohmann::json& j) { j["meshes"][0]["primitives"][0]["material"] = 42; },
       "material.gltf: meshes[0].primitives[0].material: 42 is out of range (0 materials)"},
      {"matrix.gltf", [](nlohmann::json& j) { j["nodes"][0]["matrix"] = {1, 2, 3}; }, "matrix.gltf: nodes[0].matrix: must be an array of 16 numbers"},
      {"wide.gltf",
       [](nlohmann::json& j) {
         j["images"] = {{{"uri", "wide.png"}}};
         j["textures"] = {{{"source", 0}}};
         j["materials"] = {{{"pbrMetallicRoughness", {{"baseColorTexture", {{"index", 0}}}}}}};
         j["meshes"][0]["primitives"][0]["material"] = 0;
       },
       "wide.gltf: images[0] (wide.png): 40000×2 is larger than the texture size limit"},
  };
  for (const Case& c : cases) {
    SCOPED_TRACE(c.file);
    nlohmann::json j = test::quad_model();
    std::string text;
    if (c.edit) {
      c.edit(j);
      text = j.dump();
    } else {
      text = j.dump();
      text = text.substr(0, text.size() - 1) + ",\"extras\":" + test::nested_arrays(100000) + "}";
    }
    test::write_file(d.path(c.file), text);
    auto r = test::run(test::bin("foveal") + " render --scene " + d.path(c.file) + " --size 160x90 --out " + d.path("x.png"));
    EXPECT_EQ(r.exit_code, 2) << r.err;
    EXPECT_NE(r.err.find(c.message), std::string::npos) << r.err;
    EXPECT_FALSE(std::filesystem::exists(d.path("x.png")));
  }
  auto r = test::run(test::bin("foveal") + " render --scene " + d.path("wide.gltf") + " --size 160x90 --out " + d.path("x.png"));
  EXPECT_NE(r.err.find("(GL_MAX_TEXTURE_SIZE)"), std::string::npos) << r.err;
  // The quad itself renders: the cases fail for what was changed, nothing else.
  test::write_file(d.path("quad.gltf"), test::quad_model().dump());
  r = test::run(test::bin("foveal") + " render --scene " + d.path("quad.gltf") + " --size 160x90 --frames 1 --out " + d.path("q.png"));
  EXPECT_EQ(r.exit_code, 0) << r.err;
}

TEST(FoveateCli, ForwardAndInverseMapAPhoto) {
  test::TempDir d;
  auto photo = test::source_path("data/scenes/WaterBottle/WaterBottle_baseColor.png");
  auto r = test::run(test::bin("foveal") + " foveate --in " + photo + " --sigma 2.6 --fovea 0.25,0.75 --json --out " +
                     d.path("o.png") + " --reduced-out " + d.path("r.png"));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  EXPECT_EQ(j["buffer"][0].get<int>(), 788);  // round(2048 / 2.6)
  EXPECT_GT(j["psnr_db"].get<double>(), 20.0);
  EXPECT_TRUE(image::load(d.path("r.png")));
  auto bad = test::run(test::bin("foveal") + " foveate --in " + d.path("none.png") + " --out " + d.path("p.png"));
  EXPECT_EQ(bad.exit_code, 2);
  EXPECT_NE(bad.err.find("none.png"), std::string::npos);
}

TEST(FovealdRender, HeadlessReplayRendersFramesAndASummary) {
  test::TempDir d;
  auto r = test::run("XDG_CONFIG_HOME=" + d.path("cfg") + " " + test::bin("foveald") +
                     " --headless --frames 4 --size 128x72 --scene pattern:noise --no-control --no-shm -q --json --out " +
                     d.path("out"));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto j = nlohmann::json::parse(test::read_file(d.path("out/summary.json")));
  EXPECT_EQ(j["render"]["frames"].get<int>(), 4);
  EXPECT_DOUBLE_EQ(j["render"]["last_frame"]["right"]["sigma"].get<double>(), 2.0);
  EXPECT_DOUBLE_EQ(j["render"]["last_frame"]["left"]["sigma"].get<double>(), 3.0);
  EXPECT_TRUE(image::load(d.path("out/frame_000000.png")));
  EXPECT_TRUE(image::load(d.path("out/frame_000003.png")));
}

TEST(FovealdSoak, FiveMinutesOfGazeAtSpeed100KeepMemoryAndDescriptorsFlat) {
  // The short version of the soak (docs/stability.md has the one-hour command).
  test::TempDir d;
  ASSERT_EQ(test::run(test::bin("foveal") + " synth --seed 5 --duration 300 --out " + d.path("g.csv")).exit_code, 0);
  auto r = test::run("XDG_CONFIG_HOME=" + d.path("cfg") + " " + test::bin("foveald") + " --replay " + d.path("g.csv") +
                     " --speed 100 --size 64x36 --scene pattern:checker --no-control --no-shm -q --json --out " + d.path("out"));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(r.err, "");  // nothing logged at warning level or above
  const auto j = nlohmann::json::parse(test::read_file(d.path("out/summary.json")));
  ASSERT_TRUE(j.contains("resources")) << "fewer than 100 frames rendered";
  EXPECT_EQ(j["samples"].get<int>(), 36000);
  EXPECT_GT(j["render"]["frames"].get<int>(), 200);
  EXPECT_LT(j["resources"]["rss_growth_mb"].get<double>(), 2.0);
  EXPECT_LE(j["resources"]["end"]["fds"].get<int>(), j["resources"]["warm"]["fds"].get<int>());
}

TEST(FovealdCli, DirectModeErrorsNameTheDeviceAndWriteNoFrames) {
  test::TempDir d;
  const std::string common = "XDG_CONFIG_HOME=" + d.path() + " " + test::bin("foveald") +
                             " --scene pattern:checker --no-control --no-shm -q --out " + d.path("out");
  const std::string base = common + " --drm";
  auto missing = test::run(base + " --drm-device " + d.path("card7"));
  EXPECT_NE(missing.exit_code, 0);
  EXPECT_NE(missing.err.find("no DRM device " + d.path("card7")), std::string::npos) << missing.err;
  auto not_drm = test::run(base + " --drm-device /dev/null");
  EXPECT_NE(not_drm.exit_code, 0);
  EXPECT_NE(not_drm.err.find("/dev/null is not a DRM device"), std::string::npos) << not_drm.err;
  EXPECT_FALSE(std::filesystem::exists(d.path("out/frames.csv")));
  auto both = test::run(base + " --window");
  EXPECT_EQ(both.exit_code, 2);
  EXPECT_NE(both.err.find("--drm and --window"), std::string::npos) << both.err;
  auto mode = test::run(base + " --mode 2880x1600@fast");
  EXPECT_EQ(mode.exit_code, 2);
  EXPECT_NE(mode.err.find("--mode '2880x1600@fast'"), std::string::npos) << mode.err;
  // Without a connector of the display model's size there is no headset monitor to find.
  if (std::filesystem::exists("/dev/dri")) GTEST_LOG_(INFO) << "this machine has /dev/dri; --monitor auto not checked";
  else {
    auto monitor = test::run(common + " --window --monitor auto");
    EXPECT_EQ(monitor.exit_code, 2);
    EXPECT_NE(monitor.err.find("--monitor auto: no DRM connector offers the display model's 2880x1600 mode"),
              std::string::npos) << monitor.err;
  }
  auto needs = test::run(test::bin("foveald") + " --connector DP-1");
  EXPECT_EQ(needs.exit_code, 2);
  EXPECT_NE(needs.err.find("--drm"), std::string::npos) << needs.err;
}

TEST(OutputsCli, ListsDrmDevicesAndTheDirectModeChoiceAsJson) {
  auto r = test::run("env -u DISPLAY -u WAYLAND_DISPLAY " + test::bin("foveal") + " outputs --json");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  EXPECT_TRUE(j["drm"].is_array());
  EXPECT_TRUE(j.contains("direct_mode"));
  EXPECT_TRUE(j["monitors"].is_null());  // no window system here
  EXPECT_NE(j["monitors_error"].get<std::string>().find("no display"), std::string::npos) << r.out;
}
