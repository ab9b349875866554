// Scenes: the bundled glTF files load with the features they use; bad files fail
// with messages that name the file.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <functional>

#include "gl_support.hpp"
#include "test_support.hpp"

using namespace foveal;

namespace {
const std::string kBottle = test::source_path("data/scenes/WaterBottle/WaterBottle.gltf");
const std::string kDungeon = test::source_path("data/scenes/Dungeon/dungeon_simplified.gltf");

// A copy of the WaterBottle directory whose .gltf text is edited by `edit`.
std::string edited_bottle(const test::TempDir& d, const std::function<void(std::string&)>& edit) {
  for (const auto& e : std::filesystem::directory_iterator(std::filesystem::path(kBottle).parent_path()))
    std::filesystem::copy(e.path(), d.path(e.path().filename().string()));
  std::string text = test::read_file(kBottle);
  edit(text);
  test::write_file(d.path("WaterBottle.gltf"), text);
  return d.path("WaterBottle.gltf");
}
}  // namespace

TEST(Scene, WaterBottleHasEveryPbrTexture) {
  ASSERT_TRUE(test::gl_ready());
  render::Scene s = test::scene(kBottle);
  ASSERT_EQ(s.materials.size(), 1u);
  const render::Material& m = s.materials[0];
  EXPECT_GE(m.base_color_tex, 0);
  EXPECT_GE(m.metal_rough_tex, 0);
  EXPECT_GE(m.normal_tex, 0);
  EXPECT_GE(m.occlusion_tex, 0);
  EXPECT_GE(m.emissive_tex, 0);
  EXPECT_GT(s.triangles, 4000u);
  EXPECT_EQ(s.view.source, "framing");
}

TEST(Scene, DungeonLoadsWithItsViewFileAndUnlitTorch) {
  ASSERT_TRUE(test::gl_ready());
  render::Scene s = test::scene(kDungeon);
  EXPECT_EQ(s.triangles, 42606u);
  EXPECT_NE(s.view.source.find("view file"), std::string::npos);
  bool unlit = false;
  for (const auto& m : s.materials) unlit |= m.unlit;
  EXPECT_TRUE(unlit);
  // The view file puts the head inside the room's bounds.
  const glm::vec3 eye(s.view.head_to_world[3]);
  EXPECT_TRUE(glm::all(glm::greaterThan(eye, s.bounds.min)) && glm::all(glm::lessThan(eye, s.bounds.max)));
}

// bundled:NAME finds a shipped scene wherever foveal's data is (docs/scenes.md); the name
// chooses a folder of data/scenes and nothing else.
TEST(Scene, BundledNamesLoadTheShippedScenesAndNothingElse) {
  ASSERT_TRUE(test::gl_ready());
  auto dungeon = render::load_scene("bundled:Dungeon");
  ASSERT_TRUE(dungeon) << dungeon.error().message;
  EXPECT_EQ(dungeon->triangles, 42606u);
  EXPECT_NE(dungeon->view.source.find("view file"), std::string::npos) << "its view file comes with it";
  EXPECT_TRUE(render::load_scene("bundled:WaterBottle"));
  const auto names = render::bundled_scene_names();
  EXPECT_NE(std::find(names.begin(), names.end(), "Dungeon"), names.end());
  for (const char* bad : {"bundled:Nope", "bundled:../scenes/Dungeon", "bundled:", "bundled:Dungeon/x"}) {
    auto r = render::load_scene(bad);
    ASSERT_FALSE(r) << bad;
    EXPECT_EQ(r.error().kind, ErrorKind::bad_input) << bad;
    EXPECT_NE(r.error().message.find("bundled: Dungeon, WaterBottle"), std::string::npos) << r.error().message;
  }
}

TEST(Scene, PatternSpecs) {
  ASSERT_TRUE(test::gl_ready());
  for (const std::string& name : render::pattern_names()) EXPECT_TRUE(render::load_scene("pattern:" + name)) << name;
  auto rotated = render::load_scene("pattern:stripes-v@37.5");
  ASSERT_TRUE(rotated);
  EXPECT_FLOAT_EQ(rotated->pattern->angle_deg, 37.5f);
  EXPECT_FALSE(render::load_scene("pattern:nope"));
  EXPECT_FALSE(render::load_scene("pattern:checker@abc"));
}

TEST(Scene, MalformedGltfNamesTheFile) {
  ASSERT_TRUE(test::gl_ready());
  test::TempDir d;
  test::write_file(d.path("broken.gltf"), "{ \"asset\": { \"version\": \"2.0\" }, \"nodes\": [ ");
  auto s = render::load_scene(d.path("broken.gltf"));
  ASSERT_FALSE(s);
  EXPECT_NE(s.error().message.find("broken.gltf"), std::string::npos) << s.error().message;
  auto missing = render::load_scene(d.path("absent.gltf"));
  ASSERT_FALSE(missing);
  EXPECT_NE(missing.error().message.find("absent.gltf"), std::string::npos) << missing.error().message;
}

TEST(Scene, MissingTextureNamesTheImageFile) {
  ASSERT_TRUE(test::gl_ready());
  test::TempDir d;
  const std::string path = edited_bottle(d, [](std::string&) {});
  std::filesystem::remove(d.path("WaterBottle_normal.png"));
  auto s = render::load_scene(path);
  ASSERT_FALSE(s);
  EXPECT_NE(s.error().message.find("WaterBottle_normal.png"), std::string::npos) << s.error().message;
}

TEST(Scene, UnsupportedRequiredExtensionIsRefused) {
  ASSERT_TRUE(test::gl_ready());
  test::TempDir d;
  const std::string path = edited_bottle(d, [](std::string& t) {
    t.replace(t.find('{'), 1, "{ \"extensionsUsed\": [\"KHR_texture_basisu\"], \"extensionsRequired\": [\"KHR_texture_basisu\"],");
  });
  auto s = render::load_scene(path);
  ASSERT_FALSE(s);
  EXPECT_EQ(s.error().kind, ErrorKind::unsupported);
  EXPECT_NE(s.error().message.find("KHR_texture_basisu"), std::string::npos) << s.error().message;
  EXPECT_NE(s.error().message.find("WaterBottle.gltf"), std::string::npos);
}

TEST(Scene, BrokenViewFileNamesIt) {
  ASSERT_TRUE(test::gl_ready());
  test::TempDir d;
  const std::string path = edited_bottle(d, [](std::string&) {});
  test::write_file(d.path("WaterBottle.view.json"), "{\"eye\": [0, 0], \"target\": [0, 0, -1]}");
  auto s = render::load_scene(path);
  ASSERT_FALSE(s);
  EXPECT_NE(s.error().message.find("WaterBottle.view.json"), std::string::npos) << s.error().message;
}
