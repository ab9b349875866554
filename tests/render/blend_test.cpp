// alphaMode BLEND (docs/scenes.md, "Transparency"): blended primitives are left out of
// the opaque passes and composited "over" the lit opaque result after the inverse pass,
// back to front, tested against the opaque depth. Scenes are written by the test: unit
// quads facing a camera at z = 3, an opaque background at z = 0 and blended quads in
// front of it. Unlit materials make the expected colour exact; one lit case checks the
// forward shading against the deferred one.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
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

constexpr int kWidth = 256, kHeight = 128;  // 128×128 per eye

struct Quad {
  std::array<float, 4> color;  // base colour factor, alpha last
  std::string mode;            // alphaMode
  float z, half;               // plane and half size, centred on the z axis
  bool unlit = true;
  float vertex_alpha = -1.0f;  // >= 0: a COLOR_0 (white, this alpha) at every vertex
};

// One node per quad in `quads`' order (their draw order), each with its own mesh and material.
std::string write_scene(test::TempDir& dir, const std::string& name, const std::vector<Quad>& quads) {
  json j = test::quad_model();
  j["extensionsUsed"] = {"KHR_materials_unlit"};
  j["cameras"] = {{{"type", "perspective"}, {"perspective", {{"yfov", 1.0}, {"znear", 0.1}}}}};
  j["nodes"] = {{{"camera", 0}, {"translation", {0, 0, 3}}}};
  j["meshes"] = json::array();
  j["materials"] = json::array();
  json scene_nodes = {0};
  for (std::size_t i = 0; i < quads.size(); ++i) {
    const Quad& q = quads[i];
    json m = {{"pbrMetallicRoughness", {{"baseColorFactor", q.color}, {"metallicFactor", 0.0}, {"roughnessFactor", 0.6}}},
              {"alphaMode", q.mode}};
    if (q.unlit) m["extensions"] = {{"KHR_materials_unlit", json::object()}};
    j["materials"].push_back(m);
    json primitive = {{"attributes", {{"POSITION", 0}}}, {"indices", 1}, {"material", i}};
    if (q.vertex_alpha >= 0.0f) {
      std::string colors;
      for (int v = 0; v < 4; ++v)
        for (float c : {1.0f, 1.0f, 1.0f, q.vertex_alpha}) colors.append(reinterpret_cast<const char*>(&c), sizeof c);
      j["buffers"].push_back({{"byteLength", colors.size()}, {"uri", test::data_uri(colors)}});
      j["bufferViews"].push_back({{"buffer", j["buffers"].size() - 1}, {"byteLength", colors.size()}});
      j["accessors"].push_back({{"bufferView", j["bufferViews"].size() - 1}, {"componentType", 5126}, {"count", 4}, {"type", "VEC4"}});
      primitive["attributes"]["COLOR_0"] = j["accessors"].size() - 1;
    }
    j["meshes"].push_back({{"primitives", json::array({primitive})}});
    j["nodes"].push_back({{"mesh", i}, {"translation", {-q.half, -q.half, q.z}}, {"scale", {2 * q.half, 2 * q.half, 1.0f}}});
    scene_nodes.push_back(i + 1);
  }
  j["scenes"] = {{{"nodes", scene_nodes}}};
  const std::string path = dir.path(name + ".gltf");
  test::write_file(path, j.dump());
  return path;
}

const Quad kBackground{{1, 0, 0, 1}, "OPAQUE", 0.0f, 2.0f};
const Quad kGreen{{0, 1, 0, 0.5f}, "BLEND", 1.0f, 0.6f};
const Quad kBlue{{0, 0, 1, 0.5f}, "BLEND", 1.5f, 0.4f};

double srgb_encode(double v) { return v <= 0.0031308 ? 12.92 * v : 1.055 * std::pow(v, 1.0 / 2.4) - 0.055; }
double srgb_decode(double v) { return v <= 0.04045 ? v / 12.92 : std::pow((v + 0.055) / 1.055, 2.4); }

// Each eye's centre pixel, where every quad of the scenes covers.
std::array<std::array<int, 3>, 2> centres(const image::Image& img) {
  std::array<std::array<int, 3>, 2> out{};
  for (int e = 0; e < 2; ++e) {
    const std::uint8_t* p = img.at(e * img.width / 2 + img.width / 4, img.height / 2);
    out[static_cast<std::size_t>(e)] = {p[0], p[1], p[2]};
  }
  return out;
}

struct Case {
  render::Pipeline pipeline;
  render::Method method;
  double sigma;
  render::BlendAt blend_at = render::BlendAt::output;
};
// The last: blended surfaces shaded at RMFR's kept samples (docs/rmfr.md, "Transparency at the kept samples").
const Case kCases[] = {{render::Pipeline::gbuffer, render::Method::full, 1.0},
                       {render::Pipeline::gbuffer, render::Method::rmfr, 2.0},
                       {render::Pipeline::visibility, render::Method::full, 1.0},
                       {render::Pipeline::visibility, render::Method::rmfr, 2.0},
                       {render::Pipeline::visibility, render::Method::rmfr, 2.0, render::BlendAt::samples}};

std::string describe(const Case& c) {
  return std::string(render::pipeline_name(c.pipeline)) + " " + render::method_name(c.method) + " blend at " +
         render::blend_at_name(c.blend_at);
}

render::Compositor lens_compositor() {
  auto model = DisplayModel::load(test::source_path("data/display/htc_vive_pro_eye_lens.json"));
  EXPECT_TRUE(model) << (model ? "" : model.error().message);
  render::CompositorOptions o;
  o.width = kWidth, o.height = kHeight, o.shadow_map_size = 1024;
  if (model) o.model = *model;
  auto c = render::Compositor::create(o, test::source_shaders());
  if (!c) {
    ADD_FAILURE() << c.error().message;
    std::abort();
  }
  return std::move(*c);
}

image::Image render_case(const std::string& spec, const Case& c, bool lens = false) {
  render::Compositor comp = lens ? lens_compositor() : test::make_compositor(kWidth, kHeight);
  render::Scene s = test::scene(spec);
  render::FrameParams p = test::frame(c.method, c.sigma);
  p.pipeline = c.pipeline;
  p.blend_at = c.blend_at;
  auto t = comp.render(s, p);
  EXPECT_TRUE(t) << (t ? "" : t.error().message);
  bool blended = false;
  for (const render::Material& m : s.materials) blended = blended || m.blend;
  if (t) {
    EXPECT_EQ(t->blend > 0.0, blended) << describe(c) << ": the blend pass is timed when there is one";
  }
  return comp.read_image();
}

// Both eyes' centre pixels equal `linear` (the expected linear colour) within 2 of 255.
void expect_centres(const image::Image& img, std::array<double, 3> linear, const std::string& what) {
  for (const auto& px : centres(img))
    for (int k = 0; k < 3; ++k)
      EXPECT_NEAR(px[static_cast<std::size_t>(k)], 255.0 * srgb_encode(linear[static_cast<std::size_t>(k)]), 2.0)
          << what << ", channel " << k;
}

}  // namespace

TEST(Blend, AQuadIsTheOverCompositeOfItsColourAndAlphaWithTheOpaqueResult) {
  ASSERT_TRUE(test::gl_ready());
  test::TempDir dir;
  const std::string blended = write_scene(dir, "blend", {kBackground, kGreen});
  Quad opaque_green = kGreen;
  opaque_green.mode = "OPAQUE";
  const std::string opaque = write_scene(dir, "opaque", {kBackground, opaque_green});
  {
    render::Scene s = test::scene(blended);
    ASSERT_EQ(s.materials.size(), 2u);
    EXPECT_FALSE(s.materials[0].blend);
    EXPECT_TRUE(s.materials[1].blend);
    EXPECT_TRUE(s.warnings.empty()) << s.warnings.front();
  }
  for (const Case& c : kCases) {
    // Green at alpha 0.5 over red: (0.5, 0.5, 0) in linear light.
    expect_centres(render_case(blended, c), {0.5, 0.5, 0.0}, describe(c) + ", BLEND");
    // The same quad OPAQUE covers the red: the blend makes the difference.
    expect_centres(render_case(opaque, c), {0.0, 1.0, 0.0}, describe(c) + ", OPAQUE");
  }
}

// glTF's alpha is the base colour factor's × the texture's × the vertex colour's.
TEST(Blend, AlphaIsTheFactorTimesTheVertexColoursAlpha) {
  ASSERT_TRUE(test::gl_ready());
  test::TempDir dir;
  Quad green = kGreen;
  green.vertex_alpha = 0.5f;  // × factor 0.5: α 0.25
  const std::string spec = write_scene(dir, "vertex_alpha", {kBackground, green});
  for (const Case& c : kCases) expect_centres(render_case(spec, c), {0.75, 0.25, 0.0}, describe(c));
}

// No silent fallback: an alphaMode glTF does not define is refused, naming where.
TEST(Blend, AnUnknownAlphaModeIsRefused) {
  ASSERT_TRUE(test::gl_ready());
  test::TempDir dir;
  Quad odd = kGreen;
  odd.mode = "GLASS";
  auto s = render::load_scene(write_scene(dir, "odd", {kBackground, odd}));
  ASSERT_FALSE(s);
  EXPECT_NE(s.error().message.find("materials[1].alphaMode"), std::string::npos) << s.error().message;
}

TEST(Blend, OverlappingQuadsCompositeBackToFrontWhateverTheirOrderInTheFile) {
  ASSERT_TRUE(test::gl_ready());
  test::TempDir dir;
  const std::string near_last = write_scene(dir, "near_last", {kBackground, kGreen, kBlue});
  const std::string near_first = write_scene(dir, "near_first", {kBackground, kBlue, kGreen});
  for (const Case& c : kCases) {
    const image::Image a = render_case(near_last, c), b = render_case(near_first, c);
    // Green over red, then blue (nearer) over that: (0.25, 0.25, 0.5); the other order
    // would give (0.25, 0.5, 0.25).
    expect_centres(a, {0.25, 0.25, 0.5}, describe(c) + ", nearer quad last in the file");
    expect_centres(b, {0.25, 0.25, 0.5}, describe(c) + ", nearer quad first in the file");
    EXPECT_EQ(a.rgba, b.rgba) << describe(c) << ": the file's order changes the image";
  }
}

TEST(Blend, AQuadBehindAnOpaqueOneIsHidden) {
  ASSERT_TRUE(test::gl_ready());
  test::TempDir dir;
  const Quad white{{1, 1, 1, 1}, "OPAQUE", 1.5f, 0.4f};
  const std::string spec = write_scene(dir, "hidden", {kBackground, kGreen, white});
  for (const Case& c : kCases) expect_centres(render_case(spec, c), {1.0, 1.0, 1.0}, describe(c));
}

// Lit: the forward pass shades with the deferred pass's material and lights. A lit quad at
// alpha 0.5 is the over-composite of the same quad drawn OPAQUE and of the background
// behind it, and at alpha 1 equals the OPAQUE quad (full method: both are shaded at every
// pixel). The background is rendered with the quad at alpha 0: the light rig follows the
// scene's bounds, so the quad must stay, and blended surfaces cast no shadow.
TEST(Blend, ALitQuadIsShadedAsTheOpaquePathShadesIt) {
  ASSERT_TRUE(test::gl_ready());
  test::TempDir dir;
  Quad bg = kBackground, lit = kGreen;
  bg.unlit = lit.unlit = false;
  lit.color = {0.2f, 0.8f, 0.4f, 0.5f};
  Quad solid = lit, opaque = lit, clear = lit;
  clear.color[3] = 0.0f;
  solid.color[3] = 1.0f;
  opaque.color[3] = 1.0f, opaque.mode = "OPAQUE";
  const std::string half = write_scene(dir, "half", {bg, lit}), one = write_scene(dir, "one", {bg, solid}),
                    ref = write_scene(dir, "ref", {bg, opaque}), none = write_scene(dir, "none", {bg, clear});
  for (const Case& c : kCases) {
    if (c.method != render::Method::full) continue;
    const auto quad = centres(render_case(ref, c)), behind = centres(render_case(none, c));
    const auto blended = centres(render_case(half, c)), alpha_one = centres(render_case(one, c));
    for (std::size_t e = 0; e < 2; ++e)
      for (std::size_t k = 0; k < 3; ++k) {
        EXPECT_NEAR(alpha_one[e][k], quad[e][k], 2) << describe(c) << ", alpha 1, eye " << e << " channel " << k;
        const double over = 0.5 * srgb_decode(quad[e][k] / 255.0) + 0.5 * srgb_decode(behind[e][k] / 255.0);
        EXPECT_NEAR(blended[e][k], 255.0 * srgb_encode(over), 2.5) << describe(c) << ", alpha 0.5, eye " << e << " channel " << k;
      }
    EXPECT_NE(quad, behind) << "the test needs the quad to differ from the background";
  }
}

// Through the lens the blended quads go on before the distortion: the image equals that of
// an opaque quad painted with the composite colour, distorted the same way (drawn after
// the lens, the quad would keep its undistorted outline).
TEST(Blend, UnderTheLensTheCompositeIsDistortedWithTheOpaqueResult) {
  ASSERT_TRUE(test::gl_ready());
  test::TempDir dir;
  Quad painted = kGreen;
  painted.mode = "OPAQUE";
  painted.color = {0.5f, 0.5f, 0.0f, 1.0f};
  const std::string blended = write_scene(dir, "blend", {kBackground, kGreen});
  const std::string reference = write_scene(dir, "painted", {kBackground, painted});
  for (const Case& c : kCases) {
    const image::Image a = render_case(blended, c, true), b = render_case(reference, c, true);
    expect_centres(a, {0.5, 0.5, 0.0}, describe(c) + ", through the lens");
    // Full: the same warp of the same picture; RMFR: the composite is filtered twice
    // (resolve, then the lens), the painted quad once.
    EXPECT_GT(image::psnr(a, b), c.method == render::Method::full ? 40.0 : 30.0) << describe(c);
  }
}

// The Khronos AlphaBlendModeTest (tests/render/data/khronos): its README says a viewer that
// blends shows a green check mark under the BLEND sample, where one that draws it opaque
// shows a red X (an X of alpha 0 over the check). Taking BLEND out (OPAQUE) must bring
// the X back, in both pipelines, full and RMFR.
TEST(Blend, AlphaBlendModeTestShowsTheBlendCheckMark) {
  ASSERT_TRUE(test::gl_ready());
  test::TempDir dir;
  const std::string with = test::khronos("AlphaBlendModeTest");
  const std::string without = test::edited(dir, with, [](json& j) {
    for (json& m : j["materials"])
      if (m.value("alphaMode", "") == "BLEND") m["alphaMode"] = "OPAQUE";
  });
  // Red X pixels in the left eye (the check marks are green, the bed is marble white; at
  // this size the X is pink: red well above green and blue).
  auto red = [](const image::Image& img) {
    int n = 0;
    for (int y = 0; y < img.height; ++y)
      for (int x = 0; x < img.width / 2; ++x) {
        const std::uint8_t* p = img.at(x, y);
        n += (p[0] - std::max(p[1], p[2]) > 60) ? 1 : 0;
      }
    return n;
  };
  render::Compositor comp = test::make_compositor(1536, 768);
  render::Scene blended = test::scene(with), opaque = test::scene(without);
  render::fill_view(blended);  // the bed across the view: the marks a few px wide
  render::fill_view(opaque);
  for (const Case& c : kCases) {
    render::FrameParams p = test::frame(c.method, c.sigma);
    p.pipeline = c.pipeline;
    p.blend_at = c.blend_at;
    // Measured 0 against 22-32 (the X is some 12 px wide).
    const int a = red(test::render_frame(comp, blended, p)), b = red(test::render_frame(comp, opaque, p));
    EXPECT_LT(a, 3) << describe(c) << ": red pixels with BLEND";
    EXPECT_GT(b, 12) << describe(c) << ": red pixels with BLEND drawn OPAQUE (the X the blend hides)";
  }
}

// Transparency at the kept samples (BlendAt::samples; docs/rmfr.md, "Transparency at the
// kept samples"): peeled at W×H, shaded in RMFR's reduced buffer before the inverse pass.
namespace {

render::FrameParams samples_frame(double sigma, render::BlendAt at) {
  render::FrameParams p = test::frame(render::Method::rmfr, sigma);
  p.pipeline = render::Pipeline::visibility;
  p.blend_at = at;
  return p;
}

}  // namespace

// At σ = 1 RMFR's map is the identity: the samples path shades every pixel, as the blend
// pass does, and must give its image (texture reads filtered over the texel's footprint
// in place of the rasteriser's derivatives, and the resolve's bilinear tap: not bit-equal).
TEST(BlendAtSamples, AtSigmaOneItEqualsTheBlendPassAtOutputResolution) {
  ASSERT_TRUE(test::gl_ready());
  test::TempDir dir;
  Quad bg = kBackground, a = kGreen, b = kBlue;
  bg.unlit = a.unlit = b.unlit = false;  // lit: the material and the lights, not only a colour
  const std::string quads = write_scene(dir, "lit", {bg, a, b});
  render::Compositor comp = test::make_compositor(512, 256);
  for (const std::string& spec : {quads, test::khronos("AlphaBlendModeTest"), test::khronos("TransmissionTest")}) {
    render::Scene s = test::scene(spec);
    render::fill_view(s);
    auto out = comp.render(s, samples_frame(1.0, render::BlendAt::output));
    ASSERT_TRUE(out) << out.error().message;
    const image::Image at_output = comp.read_image();
    auto in = comp.render(s, samples_frame(1.0, render::BlendAt::samples));
    ASSERT_TRUE(in) << in.error().message;
    const image::Image at_samples = comp.read_image();
    EXPECT_EQ(out->blend_layers, 0) << spec;
    EXPECT_GT(in->blend_layers, 0) << spec << ": the samples path composited no layer";
    EXPECT_GT(image::psnr(at_output, at_samples), 40.0) << spec;  // measured 94.5 (quads), 53.8 (AlphaBlendModeTest), 48.1 dB (TransmissionTest)
  }
}

// Peeled layers composite back to front: the nearer pane's colour dominates where they
// overlap, whichever the file lists first. Five panes at one pixel: the nearest four (the
// layer cap) are drawn, the deepest is left out and counted.
TEST(BlendAtSamples, OverlappingPanesCompositeNearestLastAndTheCapDropsTheDeepest) {
  ASSERT_TRUE(test::gl_ready());
  test::TempDir dir;
  const Quad red{{1, 0, 0, 0.8f}, "BLEND", 0.5f, 0.9f}, green{{0, 1, 0, 0.8f}, "BLEND", 1.0f, 0.7f};
  const Quad black{{0, 0, 0, 1}, "OPAQUE", 0.0f, 2.0f};
  for (const auto& order : {std::vector<Quad>{black, red, green}, std::vector<Quad>{black, green, red}}) {
    render::Compositor comp = test::make_compositor(kWidth, kHeight);
    render::Scene s = test::scene(write_scene(dir, "two", order));
    auto t = comp.render(s, samples_frame(2.0, render::BlendAt::samples));
    ASSERT_TRUE(t) << t.error().message;
    EXPECT_EQ(t->blend_layers, 4) << "two layers per eye";
    EXPECT_EQ(t->blend_dropped, 0u);
    // Red 0.8 over black, then green 0.8 (nearer) over that: (0.16, 0.8, 0); the other
    // order would give (0.8, 0.16, 0).
    expect_centres(comp.read_image(), {0.16, 0.8, 0.0}, "green nearer");
  }
  // Five panes, nearest last: grey 0.5 at z 0.2, then four at 0.5 alpha nearer: the
  // grey is the fifth layer at the centre, beyond the cap, and not drawn.
  std::vector<Quad> five = {black, {{1, 1, 1, 0.5f}, "BLEND", 0.2f, 0.9f}};
  for (int k = 0; k < 4; ++k) five.push_back({{0, 0, 1, 0.5f}, "BLEND", 0.4f + 0.2f * static_cast<float>(k), 0.8f - 0.1f * static_cast<float>(k)});
  render::Compositor comp = test::make_compositor(kWidth, kHeight);
  render::Scene s = test::scene(write_scene(dir, "five", five));
  auto t = comp.render(s, samples_frame(2.0, render::BlendAt::samples));
  ASSERT_TRUE(t) << t.error().message;
  EXPECT_EQ(t->blend_layers, 8) << "the cap, four layers per eye";
  EXPECT_GT(t->blend_dropped, 0u) << "the grey pane's centre is beyond the cap";
  // Four blue panes at 0.5 over black: blue 1 - 0.5^4; the grey under them would add red and green.
  expect_centres(comp.read_image(), {0.0, 0.0, 1.0 - 0.0625}, "four of five layers");
}

// The work scales with the kept samples: at σ = 2 the samples path composites about the
// reduced buffers' share of the fragments the blend pass composites at output resolution.
// A count of fragments (GL_SAMPLES_PASSED), never a time.
TEST(BlendAtSamples, TheBlendedFragmentsScaleWithTheKeptSamples) {
  ASSERT_TRUE(test::gl_ready());
  test::TempDir dir;
  render::Compositor comp = test::make_compositor(512, 256);
  // Panes over the whole view: where the fovea's region alone were covered, RMFR would
  // keep it at nearly full density.
  Quad green = kGreen, blue = kBlue;
  green.half = blue.half = 3.0f;
  render::Scene s = test::scene(write_scene(dir, "panes", {kBackground, green, blue}));
  auto out = comp.render(s, samples_frame(2.0, render::BlendAt::output));
  auto in = comp.render(s, samples_frame(2.0, render::BlendAt::samples));
  ASSERT_TRUE(out && in);
  ASSERT_GT(out->blend_samples, 0u);
  EXPECT_EQ(out->blend_layers, 0);
  EXPECT_GT(in->blend_layers, 0);
  const double kept = static_cast<double>(in->shaded_samples) / (512.0 * 256.0);
  const double ratio = static_cast<double>(in->blend_samples) / static_cast<double>(out->blend_samples);
  EXPECT_LT(kept, 0.5) << "the test needs foveation to keep a small share";
  EXPECT_NEAR(ratio, kept, 0.15) << "blended fragments " << in->blend_samples << " at samples, " << out->blend_samples << " at output";
}
