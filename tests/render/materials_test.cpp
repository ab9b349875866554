// The material extensions through both pipelines (docs/scenes.md, "Materials"): each
// Khronos feature model rendered as it is and with the extension taken out of its JSON
// (the feature must make a difference where the model's README says, and the pipelines
// must agree), the shader variant and G-buffer layout each scene chooses (a plain scene
// keeps the plain variant and its memory), and KHR_materials_variants by name.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdlib>
#include <limits>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "gl_support.hpp"
#include "gltf_test_models.hpp"
#include "khronos_models.hpp"
#include "test_support.hpp"

using namespace foveal;
using nlohmann::json;

namespace {

constexpr int kWidth = 512, kHeight = 256;  // 256×256 per eye

struct Case {
  render::Pipeline pipeline;
  render::Method method;
  double sigma;
  render::BlendAt blend_at = render::BlendAt::output;
};
const Case kCases[] = {{render::Pipeline::gbuffer, render::Method::full, 1.0},
                       {render::Pipeline::gbuffer, render::Method::rmfr, 1.6},
                       {render::Pipeline::visibility, render::Method::full, 1.0},
                       {render::Pipeline::visibility, render::Method::rmfr, 1.6}};
// Transmissive surfaces shaded at RMFR's kept samples (docs/rmfr.md, "Transparency at the kept samples").
const Case kAtSamples{render::Pipeline::visibility, render::Method::rmfr, 1.6, render::BlendAt::samples};

std::string describe(const Case& c) {
  return std::string(render::pipeline_name(c.pipeline)) + " " + render::method_name(c.method) + " blend at " +
         render::blend_at_name(c.blend_at);
}

struct Rendered {
  image::Image image;
  std::string variant;
  std::size_t gbuffer_bytes_per_pixel = 0;
};

// One compositor for the whole test program: it recompiles its variant only when a
// scene's features change (as a user's does), so a test that renders a model through
// every case pays for its shaders once.
render::Compositor& compositor() {
  static render::Compositor c = test::make_compositor(kWidth, kHeight);
  return c;
}

Rendered render_case(const std::string& spec, const Case& c, const render::SceneOptions& options = {}) {
  render::Compositor& comp = compositor();
  auto s = render::load_scene(spec, options);
  if (!s) {
    ADD_FAILURE() << s.error().message;
    return {};
  }
  render::fill_view(*s);
  render::FrameParams p = test::frame(c.method, c.sigma);
  p.pipeline = c.pipeline;
  p.blend_at = c.blend_at;
  Rendered r{test::render_frame(comp, *s, p), comp.shading_variant(), comp.gbuffer_bytes_per_pixel()};
  return r;
}

// Left-eye pixels where `a` is brighter than `b` by more than `levels` in some channel
// (`brighter_only`) or differs by more than that in either direction.
int changed_pixels(const image::Image& a, const image::Image& b, int levels, bool brighter_only = false) {
  int n = 0;
  for (int y = 0; y < a.height; ++y)
    for (int x = 0; x < a.width / 2; ++x) {
      bool changed = false;
      for (int ch = 0; ch < 3; ++ch) {
        const int d = static_cast<int>(a.at(x, y)[ch]) - static_cast<int>(b.at(x, y)[ch]);
        changed = changed || (brighter_only ? d > levels : std::abs(d) > levels);
      }
      n += changed ? 1 : 0;
    }
  return n;
}

// Each feature model: the variant it chooses, and how much the feature must change it.
struct FeatureModel {
  const char* model;
  const char* extension;
  const char* variant;
  const char* variant_without;  // with the extension taken out
  int min_changed;  // left-eye pixels (of 256×256) changed by more than 8 levels without the extension
};
const FeatureModel kModels[] = {
    {"ClearCoatTest", "KHR_materials_clearcoat", "metal-rough+clearcoat", "metal-rough", 300},
    {"SpecularTest", "KHR_materials_specular", "metal-rough+specular", "metal-rough", 300},
    {"SheenChair", "KHR_materials_sheen", "metal-rough+sheen", "metal-rough", 300},
    {"AttenuationTest", "KHR_materials_transmission", "metal-rough+transmission", "metal-rough", 300},
    {"TransmissionTest", "KHR_materials_transmission", "metal-rough+transmission", "metal-rough", 300},
    {"AnisotropyStrengthTest", "KHR_materials_anisotropy", "metal-rough+anisotropy", "metal-rough", 300},
    {"IridescenceSuzanne", "KHR_materials_iridescence", "metal-rough+specular+iridescence+transmission",
     "metal-rough+specular+transmission", 100},
};

// A unit quad of material `front` at z = 1 (half size 0.6) before an unlit background
// quad of colour `back` at z = 0 (half size 2), seen from a camera at z = 3.
std::string write_pane(test::TempDir& dir, const std::string& name, const json& front, std::array<float, 3> back) {
  json j = test::quad_model();
  j["extensionsUsed"] = {"KHR_materials_unlit", "KHR_materials_transmission", "KHR_materials_volume"};
  j["cameras"] = {{{"type", "perspective"}, {"perspective", {{"yfov", 1.0}, {"znear", 0.1}}}}};
  j["materials"] = {{{"pbrMetallicRoughness", {{"baseColorFactor", {back[0], back[1], back[2], 1.0}}}},
                     {"extensions", {{"KHR_materials_unlit", json::object()}}}},
                    front};
  j["meshes"] = json::array();
  for (int m = 0; m < 2; ++m) {
    const json primitive = {{"attributes", {{"POSITION", 0}}}, {"indices", 1}, {"material", m}};
    j["meshes"].push_back({{"primitives", json::array({primitive})}});
  }
  j["nodes"] = {{{"camera", 0}, {"translation", {0, 0, 3}}},
                {{"mesh", 0}, {"translation", {-2, -2, 0}}, {"scale", {4, 4, 1}}},
                {{"mesh", 1}, {"translation", {-0.6, -0.6, 1}}, {"scale", {1.2, 1.2, 1}}}};
  j["scenes"] = {{{"nodes", {0, 1, 2}}}};
  const std::string path = dir.path(name + ".gltf");
  test::write_file(path, j.dump());
  return path;
}

json pane_material(float transmission, float thickness = 0.0f, float distance = 0.0f, std::array<float, 3> color = {1, 1, 1}) {
  json m = {{"pbrMetallicRoughness", {{"baseColorFactor", {1, 1, 1, 1}}, {"metallicFactor", 0.0}, {"roughnessFactor", 0.0}}},
            {"doubleSided", true}};
  if (transmission > 0.0f) m["extensions"]["KHR_materials_transmission"] = {{"transmissionFactor", transmission}};
  if (thickness > 0.0f) {
    m["extensions"]["KHR_materials_volume"] = {{"thicknessFactor", thickness}, {"attenuationColor", color}};
    if (distance > 0.0f) m["extensions"]["KHR_materials_volume"]["attenuationDistance"] = distance;
  }
  return m;
}

double srgb_decode(double v) { return v <= 0.04045 ? v / 12.92 : std::pow((v + 0.055) / 1.055, 2.4); }

// The left eye's centre pixel, display-linear.
std::array<double, 3> centre(const image::Image& img) {
  const std::uint8_t* p = img.at(img.width / 4, img.height / 2);
  return {srgb_decode(p[0] / 255.0), srgb_decode(p[1] / 255.0), srgb_decode(p[2] / 255.0)};
}

}  // namespace

// Each extension changes its model, the extension removed gives the plain variant, and
// the visibility pipeline shows what the G-buffer pipeline does.
TEST(Materials, EachExtensionChangesItsModelInBothPipelines) {
  ASSERT_TRUE(test::gl_ready());
  for (const FeatureModel& m : kModels) {
    test::TempDir dir;
    const std::string with = test::khronos(m.model);
    const std::string without = test::edited(dir, with, [&](json& j) { test::strip_extension(j, m.extension); });
    std::array<image::Image, 2> full;  // per pipeline, with the extension
    std::vector<Rendered> a, b;
    for (const Case& c : kCases) a.push_back(render_case(with, c));
    for (const Case& c : kCases) b.push_back(render_case(without, c));
    for (std::size_t i = 0; i < a.size(); ++i) {
      const Case& c = kCases[i];
      EXPECT_EQ(a[i].variant, m.variant) << m.model << " " << describe(c);
      EXPECT_EQ(b[i].variant, m.variant_without) << m.model << " without " << m.extension;
      const int d = changed_pixels(a[i].image, b[i].image, 8);
      EXPECT_GT(d, m.min_changed) << m.model << " " << describe(c) << ": pixels the extension changes";
      if (c.method == render::Method::full) full[c.pipeline == render::Pipeline::gbuffer ? 0 : 1] = a[i].image;
    }
    EXPECT_GT(image::psnr(full[0], full[1]), 35.0) << m.model << ": the visibility pipeline against the G-buffer one";
  }
}

// ClearCoatTest's README: each row's middle sample (base + coat) shows the coat's sharp
// reflection over the base's rough one. With the rig's sun, the coated spheres gain
// bright specular pixels the uncoated ones lack.
TEST(Materials, ClearcoatAddsASharpHighlight) {
  ASSERT_TRUE(test::gl_ready());
  test::TempDir dir;
  const std::string with = test::khronos("ClearCoatTest");
  const std::string without = test::edited(dir, with, [](json& j) { test::strip_extension(j, "KHR_materials_clearcoat"); });
  std::vector<image::Image> coated_images;
  for (const Case& c : kCases) coated_images.push_back(render_case(with, c).image);
  for (std::size_t i = 0; i < coated_images.size(); ++i) {
    const Case& c = kCases[i];
    const image::Image& coated = coated_images[i];
    const image::Image plain = render_case(without, c).image;
    const int brighter = changed_pixels(coated, plain, 24, true), darker = changed_pixels(plain, coated, 24, true);
    EXPECT_GT(brighter, 150) << describe(c) << ": pixels the coat brightens by more than 24 levels";
    EXPECT_GT(brighter, 4 * darker) << describe(c) << ": the coat mostly adds light (brighter / darker " << brighter << " / " << darker << ")";
  }
}

// SpecularTest's first row runs specularFactor 0 → 1: the plain material is the row's
// last sample everywhere, so taking the extension out brightens the row's reflections.
// KHR_materials_ior alone changes F0 the same way ((ior − 1)/(ior + 1))².
TEST(Materials, IorAloneChoosesTheSpecularVariantAndChangesF0) {
  ASSERT_TRUE(test::gl_ready());
  test::TempDir dir;
  const std::string plain = test::edited(dir, test::khronos("SpecularTest"), [](json& j) { test::strip_extension(j, "KHR_materials_specular"); });
  test::TempDir dir2;
  const std::string water = test::edited(dir2, test::khronos("SpecularTest"), [](json& j) {
    test::strip_extension(j, "KHR_materials_specular");
    for (json& m : j["materials"]) m["extensions"]["KHR_materials_ior"] = {{"ior", 3.0}};
    j["extensionsUsed"].push_back("KHR_materials_ior");
  });
  for (const Case& c : kCases) {
    const Rendered a = render_case(plain, c), b = render_case(water, c);
    EXPECT_EQ(b.variant, "metal-rough+specular") << describe(c);
    EXPECT_GT(changed_pixels(b.image, a.image, 8, true), 300) << describe(c) << ": ior 3 (F0 0.25) against 1.5 (F0 0.04) brightens";
  }
}

// A plain scene pays nothing for the extensions: the plain variant, 20 bytes per
// G-buffer pixel, and the same target memory whether or not a scene with layers was
// drawn before it by the same compositor (the layout follows the scene).
TEST(Materials, APlainSceneKeepsThePlainLayoutAndMemory) {
  ASSERT_TRUE(test::gl_ready());
  const std::string plain = test::source_path("data/scenes/WaterBottle/WaterBottle.gltf");
  for (render::Pipeline pipeline : {render::Pipeline::gbuffer, render::Pipeline::visibility}) {
    render::Compositor comp = test::make_compositor(kWidth, kHeight);
    render::FrameParams p = test::frame(render::Method::rmfr, 1.6);
    p.pipeline = pipeline;
    render::Scene bottle = test::scene(plain), coat = test::scene(test::khronos("ClearCoatTest"));
    test::render_frame(comp, bottle, p);
    EXPECT_EQ(comp.shading_variant(), "metal-rough");
    EXPECT_EQ(comp.gbuffer_bytes_per_pixel(), 20u);
    const render::TargetMemory before = comp.memory(pipeline);
    test::render_frame(comp, coat, p);
    EXPECT_EQ(comp.shading_variant(), "metal-rough+clearcoat");
    EXPECT_EQ(comp.gbuffer_bytes_per_pixel(), 28u);
    // The coat's target: 8 more bytes per pixel of each eye's reduced surface (and of
    // the G-buffer pipeline's full-size G-buffer), nothing else.
    const render::TargetMemory coated = comp.memory(pipeline);
    std::size_t reduced_pixels = 0;
    for (Eye e : kEyes) reduced_pixels += static_cast<std::size_t>(comp.buffer_size(e)[0]) * static_cast<std::size_t>(comp.buffer_size(e)[1]);
    const std::size_t full_pixels = pipeline == render::Pipeline::gbuffer ? std::size_t{kWidth / 2} * kHeight : 0;
    EXPECT_EQ(coated.gbuffer - before.gbuffer, 8 * full_pixels) << render::pipeline_name(pipeline);
    // The visibility pipeline's material tile lists also grow with the material count
    // (19 + the default against WaterBottle's 1 + 1): per eye and material slot, a 32-byte
    // command and 4 bytes per 32×32 tile (render_targets.hpp, MaterialTiles).
    std::size_t tiles = 0;
    if (pipeline == render::Pipeline::visibility)
      for (Eye e : kEyes) {
        const auto b = comp.buffer_size(e);
        tiles += (coat.materials.size() - bottle.materials.size()) *
                 (32 + static_cast<std::size_t>((b[0] + 31) / 32) * static_cast<std::size_t>((b[1] + 31) / 32) * 4);
      }
    EXPECT_EQ(coated.transformed - before.transformed, 8 * reduced_pixels + tiles) << render::pipeline_name(pipeline);
    EXPECT_EQ(coated.total() - before.total(), coated.transformed - before.transformed + 8 * full_pixels);
    const image::Image again = test::render_frame(comp, bottle, p);
    EXPECT_EQ(comp.shading_variant(), "metal-rough");
    EXPECT_EQ(comp.memory(pipeline).total(), before.total()) << render::pipeline_name(pipeline);
    render::Compositor fresh = test::make_compositor(kWidth, kHeight);
    EXPECT_EQ(image::psnr(again, test::render_frame(fresh, bottle, p)), std::numeric_limits<double>::infinity())
        << "the plain variant after a clearcoat scene draws what a fresh compositor draws";
  }
}

// SheenChair's two KHR_materials_variants: Mango (orange) by default, Peacock (teal)
// by name; an unknown name is refused with the file's variants listed.
TEST(Materials, VariantsChooseTheMaterialsByName) {
  ASSERT_TRUE(test::gl_ready());
  const std::string chair = test::khronos("SheenChair");
  auto red_minus_blue = [](const image::Image& img) {
    double sum = 0;
    for (int y = 0; y < img.height; ++y)
      for (int x = 0; x < img.width / 2; ++x) sum += img.at(x, y)[0] - img.at(x, y)[2];
    return sum / (img.height * (img.width / 2));
  };
  auto names = render::load_scene(chair);
  ASSERT_TRUE(names) << names.error().message;
  ASSERT_EQ(names->variants.size(), 2u);
  EXPECT_EQ(names->variant, "");
  const std::string peacock = names->variants[1];
  EXPECT_NE(peacock.find("Peacock"), std::string::npos) << peacock;
  const Rendered mango = render_case(chair, kCases[0]), teal = render_case(chair, kCases[0], {peacock});
  EXPECT_GT(red_minus_blue(mango.image), red_minus_blue(teal.image) + 5.0);
  auto bad = render::load_scene(chair, {"Plaid"});
  ASSERT_FALSE(bad);
  EXPECT_NE(bad.error().message.find("no material variant 'Plaid'"), std::string::npos) << bad.error().message;
  EXPECT_NE(bad.error().message.find(peacock), std::string::npos) << bad.error().message;
}

TEST(Materials, RenderJsonReportsTheVariantAndLayout) {
  test::TempDir dir;
  const std::string base = test::bin("foveal") + " render --size 64x32 --frames 1 --warmup 0 --json --out " + dir.path("f.png") +
                           " --scene " + test::khronos("SheenChair");
  auto a = test::run(base), b = test::run(base + " --variant 'Peacock Velvet'"), c = test::run(base + " --variant Plaid");
  ASSERT_EQ(a.exit_code, 0) << a.err;
  const json ja = json::parse(a.out);
  EXPECT_EQ(ja["material_variant"]["shader"], "metal-rough+sheen");
  EXPECT_EQ(ja["material_variant"]["gbuffer_bytes_per_pixel"], 24);
  EXPECT_EQ(ja["material_variant"]["variants"].size(), 2u);
  if (b.exit_code == 0) EXPECT_EQ(json::parse(b.out)["material_variant"]["variant"], "Peacock Velvet");
  else ADD_FAILURE() << b.err;
  EXPECT_EQ(c.exit_code, 2) << c.err;
  EXPECT_NE(c.err.find("no material variant 'Plaid'"), std::string::npos) << c.err;
}

// KHR_materials_transmission: a clear white pane (roughness 0, thin-walled) shows the
// red background through it, (1 − F) of it at normal incidence; without the extension
// the pane is an opaque white dielectric. Both pipelines, full and RMFR, and at the kept samples.
TEST(Materials, TransmissionShowsTheOpaqueResultBehind) {
  ASSERT_TRUE(test::gl_ready());
  test::TempDir dir;
  const std::string clear = write_pane(dir, "clear", pane_material(1.0f), {1, 0, 0});
  const std::string opaque = write_pane(dir, "opaque", pane_material(0.0f), {1, 0, 0});
  for (const Case& c : {kCases[0], kCases[1], kCases[2], kCases[3], kAtSamples}) {
    const Rendered a = render_case(clear, c), b = render_case(opaque, c);
    EXPECT_EQ(a.variant, "metal-rough+transmission") << describe(c);
    const auto through = centre(a.image), solid = centre(b.image);
    EXPECT_NEAR(through[0], 0.96, 0.05) << describe(c) << ": red behind, (1 - F0) of it";
    EXPECT_LT(through[1], 0.1) << describe(c);
    EXPECT_GT(solid[1], 0.2) << describe(c) << ": without transmission the white pane hides the red";
  }
}

// KHR_materials_volume: Beer-Lambert through thickness d: c^(d / attenuationDistance)
// per channel. A pane of thickness 1 and colour (0.25, 1, 1) over white: red 0.25 of
// green at distance 1, 0.5 at distance 2, 1 without a distance.
TEST(Materials, VolumeAttenuatesByThicknessOverDistance) {
  ASSERT_TRUE(test::gl_ready());
  test::TempDir dir;
  for (const auto& [distance, expected] : {std::pair{1.0f, 0.25}, std::pair{2.0f, 0.5}, std::pair{0.0f, 1.0}})
    for (const Case& c : {kCases[0], kCases[3], kAtSamples}) {
      const std::string pane = write_pane(dir, "vol" + std::to_string(static_cast<int>(distance)),
                                          pane_material(1.0f, 1.0f, distance, {0.25f, 1.0f, 1.0f}), {1, 1, 1});
      const auto px = centre(render_case(pane, c).image);
      EXPECT_NEAR(px[0] / px[1], expected, 0.05) << describe(c) << " attenuation distance " << distance;
    }
}

// Four layered features on one material: the G-buffer holds three (GL promises eight
// colour attachments); the last in SurfaceLayout's order is dropped with a warning.
TEST(Materials, AScenePastThreeLayersIsDrawnWithoutTheLastAndWarned) {
  test::TempDir dir;
  json front = pane_material(0.0f);
  front["extensions"] = {{"KHR_materials_clearcoat", {{"clearcoatFactor", 1.0}}},
                         {"KHR_materials_sheen", {{"sheenColorFactor", {1.0, 1.0, 1.0}}}},
                         {"KHR_materials_specular", {{"specularFactor", 0.5}}},
                         {"KHR_materials_anisotropy", {{"anisotropyStrength", 0.5}}}};
  const std::string pane = write_pane(dir, "layers", front, {1, 0, 0});
  auto r = test::run(test::bin("foveal") + " render --size 64x32 --frames 1 --warmup 0 --json --out " + dir.path("f.png") + " --scene " + pane);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const json j = json::parse(r.out);
  EXPECT_EQ(j["material_variant"]["shader"], "metal-rough+clearcoat+specular+sheen");
  EXPECT_EQ(j["material_variant"]["gbuffer_bytes_per_pixel"], 36);
  bool warned = false;
  for (const json& w : j["warnings"]) warned = warned || w.get<std::string>().find("drawn without: anisotropy") != std::string::npos;
  EXPECT_TRUE(warned) << j["warnings"].dump();
  EXPECT_NE(r.err.find("drawn without: anisotropy"), std::string::npos) << r.err;
}

// KHR_materials_iridescence: a film of thickness 0 is no film (the Airy sum falls back
// to the base's Fresnel); 400 nm of film (ior 1.33) colours a grey metal's reflection,
// which is grey without it. Both pipelines.
TEST(Materials, IridescenceColoursTheReflectionAndVanishesAtZeroThickness) {
  ASSERT_TRUE(test::gl_ready());
  test::TempDir dir;
  auto pane = [&](const std::string& name, float thickness) {
    json m = pane_material(0.0f);
    // A grey metal (F0 0.5): a film over a perfect mirror (F0 1) would change nothing.
    m["pbrMetallicRoughness"]["metallicFactor"] = 1.0;
    m["pbrMetallicRoughness"]["baseColorFactor"] = {0.5, 0.5, 0.5, 1.0};
    m["pbrMetallicRoughness"]["roughnessFactor"] = 0.6;
    if (thickness >= 0.0f)
      m["extensions"]["KHR_materials_iridescence"] = {{"iridescenceFactor", 1.0},
                                                      {"iridescenceThicknessMinimum", thickness},
                                                      {"iridescenceThicknessMaximum", thickness}};
    return write_pane(dir, name, m, {0.2f, 0.2f, 0.2f});
  };
  const std::string none = pane("none", -1.0f), zero = pane("zero", 0.0f), film = pane("film", 400.0f);
  for (const Case& c : {kCases[0], kCases[3]}) {
    const auto a = centre(render_case(none, c).image), b = centre(render_case(zero, c).image);
    const Rendered f = render_case(film, c);
    EXPECT_EQ(f.variant, "metal-rough+iridescence") << describe(c);
    const auto x = centre(f.image);
    for (int ch = 0; ch < 3; ++ch) EXPECT_NEAR(a[static_cast<std::size_t>(ch)], b[static_cast<std::size_t>(ch)], 0.01) << describe(c) << " channel " << ch;
    const double chroma = std::max({x[0], x[1], x[2]}) - std::min({x[0], x[1], x[2]});
    const double grey = std::max({a[0], a[1], a[2]}) - std::min({a[0], a[1], a[2]});
    EXPECT_GT(chroma, grey + 0.01) << describe(c) << ": film " << x[0] << " " << x[1] << " " << x[2] << ", none " << a[0] << " " << a[1] << " " << a[2];
  }
}
