// KHR_lights_punctual in the frame (docs/scenes.md, "Lights"): a white Lambertian-like
// plane (base colour 1, metallic 0, roughness 1) at z = 0 filling the view from a camera
// at z = 3, lit by one file light, output read as float (linear, after the tone map).
// Expected values: radiance L = f·E with f·(n·l) = (0.96 + 0.01)/π at normal incidence
// and view (diffuse (1 − F0)/π plus GGX at roughness 1: D = 1/π, V = 1/4, F0 = 0.04) and
// illuminance E = I/d² (point, spot; × the range window) or E = I (directional); the
// output is the ACES fit of L (exposure 1, no ambient). Each case runs in both
// pipelines, full and RMFR σ 2; without the light the rig lights the plane instead.
// Last, the per-tile light lists against every light at every sample.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <string>

#include <glm/gtc/matrix_transform.hpp>
#include <nlohmann/json.hpp>

#include "foveal/render/light_tiles.hpp"
#include "gl_support.hpp"
#include "gltf_test_models.hpp"
#include "khronos_models.hpp"
#include "test_support.hpp"

using namespace foveal;
using nlohmann::json;

namespace {

constexpr int kWidth = 256, kHeight = 128;
constexpr double kPi = 3.14159265358979;
constexpr double kBrdfNormal = 0.97 / kPi;  // f·(n·l) at l = v = n (header)

double aces(double x) { return x * (2.51 * x + 0.03) / (x * (2.43 * x + 0.59) + 0.14); }

struct Plane {
  json light;                       // the KHR_lights_punctual light; null: none
  json light_node = json::object();  // its node's transform
  std::string alpha_mode = "OPAQUE";
};

std::string write_scene(test::TempDir& dir, const std::string& name, const Plane& p) {
  json j = test::quad_model();
  const double half = 40.0;
  j["cameras"] = {{{"type", "perspective"}, {"perspective", {{"yfov", 1.0}, {"znear", 0.1}}}}};
  j["materials"] = {{{"pbrMetallicRoughness", {{"baseColorFactor", {1, 1, 1, 1}}, {"metallicFactor", 0.0}, {"roughnessFactor", 1.0}}},
                     {"alphaMode", p.alpha_mode}}};
  j["meshes"][0]["primitives"][0]["material"] = 0;
  j["nodes"] = {{{"camera", 0}, {"translation", {0, 0, 3}}},
                {{"mesh", 0}, {"translation", {-half, -half, 0}}, {"scale", {2 * half, 2 * half, 1}}}};
  j["scenes"] = {{{"nodes", {0, 1}}}};
  if (!p.light.is_null()) {
    j["extensionsUsed"] = {"KHR_lights_punctual"};
    j["extensions"] = {{"KHR_lights_punctual", {{"lights", {p.light}}}}};
    json node = p.light_node;
    node["extensions"] = {{"KHR_lights_punctual", {{"light", 0}}}};
    j["nodes"].push_back(node);
    j["scenes"][0]["nodes"].push_back(2);
  }
  const std::string path = dir.path(name + ".gltf");
  test::write_file(path, j.dump());
  return path;
}

struct Case {
  render::Pipeline pipeline;
  render::Method method;
  double sigma;
};
const Case kCases[] = {{render::Pipeline::gbuffer, render::Method::full, 1.0},
                       {render::Pipeline::gbuffer, render::Method::rmfr, 2.0},
                       {render::Pipeline::visibility, render::Method::full, 1.0},
                       {render::Pipeline::visibility, render::Method::rmfr, 2.0}};

std::string describe(const Case& c) {
  return std::string(render::pipeline_name(c.pipeline)) + " " + render::method_name(c.method);
}

// The output as read_float gives it: linear RGBA after the tone map, bottom row first.
struct Frame {
  std::vector<float> px;
  float at(int x, int y, int c) const { return px[(static_cast<std::size_t>(y) * kWidth + static_cast<std::size_t>(x)) * 4 + static_cast<std::size_t>(c)]; }
  // The largest value of channel c in eye e (the pixel under a light pointing down).
  float eye_max(int e, int c) const {
    float m = 0;
    for (int y = 0; y < kHeight; ++y)
      for (int x = e * kWidth / 2; x < (e + 1) * kWidth / 2; ++x) m = std::max(m, at(x, y, c));
    return m;
  }
  float centre(int e, int c) const { return at(e * kWidth / 2 + kWidth / 4, kHeight / 2, c); }
};

Frame render_case(const std::string& spec, const Case& c) {
  render::Compositor comp = test::make_compositor(kWidth, kHeight, true);
  render::Scene s = test::scene(spec);
  render::FrameParams p = test::frame(c.method, c.sigma);
  p.pipeline = c.pipeline;
  auto t = comp.render(s, p);
  EXPECT_TRUE(t) << (t ? "" : t.error().message);
  return {comp.read_float()};
}

const json kDown = {{"translation", {0, 0, 1.5}}};  // 1.5 above the plane's centre; −Z points at it

}  // namespace

TEST(Lights, APointLightGivesTheInverseSquareRadianceUnderItAndRemovingItChangesTheImage) {
  ASSERT_TRUE(test::gl_ready());
  test::TempDir dir;
  const double intensity = 2.0, d = 1.5;
  const std::string lit = write_scene(dir, "point", {{{"type", "point"}, {"intensity", intensity}}, kDown});
  const std::string unlit = write_scene(dir, "none", {});
  const double expected = aces(kBrdfNormal * intensity / (d * d));
  for (const Case& c : kCases) {
    const Frame f = render_case(lit, c), rig = render_case(unlit, c);
    for (int e = 0; e < 2; ++e) {
      for (int ch = 0; ch < 3; ++ch)
        EXPECT_NEAR(f.eye_max(e, ch), expected, 0.015 * expected) << describe(c) << " eye " << e << " channel " << ch;
      // The rig (its sun, points and ambient) lights the plane otherwise.
      EXPECT_GT(std::fabs(rig.centre(e, 0) - f.centre(e, 0)), 0.05) << describe(c) << " eye " << e;
    }
  }
}

TEST(Lights, BeyondItsRangeAPointLightGivesNothingAndInsideTheWindowScalesIt) {
  ASSERT_TRUE(test::gl_ready());
  test::TempDir dir;
  const double d = 1.5, range = 1.8;
  const std::string cut = write_scene(dir, "cut", {{{"type", "point"}, {"intensity", 2.0}, {"range", 1.4}}, kDown});
  const std::string window = write_scene(dir, "window", {{{"type", "point"}, {"intensity", 2.0}, {"range", range}}, kDown});
  const double w = 1.0 - std::pow(d / range, 4.0);  // max(min(1 − (d/range)⁴, 1), 0)
  const double expected = aces(kBrdfNormal * 2.0 / (d * d) * w);
  for (const Case& c : kCases) {
    const Frame none = render_case(cut, c), f = render_case(window, c);
    for (int e = 0; e < 2; ++e) {
      EXPECT_EQ(none.eye_max(e, 0), 0.0f) << describe(c) << ": the nearest point is 1.5 away, past the range 1.4";
      EXPECT_NEAR(f.eye_max(e, 0), expected, 0.02 * expected) << describe(c) << " eye " << e;
    }
  }
}

TEST(Lights, ASpotIsFullInsideItsInnerConeAndDarkOutsideItsOuterCone) {
  ASSERT_TRUE(test::gl_ready());
  test::TempDir dir;
  const std::string point = write_scene(dir, "point", {{{"type", "point"}, {"intensity", 2.0}}, kDown});
  const std::string spot = write_scene(
      dir, "spot", {{{"type", "spot"}, {"intensity", 2.0}, {"spot", {{"innerConeAngle", 0.2}, {"outerConeAngle", 0.35}}}}, kDown});
  // Turned 180° about x (pointing up, away from the plane): every point is outside the outer cone.
  const std::string up = write_scene(dir, "up",
                                     {{{"type", "spot"}, {"intensity", 2.0}, {"spot", {{"innerConeAngle", 0.2}, {"outerConeAngle", 0.35}}}},
                                      {{"translation", {0, 0, 1.5}}, {"rotation", {1, 0, 0, 0}}}});
  for (const Case& c : kCases) {
    const Frame p = render_case(point, c), f = render_case(spot, c), away = render_case(up, c);
    for (int e = 0; e < 2; ++e) {
      // Inside the inner cone (under the light) the spot is the point light.
      EXPECT_NEAR(f.eye_max(e, 0), p.eye_max(e, 0), 0.005) << describe(c) << " eye " << e;
      // The eye's corners are 60° and more off the axis: the point light reaches them, the spot does not.
      for (int y : {2, kHeight - 3}) {
        const int x = e * kWidth / 2 + 2;
        EXPECT_GT(p.at(x, y, 0), 0.0f) << describe(c);
        EXPECT_EQ(f.at(x, y, 0), 0.0f) << describe(c) << " eye " << e << " y " << y;
      }
      EXPECT_EQ(away.eye_max(e, 0), 0.0f) << describe(c) << ": a spot pointing away lights nothing";
    }
  }
}

TEST(Lights, ADirectionalLightGivesItsIlluminanceTimesItsColourEverywhereAndInTheBlendPass) {
  ASSERT_TRUE(test::gl_ready());
  test::TempDir dir;
  const double lux = 0.8;
  const json sun = {{"type", "directional"}, {"intensity", lux}, {"color", {1.0, 0.5, 0.25}}, {"range", 0.01}};
  const std::string opaque = write_scene(dir, "sun", {sun, json::object()});
  Plane blended{sun, json::object(), "BLEND"};  // α 1: the forward pass's colour exactly
  const std::string blend = write_scene(dir, "sun_blend", blended);
  for (const Case& c : kCases) {
    const Frame f = render_case(opaque, c), b = render_case(blend, c);
    for (int e = 0; e < 2; ++e)
      for (int ch = 0; ch < 3; ++ch) {
        const double expected = aces(kBrdfNormal * lux * std::array{1.0, 0.5, 0.25}[static_cast<std::size_t>(ch)]);
        EXPECT_NEAR(f.centre(e, ch), expected, 0.01 * expected) << describe(c) << " eye " << e << " channel " << ch;
        EXPECT_NEAR(b.centre(e, ch), expected, 0.01 * expected) << describe(c) << " blend pass, eye " << e << " channel " << ch;
      }
  }
}

TEST(Lights, RenderJsonSaysWhetherTheFileOrTheRigLightsTheScene) {
  test::TempDir dir;
  const std::string lit = write_scene(dir, "point", {{{"type", "point"}, {"intensity", 2.0}}, kDown});
  const std::string unlit = write_scene(dir, "none", {});
  const std::string base = test::bin("foveal") + " render --size 64x32 --frames 1 --warmup 0 --json --out " + dir.path("f.png") + " --scene ";
  auto a = test::run(base + lit), b = test::run(base + unlit);
  ASSERT_EQ(a.exit_code, 0) << a.err;
  ASSERT_EQ(b.exit_code, 0) << b.err;
  const json ja = json::parse(a.out), jb = json::parse(b.out);
  EXPECT_EQ(ja["lights"]["source"], "file");
  EXPECT_EQ(ja["lights"]["count"], 1);
  EXPECT_EQ(jb["lights"]["source"], "rig");
  EXPECT_EQ(jb["lights"]["count"], 65);  // 64 points and the sun
  for (const json& w : ja["warnings"]) EXPECT_EQ(w.get<std::string>().find("KHR_lights_punctual"), std::string::npos) << w;
}

// Per-tile light lists (light_tiles.hpp): a light's tiles hold its range sphere's screen
// rectangle, and lighting through the lists is the image of every light at every sample.
TEST(LightTiles, ASphereInFrontCoversItsProjectionAndOneBehindTheEyeEverything) {
  const glm::mat4 proj = glm::perspective(1.0f, 1.0f, 0.1f, 100.0f);  // eye at the origin looking down −z
  const glm::ivec4 centre = render::sphere_screen_rect({0, 0, -10}, 1.0f, proj, 100, 100);
  EXPECT_LE(centre.x, 45);
  EXPECT_GE(centre.z, 55);
  EXPECT_GT(centre.x, 30) << "a 1-unit sphere at 10 units covers far less than the screen";
  EXPECT_LT(centre.z, 70);
  EXPECT_EQ(render::sphere_screen_rect({0, 0, 0.5f}, 1.0f, proj, 100, 100), glm::ivec4(0, 0, 100, 100)) << "the eye is inside";
  const glm::ivec4 off = render::sphere_screen_rect({50, 0, -10}, 1.0f, proj, 100, 100);
  EXPECT_TRUE(off.x >= off.z) << "off screen: no tiles";
  render::PunctualLight near, far, unbounded;
  near.position = {0, 0, -10}, near.range = 1.0f;
  far.position = {50, 0, -10}, far.range = 1.0f;
  unbounded.position = {50, 0, -10};
  const render::LightTiles t = render::build_light_tiles({near, far, unbounded}, 3, proj, 100, 100, 16);
  EXPECT_EQ(t.cols, 7);
  EXPECT_EQ(t.rows, 7);
  auto list = [&](int x, int y) {
    const std::size_t k = static_cast<std::size_t>(y * t.cols + x);
    return std::vector<std::uint32_t>(t.data.begin() + t.data[2 * k], t.data.begin() + t.data[2 * k] + t.data[2 * k + 1]);
  };
  EXPECT_EQ(list(3, 3), (std::vector<std::uint32_t>{0, 2})) << "the centre tile: the near light and the one without range";
  EXPECT_EQ(list(0, 0), (std::vector<std::uint32_t>{2}));
}

TEST(LightTiles, LightingThroughTheListsIsLightingWithEveryLightInBothPipelines) {
  ASSERT_TRUE(test::gl_ready());
  test::TempDir dir;
  // Three short-range lights over different parts of the plane and one without a range.
  json j = json::parse(test::read_file(write_scene(dir, "base", {{{"type", "point"}, {"intensity", 0.3}}, kDown})));
  for (double x : {-1.5, 0.0, 1.5}) {
    j["extensions"]["KHR_lights_punctual"]["lights"].push_back({{"type", "point"}, {"intensity", 1.0}, {"range", 1.2}});
    j["nodes"].push_back({{"translation", {x, 0.5 * x, 0.4}}, {"extensions", {{"KHR_lights_punctual", {{"light", j["extensions"]["KHR_lights_punctual"]["lights"].size() - 1}}}}}});
    j["scenes"][0]["nodes"].push_back(j["nodes"].size() - 1);
  }
  const std::string path = dir.path("four.gltf");
  test::write_file(path, j.dump());
  render::Scene s = test::scene(path);
  ASSERT_EQ(s.lights.size(), 4u);
  for (const Case& c : kCases) {
    std::vector<float> images[2];
    for (int tiled = 0; tiled < 2; ++tiled) {
      render::CompositorOptions o;
      o.width = kWidth, o.height = kHeight, o.float_output = true, o.light_tiles = tiled == 1;
      auto comp = render::Compositor::create(o, test::source_shaders());
      ASSERT_TRUE(comp) << comp.error().message;
      render::FrameParams p = test::frame(c.method, c.sigma);
      p.pipeline = c.pipeline;
      auto t = comp->render(s, p);
      ASSERT_TRUE(t) << t.error().message;
      images[tiled] = comp->read_float();
    }
    double worst = 0;
    for (std::size_t k = 0; k < images[0].size(); ++k) worst = std::max(worst, std::fabs(double(images[0][k]) - images[1][k]));
    EXPECT_LE(worst, 1e-6) << describe(c) << ": the lists leave out only lights that add nothing";
    EXPECT_GT(*std::max_element(images[1].begin(), images[1].end()), 0.2f) << describe(c) << ": the short-range lights light the plane";
  }
}

// The Khronos LightsPunctualLamp (tests/render/data/khronos): five point lights of its own,
// warm ones (colour (1, 0.63, 0.24) at 15 cd in the shade, (1, 0.63, 0.5) at 180 cd in
// front) and two teal ones at 80 cd. Lit by them the brass frame shows warm highlights,
// which the rig's white lights (the file without KHR_lights_punctual) do not give it.
// Both pipelines, full and RMFR.
TEST(Lights, LightsPunctualLampIsLitByItsOwnLights) {
  ASSERT_TRUE(test::gl_ready());
  test::TempDir dir;
  const std::string with = test::khronos("LightsPunctualLamp");
  const std::string without = test::edited(dir, with, [](json& j) { test::strip_extension(j, "KHR_lights_punctual"); });
  render::Scene file_lit = test::scene(with), rig_lit = test::scene(without);
  ASSERT_EQ(file_lit.lights.size(), 5u);
  EXPECT_TRUE(rig_lit.lights.empty());
  // Warm, bright pixels of the left eye.
  auto warm = [](const image::Image& img) {
    int n = 0;
    for (int y = 0; y < img.height; ++y)
      for (int x = 0; x < img.width / 2; ++x) {
        const std::uint8_t* p = img.at(x, y);
        n += (p[0] > 150 && p[0] > p[2] + 60) ? 1 : 0;
      }
    return n;
  };
  render::Compositor comp = test::make_compositor(512, 256);
  for (const Case& c : kCases) {
    render::FrameParams p = test::frame(c.method, c.sigma);
    p.pipeline = c.pipeline;
    const int a = warm(test::render_frame(comp, file_lit, p)), b = warm(test::render_frame(comp, rig_lit, p));
    // Measured 430-489 against 38-82.
    EXPECT_GT(a, 3 * b + 100) << describe(c) << ": warm pixels lit by the file's lights (" << a << ") and by the rig (" << b << ")";
  }
}
