// The Khronos feature-test models (tests/render/data/khronos, SOURCE.md there) render
// as their READMEs say a correct viewer shows them. Each test also renders the model with
// the feature taken out of its JSON, so it can fail: the feature must make the
// difference the README describes.
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <functional>

#include <nlohmann/json.hpp>

#include <meshoptimizer.h>

#include "gl_support.hpp"
#include "khronos_models.hpp"
#include "test_support.hpp"

using namespace foveal;
using nlohmann::json;

namespace {

using test::edited;
using test::khronos;
using test::strip_extension;

constexpr int kWidth = 1024, kHeight = 512;  // 512×512 per eye

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

// README: in the rotation quad the arrow points to the green marker; red means the
// rotation went the wrong way, yellow that it was not applied. Measured as the distance
// in pixels from the arrow (black) to each marker inside the bottom-left quad; with the
// rotation negated in the file the arrow must point to red instead (so the check can fail).
TEST(GltfFeatures, TextureTransformRotatesTheRightWay) {
  ASSERT_TRUE(test::gl_ready());
  struct Distances { double green, red, yellow; };
  auto distances = [](const image::Image& img) {
    // The model's bounding box in the left eye, then the left 2/5 of its bottom half.
    const std::uint8_t* bg = img.at(0, 0);
    int x0 = img.width, x1 = -1, y0 = img.height, y1 = -1;
    for (int y = 0; y < img.height; ++y)
      for (int x = 0; x < img.width / 2; ++x) {
        const std::uint8_t* p = img.at(x, y);
        if (std::abs(p[0] - bg[0]) + std::abs(p[1] - bg[1]) + std::abs(p[2] - bg[2]) > 30)
          x0 = std::min(x0, x), x1 = std::max(x1, x), y0 = std::min(y0, y), y1 = std::max(y1, y);
      }
    std::vector<std::array<int, 2>> black, green, red, yel;
    for (int y = (y0 + y1) / 2 + (y1 - y0) / 10; y <= y1; ++y)  // below the green "U" tile
      for (int x = x0; x <= x0 + (x1 - x0) * 2 / 5; ++x) {
        const std::uint8_t* p = img.at(x, y);
        const int r = p[0], g = p[1], b = p[2];
        if (r < 50 && g < 50 && b < 50) {
          if (x <= x0 + (x1 - x0) / 3) black.push_back({x, y});  // the scale quad's arrow starts beyond
        }
        else if (g > 120 && r < 80 && b < 80) green.push_back({x, y});
        else if (r > 150 && g < 80 && b < 80) red.push_back({x, y});
        else if (yellow(r, g, b)) yel.push_back({x, y});
      }
    // The arrow is the largest 8-connected black blob (markers have dark outlines too).
    std::vector<std::array<int, 2>> arrow;
    std::vector<bool> used(black.size(), false);
    for (std::size_t seed = 0; seed < black.size(); ++seed) {
      if (used[seed]) continue;
      std::vector<std::array<int, 2>> blob{black[seed]};
      used[seed] = true;
      for (std::size_t k = 0; k < blob.size(); ++k)
        for (std::size_t j = 0; j < black.size(); ++j)
          if (!used[j] && std::abs(black[j][0] - blob[k][0]) <= 1 && std::abs(black[j][1] - blob[k][1]) <= 1)
            used[j] = true, blob.push_back(black[j]);
      if (blob.size() > arrow.size()) arrow = blob;
    }
    auto nearest = [&](const std::vector<std::array<int, 2>>& marker) {
      double best = 1e9;
      for (const auto& a : arrow)
        for (const auto& m : marker) best = std::min(best, std::hypot(a[0] - m[0], a[1] - m[1]));
      return best;
    };
    return Distances{nearest(green), nearest(red), nearest(yel)};
  };
  const std::string model = khronos("TextureTransformTest");
  const Distances ok = distances(render_model(model));
  EXPECT_LT(ok.green, 6.0);
  EXPECT_GT(ok.red, 3 * ok.green + 8) << "arrow to red marker";
  EXPECT_GT(ok.yellow, 3 * ok.green + 8) << "arrow to yellow marker";
  test::TempDir d;
  const Distances wrong = distances(render_model(edited(d, model, [](json& j) {
    json& t = j["materials"][3]["pbrMetallicRoughness"]["baseColorTexture"]["extensions"]["KHR_texture_transform"];
    t["rotation"] = -t["rotation"].get<double>();
  })));
  EXPECT_LT(wrong.red, wrong.green) << "negated rotation: the arrow should point to red";
  EXPECT_LT(wrong.red, wrong.yellow) << "negated rotation: the arrow should point to red";
  std::printf("arrow to green/red/yellow: %.1f %.1f %.1f px; negated: %.1f %.1f %.1f px\n", ok.green, ok.red, ok.yellow,
              wrong.green, wrong.red, wrong.yellow);
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
// The model's clearcoat is drawn now (docs/scenes.md, "Materials"): no warning. An
// extension foveal does not know, used by several of its materials, is named once.
TEST(GltfFeatures, IgnoredExtensionsAreNamedOnce) {
  ASSERT_TRUE(test::gl_ready());
  auto count = [](const render::Scene& s, const std::string& ext) {
    int n = 0;
    for (const std::string& w : s.warnings) n += w.find(ext) != std::string::npos;
    return n;
  };
  auto s = render::load_scene(khronos("TextureTransformMultiTest"));
  ASSERT_TRUE(s) << s.error().message;
  EXPECT_EQ(count(*s, "KHR_materials_clearcoat"), 0);
  test::TempDir d;
  const std::string unknown = edited(d, khronos("TextureTransformMultiTest"), [](json& j) {
    j["extensionsUsed"].push_back("FOVEAL_unknown_layer");
    for (json& m : j["materials"]) m["extensions"]["FOVEAL_unknown_layer"] = json::object();
  });
  auto u = render::load_scene(unknown);
  ASSERT_TRUE(u) << u.error().message;
  EXPECT_EQ(count(*u, "FOVEAL_unknown_layer"), 1);
}

namespace {

// A unit quad facing +z (the framing camera's view) with `material`, written to
// DIR/NAME.gltf + NAME.bin; `extra` adds attributes as (name, accessor JSON, bytes).
struct ExtraAttribute {
  std::string name;
  json accessor;  // componentType, type, normalized
  std::vector<unsigned char> bytes;
};

template <class T>
void append(std::vector<unsigned char>& out, const std::vector<T>& v) {
  const auto* p = reinterpret_cast<const unsigned char*>(v.data());
  out.insert(out.end(), p, p + v.size() * sizeof(T));
  while (out.size() % 4) out.push_back(0);
}

const std::vector<float> kQuadPositions = {-0.5f, -0.5f, 0, 0.5f, -0.5f, 0, 0.5f, 0.5f, 0, -0.5f, 0.5f, 0};
const std::vector<float> kQuadNormals = {0, 0, 1, 0, 0, 1, 0, 0, 1, 0, 0, 1};
const std::vector<std::uint16_t> kQuadIndices = {0, 1, 2, 0, 2, 3};

std::string quad(test::TempDir& d, const std::string& name, const json& material, const std::vector<ExtraAttribute>& extra = {},
                 const std::vector<std::uint16_t>& quad_indices = kQuadIndices, int mode = 4) {
  std::vector<unsigned char> bin;
  json views = json::array(), accessors = json::array();
  auto add = [&](const std::vector<unsigned char>& bytes, json accessor) {
    views.push_back({{"buffer", 0}, {"byteOffset", bin.size()}, {"byteLength", bytes.size()}});
    bin.insert(bin.end(), bytes.begin(), bytes.end());
    while (bin.size() % 4) bin.push_back(0);
    accessor["bufferView"] = views.size() - 1;
    accessors.push_back(accessor);
    return accessors.size() - 1;
  };
  auto bytes = [](const auto& v) {
    std::vector<unsigned char> b;
    append(b, v);
    return b;
  };
  json attributes = {
      {"POSITION", add(bytes(kQuadPositions), {{"componentType", 5126}, {"type", "VEC3"}, {"count", 4}, {"min", {-0.5, -0.5, 0}}, {"max", {0.5, 0.5, 0}}})},
      {"NORMAL", add(bytes(kQuadNormals), {{"componentType", 5126}, {"type", "VEC3"}, {"count", 4}})}};
  for (const ExtraAttribute& e : extra) {
    json a = e.accessor;
    a["count"] = 4;
    attributes[e.name] = add(e.bytes, a);
  }
  const auto indices = add(bytes(quad_indices), {{"componentType", 5123}, {"type", "SCALAR"}, {"count", quad_indices.size()}});
  json j = {{"asset", {{"version", "2.0"}}},
            {"scene", 0},
            {"scenes", {{{"nodes", {0}}}}},
            {"nodes", {{{"mesh", 0}}}},
            {"meshes", {{{"primitives", {{{"attributes", attributes}, {"indices", indices}, {"material", 0}, {"mode", mode}}}}}}},
            {"materials", {material}},
            {"accessors", accessors},
            {"bufferViews", views},
            {"buffers", {{{"uri", name + ".bin"}, {"byteLength", bin.size()}}}}};
  if (material.contains("extensions"))
    for (auto& [ext, v] : material["extensions"].items()) j["extensionsUsed"].push_back(ext);
  test::write_file(d.path(name + ".bin"), std::string(bin.begin(), bin.end()));
  test::write_file(d.path(name + ".gltf"), j.dump());
  return d.path(name + ".gltf");
}

}  // namespace

// docs/scenes.md's conversion: a spec-gloss dielectric (specular 0.04) and a spec-gloss
// metal (no diffuse, coloured specular) render as their metal-roughness twins.
TEST(GltfFeatures, SpecularGlossinessRendersAsItsMetalRoughnessTwin) {
  ASSERT_TRUE(test::gl_ready());
  test::TempDir d;
  auto sg = [](json diffuse, json specular, double gloss) {
    return json{{"extensions", {{"KHR_materials_pbrSpecularGlossiness",
                                 {{"diffuseFactor", diffuse}, {"specularFactor", specular}, {"glossinessFactor", gloss}}}}}};
  };
  auto mr = [](json base, double metallic, double roughness) {
    return json{{"pbrMetallicRoughness", {{"baseColorFactor", base}, {"metallicFactor", metallic}, {"roughnessFactor", roughness}}}};
  };
  const image::Image dielectric = render_model(quad(d, "mr0", mr({0.8, 0.3, 0.2, 1}, 0.0, 0.4)));
  EXPECT_GT(image::psnr(dielectric, render_model(quad(d, "sg0", sg({0.8, 0.3, 0.2, 1}, {0.04, 0.04, 0.04}, 0.6)))), 45.0);
  const image::Image metal = render_model(quad(d, "mr1", mr({0.9, 0.6, 0.3, 1}, 1.0, 0.3)));
  EXPECT_GT(image::psnr(metal, render_model(quad(d, "sg1", sg({0, 0, 0, 1}, {0.9, 0.6, 0.3}, 0.7)))), 45.0);
  EXPECT_LT(image::psnr(dielectric, metal), 30.0);  // the two cases do differ
}

// COLOR_0 as float vec3, normalised ubyte vec4 and normalised ushort vec3 all multiply the
// base colour alike.
TEST(GltfFeatures, VertexColourTypesAgree) {
  ASSERT_TRUE(test::gl_ready());
  test::TempDir d;
  const json white = {{"pbrMetallicRoughness", {{"metallicFactor", 0.0}}}};
  std::vector<float> f;
  std::vector<std::uint8_t> u8;
  std::vector<std::uint16_t> u16;
  for (int v = 0; v < 4; ++v) {
    f.insert(f.end(), {0.2f, 0.6f, 1.0f});
    u8.insert(u8.end(), {51, 153, 255, 255});
    u16.insert(u16.end(), {13107, 39321, 65535});
  }
  std::vector<unsigned char> bf, b8, b16;
  append(bf, f), append(b8, u8), append(b16, u16);
  const image::Image plain = render_model(quad(d, "plain", white));
  const image::Image as_float = render_model(quad(d, "float", white, {{"COLOR_0", {{"componentType", 5126}, {"type", "VEC3"}}, bf}}));
  EXPECT_LT(image::psnr(plain, as_float), 30.0) << "the colour changes the picture";
  EXPECT_GT(image::psnr(as_float, render_model(quad(d, "u8", white, {{"COLOR_0", {{"componentType", 5121}, {"type", "VEC4"}, {"normalized", true}}, b8}}))), 48.0);
  EXPECT_GT(image::psnr(as_float, render_model(quad(d, "u16", white, {{"COLOR_0", {{"componentType", 5123}, {"type", "VEC3"}, {"normalized", true}}, b16}}))), 48.0);
}

// EXT_meshopt_compression (encoded here with meshoptimizer): the quad with its vertices
// and indices compressed, and a fallback buffer without data as gltfpack writes it,
// renders exactly as the plain quad.
TEST(GltfFeatures, MeshoptCompressedQuadMatchesThePlainOne) {
  ASSERT_TRUE(test::gl_ready());
  test::TempDir d;
  const json material = {{"pbrMetallicRoughness", {{"baseColorFactor", {0.7, 0.5, 0.2, 1}}, {"metallicFactor", 0.0}}}};
  std::vector<float> interleaved;
  for (int v = 0; v < 4; ++v)
    for (const auto* src : {&kQuadPositions, &kQuadNormals})
      interleaved.insert(interleaved.end(), src->begin() + v * 3, src->begin() + v * 3 + 3);
  std::vector<unsigned char> packed(meshopt_encodeVertexBufferBound(4, 24));
  packed.resize(meshopt_encodeVertexBuffer(packed.data(), packed.size(), interleaved.data(), 4, 24));
  const std::size_t vertex_bytes = packed.size();
  const std::vector<unsigned> idx(kQuadIndices.begin(), kQuadIndices.end());
  std::vector<unsigned char> packed_idx(meshopt_encodeIndexBufferBound(6, 4));
  packed_idx.resize(meshopt_encodeIndexBuffer(packed_idx.data(), packed_idx.size(), idx.data(), 6));
  while (packed.size() % 4) packed.push_back(0);
  const std::size_t index_at = packed.size();
  packed.insert(packed.end(), packed_idx.begin(), packed_idx.end());
  test::write_file(d.path("c.bin"), std::string(packed.begin(), packed.end()));
  auto ext = [](std::size_t offset, std::size_t length, int stride, int count, const char* mode) {
    return json{{"EXT_meshopt_compression", {{"buffer", 0}, {"byteOffset", offset}, {"byteLength", length}, {"byteStride", stride},
                                             {"count", count}, {"mode", mode}}}};
  };
  const json j = {
      {"asset", {{"version", "2.0"}}},
      {"extensionsUsed", {"EXT_meshopt_compression"}},
      {"extensionsRequired", {"EXT_meshopt_compression"}},
      {"scene", 0},
      {"scenes", {{{"nodes", {0}}}}},
      {"nodes", {{{"mesh", 0}}}},
      {"meshes", {{{"primitives", {{{"attributes", {{"POSITION", 0}, {"NORMAL", 1}}}, {"indices", 2}, {"material", 0}}}}}}},
      {"materials", {material}},
      {"accessors",
       {{{"bufferView", 0}, {"componentType", 5126}, {"type", "VEC3"}, {"count", 4}, {"min", {-0.5, -0.5, 0}}, {"max", {0.5, 0.5, 0}}},
        {{"bufferView", 0}, {"byteOffset", 12}, {"componentType", 5126}, {"type", "VEC3"}, {"count", 4}},
        {{"bufferView", 1}, {"componentType", 5123}, {"type", "SCALAR"}, {"count", 6}}}},
      {"bufferViews",
       {{{"buffer", 1}, {"byteLength", 96}, {"byteStride", 24}, {"extensions", ext(0, vertex_bytes, 24, 4, "ATTRIBUTES")}},
        {{"buffer", 1}, {"byteOffset", 96}, {"byteLength", 12}, {"extensions", ext(index_at, packed_idx.size(), 2, 6, "TRIANGLES")}}}},
      {"buffers",
       {{{"uri", "c.bin"}, {"byteLength", packed.size()}},
        {{"byteLength", 108}, {"extensions", {{"EXT_meshopt_compression", {{"fallback", true}}}}}}}}};
  test::write_file(d.path("meshopt.gltf"), j.dump());
  const image::Image plain = render_model(quad(d, "plain", material));
  EXPECT_EQ(image::max_abs_diff(plain, render_model(d.path("meshopt.gltf"))), 0);

  json corrupt = j;  // compressed stream cut short: a clear error naming the view
  corrupt["bufferViews"][0]["extensions"]["EXT_meshopt_compression"]["byteLength"] = 5;
  test::write_file(d.path("corrupt.gltf"), corrupt.dump());
  auto s = render::load_scene(d.path("corrupt.gltf"));
  ASSERT_FALSE(s);
  EXPECT_EQ(s.error().kind, ErrorKind::bad_input);
  EXPECT_NE(s.error().message.find("corrupt.gltf: buffer view 0 (EXT_meshopt_compression)"), std::string::npos) << s.error().message;
}

// Sparse data that points outside its accessor is refused with the accessor named.
TEST(GltfFeatures, BadSparseIndicesAreRefused) {
  ASSERT_TRUE(test::gl_ready());
  test::TempDir d;
  const std::string path = edited(d, khronos("SimpleSparseAccessor"), [](json& j) {
    for (json& a : j["accessors"])
      if (a.contains("sparse")) a["count"] = 2;  // the sparse indices reach 8
  });
  auto s = render::load_scene(path);
  ASSERT_FALSE(s);
  EXPECT_NE(s.error().message.find("(sparse)"), std::string::npos) << s.error().message;
}

// Triangle strips and fans draw the same quad, facing the same way, as the list (the
// material is double-sided, so a back-facing triangle would be shaded with the normal flipped).
TEST(GltfFeatures, StripsAndFansDrawLikeLists) {
  ASSERT_TRUE(test::gl_ready());
  test::TempDir d;
  const json material = {{"pbrMetallicRoughness", {{"baseColorFactor", {0.3, 0.6, 0.9, 1}}, {"metallicFactor", 0.0}}},
                         {"doubleSided", true}};
  const image::Image list = render_model(quad(d, "list", material));
  // The strip splits the quad along the other diagonal: only pixels on it may differ.
  EXPECT_GT(image::psnr(list, render_model(quad(d, "strip", material, {}, {0, 1, 3, 2}, 5))), 50.0);
  EXPECT_EQ(image::max_abs_diff(list, render_model(quad(d, "fan", material, {}, {0, 1, 2, 3}, 6))), 0);
}
