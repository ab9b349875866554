// The visibility pipeline (docs/rmfr.md, "Pipelines"): at σ = 1 it renders what the
// G-buffer pipeline renders, for every kind of material; foveated, it stays close to the
// G-buffer pipeline's image while evaluating materials only at the kept samples.
#include <gtest/gtest.h>

#include <cstring>
#include <vector>

#include <nlohmann/json.hpp>

#include "gl_support.hpp"
#include "gltf_test_models.hpp"
#include "test_support.hpp"

using namespace foveal;
using nlohmann::json;
using render::Method;
using render::Pipeline;

namespace {

constexpr int kW = 480, kH = 270;
const double kPositions[9][2] = {{0, 0}, {1, 0}, {0, 1}, {1, 1}, {0.5, 0}, {0.5, 1}, {0, 0.5}, {1, 0.5}, {0.5, 0.5}};

render::FrameParams through(Pipeline p, render::FrameParams f) {
  f.pipeline = p;
  return f;
}

template <class T>
void append(std::string& bin, const std::vector<T>& v) {
  bin.append(reinterpret_cast<const char*>(v.data()), v.size() * sizeof(T));
  while (bin.size() % 4) bin.push_back('\0');
}

// A quad tilted away from the viewer (so texture footprints vary across it) with
// positions, normals, UVs and optionally vertex colours, one material; `reversed` winds it
// clockwise, so the camera sees its back face. Written into `dir` with its PNGs.
std::string quad_model(test::TempDir& dir, const std::string& name, json material, bool reversed = false,
                       bool vertex_colours = false) {
  const std::vector<float> pos = {-1, -1, 0.4f, 1, -1, 0.4f, 1, 1, -0.4f, -1, 1, -0.4f};
  const std::vector<float> nrm = {0, 0.37f, 0.93f, 0, 0.37f, 0.93f, 0, 0.37f, 0.93f, 0, 0.37f, 0.93f};
  const std::vector<float> uv = {0, 4, 4, 4, 4, 0, 0, 0};
  const std::vector<float> col = {1, 0.2f, 0.2f, 1, 0.2f, 1, 0.2f, 1, 0.2f, 0.2f, 1, 1, 1, 1, 0.2f, 1};
  const std::vector<std::uint16_t> idx = reversed ? std::vector<std::uint16_t>{0, 2, 1, 0, 3, 2} : std::vector<std::uint16_t>{0, 1, 2, 0, 2, 3};
  std::string bin;
  json views = json::array(), accessors = json::array();
  auto add = [&](auto v, json accessor) {
    views.push_back({{"buffer", 0}, {"byteOffset", bin.size()}, {"byteLength", v.size() * sizeof(v[0])}});
    append(bin, v);
    accessor["bufferView"] = views.size() - 1;
    accessors.push_back(accessor);
    return accessors.size() - 1;
  };
  json attributes = {{"POSITION", add(pos, {{"componentType", 5126}, {"type", "VEC3"}, {"count", 4}, {"min", {-1, -1, -0.4}}, {"max", {1, 1, 0.4}}})},
                     {"NORMAL", add(nrm, {{"componentType", 5126}, {"type", "VEC3"}, {"count", 4}})},
                     {"TEXCOORD_0", add(uv, {{"componentType", 5126}, {"type", "VEC2"}, {"count", 4}})}};
  if (vertex_colours) attributes["COLOR_0"] = add(col, {{"componentType", 5126}, {"type", "VEC4"}, {"count", 4}});
  const auto indices = add(idx, {{"componentType", 5123}, {"type", "SCALAR"}, {"count", 6}});
  // A 64×64 texture: fine stripes (so filtering matters) in colour, a checker in alpha.
  image::Image tex(64, 64);
  for (int y = 0; y < 64; ++y)
    for (int x = 0; x < 64; ++x) {
      std::uint8_t* p = tex.at(x, y);
      const bool stripe = (x / 2) % 2 == 0, on = ((x / 16) + (y / 16)) % 2 == 0;
      p[0] = stripe ? 230 : 40, p[1] = stripe ? 180 : 60, p[2] = 90, p[3] = on ? 255 : 0;
    }
  EXPECT_TRUE(image::save_png(dir.path(name + ".png"), tex));
  json j = {{"asset", {{"version", "2.0"}}},
            {"scene", 0},
            {"scenes", {{{"nodes", {0}}}}},
            {"nodes", {{{"mesh", 0}}}},
            {"meshes", {{{"primitives", {{{"attributes", attributes}, {"indices", indices}, {"material", 0}}}}}}},
            {"materials", {material}},
            {"textures", {{{"source", 0}}}},
            {"images", {{{"uri", name + ".png"}}}},
            {"accessors", accessors},
            {"bufferViews", views},
            {"buffers", {{{"uri", name + ".bin"}, {"byteLength", bin.size()}}}}};
  test::write_file(dir.path(name + ".bin"), bin);
  test::write_file(dir.path(name + ".gltf"), j.dump());
  return dir.path(name + ".gltf");
}

const json kTextured = {{"pbrMetallicRoughness", {{"baseColorTexture", {{"index", 0}}}, {"metallicFactor", 0.0}, {"roughnessFactor", 0.6}}}};

const json kPlain = {{"pbrMetallicRoughness", {{"baseColorFactor", {0.8, 0.5, 0.3, 1.0}}, {"metallicFactor", 0.0}, {"roughnessFactor", 0.6}}}};

// σ = 1 through the visibility pipeline (RMFR with the fovea anywhere) against the full
// method, both pipelines. Against the G-buffer pipeline the bound is `gbuffer_db`: the
// G-buffer pass's reads are llvmpipe's 8× anisotropic (EWA) filter, the material pass's
// its in-shader one (common/anisotropic_filter.glsl, docs/rmfr.md): measured 60.3 dB on
// WaterBottle and 39.9 dB on Dungeon (grazing floors; 55.0 and 34.6 with the former
// single isotropic tap, so the Dungeon bound fails without the anisotropic filter);
// untextured and pattern scenes: exact.
void expect_pipelines_agree(const std::string& spec, double gbuffer_db) {
  render::Compositor c = test::make_compositor(kW, kH);
  render::Scene s = test::scene(spec);
  const image::Image gbuffer = test::render_frame(c, s, test::frame(Method::full, 1.0));
  const image::Image full = test::render_frame(c, s, through(Pipeline::visibility, test::frame(Method::full, 1.0)));
  EXPECT_GE(image::psnr(gbuffer, full), gbuffer_db) << spec << ": full, visibility against G-buffer";
  for (const auto& p : kPositions) {
    const image::Image r = test::render_frame(c, s, through(Pipeline::visibility, test::frame(Method::rmfr, 1.0, p[0], p[1])));
    EXPECT_GE(image::psnr(full, r), 40.0) << spec << ": RMFR at sigma 1, fovea " << p[0] << "," << p[1];
    EXPECT_GE(image::psnr(gbuffer, r), gbuffer_db) << spec << ": RMFR at sigma 1 against the G-buffer pipeline";
  }
}

// A scene in both pipelines at full rate: they agree within `db`; returns the image.
image::Image expect_same_material(render::Compositor& c, const std::string& spec, double db) {
  render::Scene s = test::scene(spec);
  const image::Image gbuffer = test::render_frame(c, s, test::frame(Method::full, 1.0));
  const image::Image vis = test::render_frame(c, s, through(Pipeline::visibility, test::frame(Method::full, 1.0)));
  EXPECT_GE(image::psnr(gbuffer, vis), db) << spec;
  return vis;
}


// A grid of `count` small quads facing the viewer, each with a material of its own (plain
// colours): more materials than the material passes have tile lists for
// (kMaterialSlots in render/pipeline/src/visibility_pipeline.cpp), so the last list is
// shared.
std::string many_materials_model(test::TempDir& dir, int count) {
  const int across = 40, down = (count + across - 1) / across;
  const float cell_w = 3.2f / static_cast<float>(across), cell_h = 2.0f / static_cast<float>(down);
  std::vector<float> pos, nrm;
  std::vector<std::uint32_t> idx;
  json accessors = json::array(), primitives = json::array(), materials = json::array();
  for (int q = 0; q < count; ++q) {
    const float x0 = -1.6f + cell_w * static_cast<float>(q % across), y0 = -1.0f + cell_h * static_cast<float>(q / across);
    const float x1 = x0 + 0.8f * cell_w, y1 = y0 + 0.8f * cell_h;
    const auto v = static_cast<std::uint32_t>(pos.size() / 3);
    for (float p : {x0, y0, 0.0f, x1, y0, 0.0f, x1, y1, 0.0f, x0, y1, 0.0f}) pos.push_back(p);
    for (int k = 0; k < 4; ++k) nrm.insert(nrm.end(), {0.0f, 0.0f, 1.0f});
    for (std::uint32_t k : {0u, 1u, 2u, 0u, 2u, 3u}) idx.push_back(v + k);
    accessors.push_back({{"bufferView", 2}, {"byteOffset", 24 * q}, {"componentType", 5125}, {"type", "SCALAR"}, {"count", 6}});
    primitives.push_back({{"attributes", {{"POSITION", 0}, {"NORMAL", 1}}}, {"indices", q + 2}, {"material", q}});
    const unsigned h = static_cast<unsigned>(q) * 2654435761u;
    materials.push_back({{"pbrMetallicRoughness",
                          {{"baseColorFactor", {(h & 255) / 255.0, ((h >> 8) & 255) / 255.0, ((h >> 16) & 255) / 255.0, 1.0}},
                           {"metallicFactor", 0.0},
                           {"roughnessFactor", 0.6}}}});
  }
  const auto vertices = static_cast<int>(pos.size() / 3);
  const json normals = {{"bufferView", 1}, {"componentType", 5126}, {"type", "VEC3"}, {"count", vertices}};
  const json positions = {{"bufferView", 0}, {"componentType", 5126}, {"type", "VEC3"}, {"count", vertices},
                          {"min", {-1.6, -1.0, 0.0}}, {"max", {1.6, 1.0, 0.0}}};
  accessors.insert(accessors.begin(), normals);
  accessors.insert(accessors.begin(), positions);
  std::string bin;
  json views = json::array();
  auto view = [&](const auto& v) {
    views.push_back({{"buffer", 0}, {"byteOffset", bin.size()}, {"byteLength", v.size() * sizeof(v[0])}});
    append(bin, v);
  };
  view(pos), view(nrm), view(idx);
  json j = {{"asset", {{"version", "2.0"}}},
            {"scene", 0},
            {"scenes", {{{"nodes", {0}}}}},
            {"nodes", {{{"mesh", 0}}}},
            {"meshes", {{{"primitives", primitives}}}},
            {"materials", materials},
            {"accessors", accessors},
            {"bufferViews", views},
            {"buffers", {{{"uri", "many.bin"}, {"byteLength", bin.size()}}}}};
  test::write_file(dir.path("many.bin"), bin);
  test::write_file(dir.path("many.gltf"), j.dump());
  return dir.path("many.gltf");
}
}  // namespace

TEST(Visibility, SigmaOneEqualsFull) {
  ASSERT_TRUE(test::gl_ready());
  test::TempDir d;
  expect_pipelines_agree("pattern:noise@20", 60.0);
  expect_pipelines_agree(quad_model(d, "plain", kPlain), 60.0);
  expect_pipelines_agree(test::source_path("data/scenes/WaterBottle/WaterBottle.gltf"), 57.0);
  expect_pipelines_agree(test::source_path("data/scenes/Dungeon/dungeon_simplified.gltf"), 40.5);  // 41.1 dB; 39.9 before the minor-axis level (common/anisotropic_filter.glsl)
}

// Each kind of material renders alike in both pipelines, and each feature makes the
// difference it should (so the comparison can fail).
TEST(Visibility, EveryKindOfMaterialMatchesTheGBufferPipeline) {
  ASSERT_TRUE(test::gl_ready());
  test::TempDir d;
  render::Compositor c = test::make_compositor(kW, kH);
  // Untextured: exact.
  const image::Image plain = expect_same_material(c, quad_model(d, "plain", kPlain), 60.0);
  // Vertex-coloured: the crafted quad and the Khronos test model.
  const image::Image coloured = expect_same_material(c, quad_model(d, "coloured", kPlain, false, true), 60.0);
  EXPECT_LT(image::psnr(plain, coloured), 30.0) << "the vertex colours change the picture";
  expect_same_material(c, test::source_path("tests/render/data/khronos/VertexColorTest/glTF/VertexColorTest.gltf"), 28.0);
  // Alpha-masked: the texture's alpha checker cuts holes (the background shows through).
  json masked = kTextured;
  masked["alphaMode"] = "MASK";
  masked["alphaCutoff"] = 0.5;
  const image::Image textured = expect_same_material(c, quad_model(d, "textured", kTextured), 28.0);
  const image::Image holes = expect_same_material(c, quad_model(d, "masked", masked), 28.0);
  EXPECT_LT(image::psnr(textured, holes), 20.0) << "the mask cuts holes";
  // Double-sided: seen from behind, the normal flips (lit), else it faces away (dark).
  json two_sided = kPlain;
  two_sided["doubleSided"] = true;
  const image::Image back = expect_same_material(c, quad_model(d, "back", kPlain, true), 60.0);
  const image::Image back_lit = expect_same_material(c, quad_model(d, "back2", two_sided, true), 60.0);
  EXPECT_LT(image::psnr(back, back_lit), 35.0) << "double-sided flips the normal of the back face";
  // Normal-mapped, metal-roughness and occlusion textures, emissive: WaterBottle; texture
  // transforms and the second UV set: the Khronos models.
  expect_same_material(c, test::source_path("data/scenes/WaterBottle/WaterBottle.gltf"), 30.0);
  for (const char* m : {"TextureTransformTest", "MultiUVTest"})
    expect_same_material(c, test::source_path(std::string("tests/render/data/khronos/") + m + "/glTF/" + m + ".gltf"), 30.0);
}

// Foveated, both pipelines shade the same samples of the same surfaces: their images
// stay close (the visibility pipeline filters textures over each texel's footprint, the
// G-buffer pipeline point-samples a full-rate G-buffer, so they are not equal).
TEST(Visibility, FoveatedFramesStayCloseToTheGBufferPipeline) {
  ASSERT_TRUE(test::gl_ready());
  render::Compositor c = test::make_compositor(kW, kH);
  for (const std::string& spec : {std::string("pattern:noise@20"), test::source_path("data/scenes/WaterBottle/WaterBottle.gltf")}) {
    render::Scene s = test::scene(spec);
    for (Method m : render::all_methods()) {
      if (m == Method::full) continue;
      const render::FrameParams f = render::efr_frame(m, Eye::right, 2.0, 3.0, 0.3, 0.3);
      const image::Image g = test::render_frame(c, s, f);
      EXPECT_GE(image::psnr(g, test::render_frame(c, s, through(Pipeline::visibility, f))), 20.0) << spec << " " << render::method_name(m);
    }
  }
}

TEST(Visibility, RenderTargetsAreSmallerThanTheGBufferPipelines) {
  ASSERT_TRUE(test::gl_ready());
  render::CompositorOptions o;  // 2880x1600
  auto c = render::Compositor::create(o, test::source_shaders());
  ASSERT_TRUE(c) << c.error().message;
  render::Scene s = test::scene(test::source_path("data/scenes/WaterBottle/WaterBottle.gltf"));
  const render::FrameParams efr = render::efr_frame(Method::rmfr, Eye::right, 2.0, 3.0, 0.3, 0.3);
  ASSERT_TRUE(c->render(s, through(Pipeline::visibility, efr)));
  const std::size_t vis = c->memory(Pipeline::visibility).total();
  EXPECT_EQ(c->memory().total(), vis) << "no G-buffer is made for the visibility pipeline";
  ASSERT_TRUE(c->render(s, efr));
  const std::size_t gbuffer = c->memory(Pipeline::gbuffer).total();
  EXPECT_LT(vis, gbuffer);
  EXPECT_LT(static_cast<double>(vis) / 1e6, 90.0);
}

TEST(Visibility, PipelineNamesParse) {
  for (render::Pipeline p : render::all_pipelines()) EXPECT_EQ(render::parse_pipeline(render::pipeline_name(p)).value(), p);
  auto bad = render::parse_pipeline("deferred");
  ASSERT_FALSE(bad);
  EXPECT_NE(bad.error().message.find("gbuffer, visibility"), std::string::npos);
}

// Materials are shaded only over the tiles that hold them (per-material tile lists), also
// past the last list of their own: 1100 one-colour materials render as in the G-buffer
// pipeline, at full rate and foveated through every mapping.
TEST(Visibility, ManyMaterialsRenderAsInTheGBufferPipeline) {
  ASSERT_TRUE(test::gl_ready());
  test::TempDir d;
  const std::string spec = many_materials_model(d, 1100);
  expect_pipelines_agree(spec, 60.0);
  render::Compositor c = test::make_compositor(kW, kH);
  render::Scene s = test::scene(spec);
  ASSERT_EQ(s.materials.size(), 1100u);
  for (Method m : render::all_methods()) {
    if (m == Method::full) continue;
    const render::FrameParams f = render::efr_frame(m, Eye::right, 2.0, 3.0, 0.3, 0.3);
    EXPECT_GE(image::psnr(test::render_frame(c, s, f), test::render_frame(c, s, through(Pipeline::visibility, f))), 45.0)
        << render::method_name(m);
  }
}
