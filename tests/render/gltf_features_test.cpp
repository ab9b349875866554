// The Khronos feature-test models (../shared/data/scenes/khronos, SOURCE.md there) render
// as their READMEs say a correct viewer shows them. Each test also renders the model with
// the feature taken out of its JSON, so it can fail: the feature must make the
// difference the README describes.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <functional>

#include <nlohmann/json.hpp>

#include "gl_support.hpp"
#include "test_support.hpp"

using namespace foveal;
using nlohmann::json;

namespace {

constexpr int kWidth = 1024, kHeight = 512;  // 512×512 per eye

std::string khronos(const std::string& model) {
  return test::shared_data("scenes/khronos/" + model + "/glTF/" + model + ".gltf");
}

// A copy of the glTF (and every file beside it) in `dir`, its JSON passed through `edit`.
std::string edited(test::TempDir& dir, const std::string& gltf, const std::function<void(json&)>& edit) {
  const std::filesystem::path src(gltf);
  for (const auto& f : std::filesystem::directory_iterator(src.parent_path()))
    std::filesystem::copy_file(f.path(), dir.path(f.path().filename().string()));
  const std::string out = dir.path(src.filename().string());
  json j = json::parse(std::ifstream(out));
  edit(j);
  test::write_file(out, j.dump());
  return out;
}

image::Image render_model(const std::string& spec, render::Method m = render::Method::full) {
  render::Compositor c = test::make_compositor(kWidth, kHeight);
  render::Scene s = test::scene(spec);
  return test::render_frame(c, s, test::frame(m, 1.0));
}

// Pixels of the left eye for which `pred(r, g, b)` holds.
int count(const image::Image& img, const std::function<bool(int, int, int)>& pred) {
  int n = 0;
  for (int y = 0; y < img.height; ++y)
    for (int x = 0; x < img.width / 2; ++x) {
      const std::uint8_t* p = img.at(x, y);
      n += pred(p[0], p[1], p[2]) ? 1 : 0;
    }
  return n;
}

void strip_extension(json& j, const std::string& ext) {
  std::function<void(json&)> walk = [&](json& v) {
    if (v.is_object()) {
      if (v.contains("extensions")) v["extensions"].erase(ext);
      for (auto& [k, x] : v.items()) walk(x);
    } else if (v.is_array()) {
      for (auto& x : v) walk(x);
    }
  };
  walk(j);
  for (const char* list : {"extensionsUsed", "extensionsRequired"})
    if (j.contains(list)) {
      json kept = json::array();
      for (const auto& e : j[list])
        if (e != ext) kept.push_back(e);
      j[list] = kept;
    }
}

bool yellow(int r, int g, int b) { return r > 150 && g > 150 && b < 100; }

}  // namespace

// README: the top row shows the U, V and UV check tiles (green, blue, cyan) where the
// offsets are applied and a yellow image where not; the arrows point to the green marker
// (the yellow marker: rotation/scale not applied).
TEST(GltfFeatures, TextureTransformShowsTheCorrectMarks) {
  ASSERT_TRUE(test::gl_ready());
  const image::Image ok = render_model(khronos("TextureTransformTest"));
  test::TempDir d;
  const image::Image off = render_model(edited(d, khronos("TextureTransformTest"), [](json& j) { strip_extension(j, "KHR_texture_transform"); }));
  const int yellow_ok = count(ok, yellow), yellow_off = count(off, yellow);
  const int green_ok = count(ok, [](int r, int g, int b) { return g > 120 && r < 60 && b < 60; });
  const int blue_ok = count(ok, [](int r, int g, int b) { return b > 120 && r < 40 && g < 40; });
  const int cyan_ok = count(ok, [](int r, int g, int b) { return g > 120 && b > 120 && r < 60; });
  EXPECT_GT(yellow_off, 4 * yellow_ok) << "yellow 'not applied' area with / without the transform: " << yellow_ok << " / " << yellow_off;
  EXPECT_GT(green_ok, 2000);
  EXPECT_GT(blue_ok, 2000);
  EXPECT_GT(cyan_ok, 2000);
  EXPECT_LT(image::psnr(ok, off), 25.0);
}

// README: every input (base colour, emission, normal, metal-rough, occlusion) is
// transformed, and TEXCOORD_1 is used where a texture says so. Taking the transform off
// any one slot, or TEXCOORD_1 away, must change the picture.
TEST(GltfFeatures, TextureTransformAppliesToEverySlotAndTexCoord1) {
  ASSERT_TRUE(test::gl_ready());
  const std::string model = khronos("TextureTransformMultiTest");
  const image::Image ok = render_model(model);
  const std::vector<std::pair<std::string, std::function<json*(json&)>>> slots = {
      {"baseColorTexture", [](json& m) { return m.contains("pbrMetallicRoughness") && m["pbrMetallicRoughness"].contains("baseColorTexture") ? &m["pbrMetallicRoughness"]["baseColorTexture"] : nullptr; }},
      {"metallicRoughnessTexture", [](json& m) { return m.contains("pbrMetallicRoughness") && m["pbrMetallicRoughness"].contains("metallicRoughnessTexture") ? &m["pbrMetallicRoughness"]["metallicRoughnessTexture"] : nullptr; }},
      {"normalTexture", [](json& m) { return m.contains("normalTexture") ? &m["normalTexture"] : nullptr; }},
      {"occlusionTexture", [](json& m) { return m.contains("occlusionTexture") ? &m["occlusionTexture"] : nullptr; }},
      {"emissiveTexture", [](json& m) { return m.contains("emissiveTexture") ? &m["emissiveTexture"] : nullptr; }},
  };
  for (const auto& [name, slot] : slots) {
    test::TempDir d;
    int stripped = 0;
    const image::Image off = render_model(edited(d, model, [&](json& j) {
      for (json& m : j["materials"])
        if (json* t = slot(m); t && t->contains("extensions") && (*t)["extensions"].contains("KHR_texture_transform"))
          (*t)["extensions"].erase("KHR_texture_transform"), ++stripped;
    }));
    EXPECT_GT(stripped, 0) << name;
    EXPECT_GT(image::max_abs_diff(ok, off), 12) << name << ": its transform makes no visible difference";
  }
  test::TempDir d;
  const image::Image uv0 = render_model(edited(d, model, [](json& j) {
    std::function<void(json&)> walk = [&](json& v) {
      if (v.is_object()) {
        if (v.contains("texCoord") && v["texCoord"] == 1) v["texCoord"] = 0;
        for (auto& [k, x] : v.items()) walk(x);
      } else if (v.is_array()) {
        for (auto& x : v) walk(x);
      }
    };
    walk(j["materials"]);
  }));
  EXPECT_LT(image::psnr(ok, uv0), 40.0) << "TEXCOORD_1 makes no difference";
}

// README: with COLOR_0 applied the test row shows clean red, green and blue checks; a
// viewer that ignores it shows cyan, magenta and yellow crosses over them.
TEST(GltfFeatures, VertexColoursRemoveTheCrosses) {
  ASSERT_TRUE(test::gl_ready());
  auto crosses = [](const image::Image& img) {
    return count(img, [](int r, int g, int b) { return (g > 100 && b > 100 && r < 50) || (r > 100 && b > 100 && g < 50) || yellow(r, g, b); });
  };
  const image::Image ok = render_model(khronos("VertexColorTest"));
  test::TempDir d;
  const image::Image off = render_model(edited(d, khronos("VertexColorTest"), [](json& j) {
    for (json& m : j["meshes"])
      for (json& p : m["primitives"]) p["attributes"].erase("COLOR_0");
  }));
  EXPECT_GT(crosses(off), 500);
  EXPECT_LT(crosses(ok), crosses(off) / 10) << "crosses with / without COLOR_0: " << crosses(ok) << " / " << crosses(off);
}

// README: the five cubes are progressively brighter to the right (1×, 2×, 4×, 8×, 16×);
// without the extension they all emit the same colour. The cubes are found as the pixels
// that change when every emissive factor is zeroed.
TEST(GltfFeatures, EmissiveStrengthsAreOrdered) {
  ASSERT_TRUE(test::gl_ready());
  const image::Image ok = render_model(khronos("EmissiveStrengthTest"));
  test::TempDir d;
  const image::Image dark = render_model(edited(d, khronos("EmissiveStrengthTest"), [](json& j) {
    for (json& m : j["materials"]) m.erase("emissiveFactor");
  }));
  // Columns of the left eye where some pixel changed, grouped into runs: one per cube.
  std::vector<std::array<double, 2>> cubes;  // sum of red, pixels
  bool in_run = false;
  for (int x = 0; x < kWidth / 2; ++x) {
    double red = 0, n = 0;
    for (int y = 0; y < kHeight; ++y) {
      const std::uint8_t *a = ok.at(x, y), *b = dark.at(x, y);
      if (std::abs(a[0] - b[0]) + std::abs(a[1] - b[1]) + std::abs(a[2] - b[2]) > 30) red += a[0], ++n;
    }
    if (n > 0 && !in_run) cubes.push_back({0, 0});
    if (n > 0) cubes.back()[0] += red, cubes.back()[1] += n;
    in_run = n > 0;
  }
  ASSERT_EQ(cubes.size(), 5u);
  for (std::size_t i = 1; i < cubes.size(); ++i)
    EXPECT_GT(cubes[i][0] / cubes[i][1], cubes[i - 1][0] / cubes[i - 1][1] + 5.0) << "cube " << i << " is not brighter than cube " << i - 1;
}

// README: the sparse accessor moves three vertices up into peaks; without it the strip is flat.
TEST(GltfFeatures, SparseAccessorRaisesThePeaks) {
  ASSERT_TRUE(test::gl_ready());
  auto aspect = [](const image::Image& img) {
    const std::uint8_t* bg = img.at(0, 0);
    int x0 = img.width, x1 = -1, y0 = img.height, y1 = -1;
    for (int y = 0; y < img.height; ++y)
      for (int x = 0; x < img.width / 2; ++x) {
        const std::uint8_t* p = img.at(x, y);
        if (std::abs(p[0] - bg[0]) + std::abs(p[1] - bg[1]) + std::abs(p[2] - bg[2]) > 30)
          x0 = std::min(x0, x), x1 = std::max(x1, x), y0 = std::min(y0, y), y1 = std::max(y1, y);
      }
    return x1 > x0 ? static_cast<double>(y1 - y0) / (x1 - x0) : 0.0;
  };
  test::TempDir d;
  const image::Image flat = render_model(edited(d, khronos("SimpleSparseAccessor"), [](json& j) {
    for (json& a : j["accessors"]) a.erase("sparse"), a.erase("min"), a.erase("max");
  }));
  const double peaks = aspect(render_model(khronos("SimpleSparseAccessor"))), strip = aspect(flat);
  EXPECT_GT(peaks, 0.4) << "height / width of the model on screen";
  EXPECT_LT(strip, 0.25);
}

// The emissive texture reads TEXCOORD_1: dropping that attribute changes the picture and
// is reported (TEXCOORD_0 is used instead).
TEST(GltfFeatures, SecondUvSetIsUsed) {
  ASSERT_TRUE(test::gl_ready());
  const image::Image ok = render_model(khronos("MultiUVTest"));
  test::TempDir d;
  const std::string path = edited(d, khronos("MultiUVTest"), [](json& j) {
    for (json& m : j["meshes"])
      for (json& p : m["primitives"]) p["attributes"].erase("TEXCOORD_1");
  });
  auto s = render::load_scene(path);
  ASSERT_TRUE(s) << s.error().message;
  ASSERT_EQ(s->warnings.size(), 1u);
  EXPECT_NE(s->warnings[0].find("TEXCOORD_1"), std::string::npos) << s->warnings[0];
  EXPECT_LT(image::psnr(ok, render_model(path)), 40.0);
}

// Draco and quantized variants of the same model render like the plain one
// (tests/render/data/khronos, SOURCE.md there).
TEST(GltfFeatures, DracoAndQuantizedMatchThePlainModel) {
  ASSERT_TRUE(test::gl_ready());
  const std::string data = test::source_path("tests/render/data/khronos/");
  const image::Image box = render_model(data + "Box/glTF/Box.gltf");
  EXPECT_GT(image::psnr(box, render_model(data + "Box/glTF-Draco/Box.gltf")), 35.0);
  const image::Image cube = render_model(data + "AnimatedMorphCube/glTF/AnimatedMorphCube.gltf");
  EXPECT_GT(image::psnr(cube, render_model(data + "AnimatedMorphCube/glTF-Quantized/AnimatedMorphCube.gltf")), 35.0);
}

// Used-but-unsupported extensions are named once each; required ones are refused.
TEST(GltfFeatures, IgnoredExtensionsAreNamedOnce) {
  ASSERT_TRUE(test::gl_ready());
  auto s = render::load_scene(khronos("TextureTransformMultiTest"));
  ASSERT_TRUE(s) << s.error().message;
  int clearcoat = 0;
  for (const std::string& w : s->warnings) clearcoat += w.find("KHR_materials_clearcoat") != std::string::npos;
  EXPECT_EQ(clearcoat, 1);
}
