// KHR_lights_punctual in the loader, without GL: lights placed by their nodes' world
// transforms, every value checked with the light's path in the message.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "gltf_load_json.hpp"
#include "gltf_test_models.hpp"
#include "test_support.hpp"

using namespace foveal;
using nlohmann::json;

namespace {

// The quad plus `lights`, each on a node of its own under a parent translated by (0, 0, 1).
json with_lights(const json& lights) {
  json j = test::quad_model();
  j["extensionsUsed"] = {"KHR_lights_punctual"};
  j["extensions"] = {{"KHR_lights_punctual", {{"lights", lights}}}};
  json children = json::array();
  for (std::size_t i = 0; i < lights.size(); ++i) {
    // Rotated −90° about x: the light's −Z becomes −Y (down); translated to (1, 2, 3) in the parent.
    const double s = std::sqrt(0.5);
    j["nodes"].push_back({{"translation", {1, 2, 3}}, {"rotation", {-s, 0, 0, s}}, {"scale", {2, 2, 2}},
                          {"extensions", {{"KHR_lights_punctual", {{"light", i}}}}}});
    children.push_back(j["nodes"].size() - 1);
  }
  j["nodes"].push_back({{"translation", {0, 0, 1}}, {"children", children}});
  j["scenes"][0]["nodes"].push_back(j["nodes"].size() - 1);
  return j;
}

Result<render::GltfScene> load(const json& j) { return test::load_gltf_json(j, "lights.gltf"); }

void expect_refused(const json& j, const std::string& what) {
  auto r = load(j);
  ASSERT_FALSE(r) << "loaded, expected: " << what;
  EXPECT_EQ(r.error().kind, ErrorKind::bad_input) << r.error().message;
  EXPECT_NE(r.error().message.find("lights.gltf: "), std::string::npos) << r.error().message;
  EXPECT_NE(r.error().message.find(what), std::string::npos) << r.error().message;
}

bool has_warning(const render::GltfScene& s, const std::string& what) {
  for (const std::string& w : s.warnings)
    if (w.find(what) != std::string::npos) return true;
  return false;
}

}  // namespace

TEST(GltfLights, PointSpotAndDirectionalLightsArePlacedByTheirNodesWorldTransforms) {
  const json lights = {
      {{"type", "point"}, {"color", {1.0, 0.5, 0.25}}, {"intensity", 40.0}, {"range", 7.5}},
      {{"type", "spot"}, {"intensity", 3.0}, {"spot", {{"innerConeAngle", 0.2}, {"outerConeAngle", 0.6}}}},
      {{"type", "directional"}, {"intensity", 2.0}, {"range", 5.0}},
  };
  auto s = load(with_lights(lights));
  ASSERT_TRUE(s) << s.error().message;
  ASSERT_EQ(s->lights.size(), 3u);
  EXPECT_FALSE(has_warning(*s, "KHR_lights_punctual")) << "the extension is read, not ignored";
  const render::PunctualLight& p = s->lights[0];
  EXPECT_EQ(p.type, render::PunctualLight::Type::point);
  EXPECT_EQ(p.index, 0);
  EXPECT_FLOAT_EQ(p.intensity, 40.0f);
  EXPECT_FLOAT_EQ(p.range, 7.5f);  // not scaled by the node's scale 2
  EXPECT_FLOAT_EQ(p.color.g, 0.5f);
  EXPECT_NEAR(p.position.x, 1.0f, 1e-6f);
  EXPECT_NEAR(p.position.y, 2.0f, 1e-6f);
  EXPECT_NEAR(p.position.z, 4.0f, 1e-6f);  // the parent's z + 1
  const render::PunctualLight& spot = s->lights[1];
  EXPECT_EQ(spot.type, render::PunctualLight::Type::spot);
  EXPECT_FLOAT_EQ(spot.range, 0.0f) << "no range: no cutoff";
  EXPECT_FLOAT_EQ(spot.inner_cone, 0.2f);
  EXPECT_FLOAT_EQ(spot.outer_cone, 0.6f);
  EXPECT_NEAR(spot.direction.x, 0.0f, 1e-6f);
  EXPECT_NEAR(spot.direction.y, -1.0f, 1e-6f) << "the node's −Z, rotated down, unit length despite the scale";
  EXPECT_NEAR(spot.direction.z, 0.0f, 1e-6f);
  EXPECT_EQ(s->lights[2].type, render::PunctualLight::Type::directional);
  EXPECT_FLOAT_EQ(s->lights[2].range, 0.0f) << "range is ignored for directional lights";
  // A spot without angles gets the specification's defaults 0 and π/4.
  auto d = load(with_lights({{{"type", "spot"}, {"spot", json::object()}}}));
  ASSERT_TRUE(d) << d.error().message;
  EXPECT_FLOAT_EQ(d->lights[0].inner_cone, 0.0f);
  EXPECT_NEAR(d->lights[0].outer_cone, std::numbers::pi / 4, 1e-6);
  EXPECT_FLOAT_EQ(d->lights[0].intensity, 1.0f);
}

TEST(GltfLights, AFileWithoutLightsHasNoneAndAColourAboveOneIsAWarning) {
  auto none = load(test::quad_model());
  ASSERT_TRUE(none) << none.error().message;
  EXPECT_TRUE(none->lights.empty());
  auto bright = load(with_lights({{{"type", "point"}, {"color", {1.5, 1, 1}}}}));
  ASSERT_TRUE(bright) << bright.error().message;
  EXPECT_TRUE(has_warning(*bright, "extensions.KHR_lights_punctual.lights[0].color[0]: 1.5 is above 1"));
}

TEST(GltfLights, BadValuesAreRefusedNamingTheLight) {
  const std::string l0 = "extensions.KHR_lights_punctual.lights[0]";
  expect_refused(with_lights({{{"intensity", 1.0}}}), l0 + ": 'type' is missing");
  expect_refused(with_lights({{{"type", "area"}}}), l0 + ".type: \"area\" is not one of directional, point, spot");
  expect_refused(with_lights({{{"type", "point"}, {"intensity", -1.0}}}), l0 + ".intensity: -1.0 is negative");
  // Issue 38 item 15: 3e38 overflowed the shader's floats and lit the surface black.
  expect_refused(with_lights({{{"type", "point"}, {"intensity", 3e38}}}), l0 + ".intensity: 3e+38 is beyond 1e9");
  expect_refused(with_lights({{{"type", "point"}, {"intensity", "x"}}}), l0 + ".intensity: must be a finite number");
  expect_refused(with_lights({{{"type", "point"}, {"range", 0.0}}}), l0 + ".range: 0.0 is not greater than 0");
  expect_refused(with_lights({{{"type", "point"}, {"color", {1, 1}}}}), l0 + ".color: must be an array of 3 numbers");
  expect_refused(with_lights({{{"type", "point"}, {"color", {1, -0.5, 1}}}}), l0 + ".color[1]: -0.5 is negative");
  expect_refused(with_lights({{{"type", "spot"}}}), l0 + ".spot: a spot light needs a 'spot' object");
  expect_refused(with_lights({{{"type", "spot"}, {"spot", {{"innerConeAngle", 0.5}, {"outerConeAngle", 0.5}}}}}),
                 l0 + ".spot.innerConeAngle: 0.500000 is not less than outerConeAngle 0.500000");
  expect_refused(with_lights({{{"type", "spot"}, {"spot", {{"innerConeAngle", -0.1}}}}}), l0 + ".spot.innerConeAngle: -0.100000 is negative");
  expect_refused(with_lights({{{"type", "spot"}, {"spot", {{"outerConeAngle", 2.0}}}}}), l0 + ".spot.outerConeAngle: 2.000000 is more than pi/2");
  // The node's reference.
  json j = with_lights({{{"type", "point"}}});
  j["nodes"][1]["extensions"]["KHR_lights_punctual"]["light"] = 3;
  expect_refused(j, "nodes[1].extensions.KHR_lights_punctual.light: 3 is out of range (1 lights)");
  j["nodes"][1]["extensions"]["KHR_lights_punctual"] = json::object();
  expect_refused(j, "nodes[1].extensions.KHR_lights_punctual: 'light' is missing");
  json k = with_lights({{{"type", "point"}}});
  k["extensions"]["KHR_lights_punctual"] = {{"lights", "none"}};
  expect_refused(k, "extensions.KHR_lights_punctual.lights: must be an array of lights");
  // A spot light whose node's scale flattens −Z has no direction.
  json z = with_lights({{{"type", "spot"}, {"spot", json::object()}}});
  z["nodes"][1].erase("rotation");
  z["nodes"][1]["scale"] = {1, 1, 0};
  expect_refused(z, "nodes[1]: the transform of its light (KHR_lights_punctual.lights[0]) has no −Z direction");
}

TEST(GltfLights, RequiringTheExtensionIsAccepted) {
  json j = with_lights({{{"type", "point"}}});
  j["extensionsRequired"] = {"KHR_lights_punctual"};
  auto s = load(j);
  ASSERT_TRUE(s) << s.error().message;
  EXPECT_EQ(s->lights.size(), 1u);
}

// tools/scenes/point_lights.py: the benchmark scene's lights load, inside the scene's bounds.
TEST(GltfLights, ThePointLightsScriptWritesADungeonCopyWithItsLights) {
  test::TempDir dir;
  const std::string src = test::source_path("data/scenes/Dungeon/dungeon_simplified.gltf");
  auto r = test::run("python3 " + test::source_path("tools/scenes/point_lights.py") + " " + src + " " + dir.path("out") + " --lights 8");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  test::NullGltfSink sink;
  auto s = render::load_gltf(dir.path("out/dungeon_simplified_lights8.gltf"), {}, sink);
  ASSERT_TRUE(s) << s.error().message;
  ASSERT_EQ(s->lights.size(), 8u);
  EXPECT_GT(sink.textures, 0) << "the copy reads the original's images";
  for (const render::PunctualLight& l : s->lights) {
    EXPECT_EQ(l.type, render::PunctualLight::Type::point);
    EXPECT_NEAR(l.range, 0.35f * 2.0f * s->bounds.radius(), 1e-4f * l.range) << "the rig's range";
    for (int k = 0; k < 3; ++k) {
      EXPECT_GT(l.position[k], s->bounds.min[k]);
      EXPECT_LT(l.position[k], s->bounds.max[k]);
    }
  }
  EXPECT_NE(test::run("python3 " + test::source_path("tools/scenes/point_lights.py") + " " + src + " " + dir.path("x") + " --lights 65").exit_code, 0);
}
