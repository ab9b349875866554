// Golden images of pattern scenes and a glTF scene, full and every foveation method with EFR, and of the
// Khronos feature models, full and RMFR with EFR, through both pipelines (tolerance: PSNR >= 40 dB against
// the committed image; a diff image is written on failure; FOVEAL_UPDATE_GOLDEN=1 rewrites them). The
// G-buffer pipeline's images are NAME_METHOD.png, the visibility pipeline's NAME_vis_METHOD.png.
#include <gtest/gtest.h>

#include <cctype>

#include "gl_support.hpp"
#include "khronos_models.hpp"
#include "test_support.hpp"

using namespace foveal;
using render::Method;

namespace {
// Every method: full, then each foveation method with EFR (σ 2 right, 3 left) and a
// different fovea per eye; NAME_METHOD.png.
void golden(const std::string& spec, const std::string& name, render::Pipeline pipeline = render::Pipeline::gbuffer) {
  ASSERT_TRUE(test::gl_ready());
  render::Compositor c = test::make_compositor(480, 270);
  render::Scene s = test::scene(spec);
  const std::string prefix = name + (pipeline == render::Pipeline::visibility ? "_vis_" : "_");
  render::FrameParams full = test::frame(Method::full, 1.0);
  full.pipeline = pipeline;
  test::expect_matches_golden(test::render_frame(c, s, full), prefix + "full");
  for (Method m : render::all_methods()) {
    if (m == Method::full) continue;
    render::FrameParams p = render::efr_frame(m, Eye::right, 2.0, 3.0, 0.3, 0.3);
    p.pipeline = pipeline;
    p.eyes[0].fovea_x = 0.3, p.eyes[0].fovea_y = 0.4;
    p.eyes[1].fovea_x = 0.8, p.eyes[1].fovea_y = 0.9;
    test::expect_matches_golden(test::render_frame(c, s, p), prefix + render::method_name(m));
  }
}
const render::Pipeline kVis = render::Pipeline::visibility;

// A Khronos feature model (tests/render/data/khronos): full and RMFR with EFR through both
// pipelines, smaller (192×192 per eye) since there are many: model_full.png,
// model_rmfr.png, model_vis_full.png, model_vis_rmfr.png (lower case).
void feature_golden(const std::string& model) {
  ASSERT_TRUE(test::gl_ready());
  render::Compositor c = test::make_compositor(384, 192);
  render::Scene s = test::scene(test::khronos(model));
  render::fill_view(s);  // the model across the view
  std::string name = model;
  for (char& ch : name) ch = static_cast<char>(std::tolower(static_cast<unsigned char>(ch)));
  for (render::Pipeline pipeline : render::all_pipelines()) {
    const std::string prefix = name + (pipeline == kVis ? "_vis_" : "_");
    render::FrameParams full = test::frame(Method::full, 1.0);
    full.pipeline = pipeline;
    test::expect_matches_golden(test::render_frame(c, s, full), prefix + "full");
    render::FrameParams p = render::efr_frame(Method::rmfr, Eye::right, 2.0, 3.0, 0.3, 0.3);
    p.pipeline = pipeline;
    p.eyes[0].fovea_x = 0.4, p.eyes[0].fovea_y = 0.45;
    p.eyes[1].fovea_x = 0.6, p.eyes[1].fovea_y = 0.55;
    test::expect_matches_golden(test::render_frame(c, s, p), prefix + "rmfr");
  }
}
}  // namespace

TEST(Golden, Checker) { golden("pattern:checker", "checker"); }
TEST(Golden, VerticalStripes) { golden("pattern:stripes-v", "stripes_v"); }
TEST(Golden, RotatedNoise) { golden("pattern:noise@30", "noise_30"); }
TEST(Golden, WaterBottle) { golden(test::source_path("data/scenes/WaterBottle/WaterBottle.gltf"), "waterbottle"); }
TEST(Golden, CheckerVisibility) { golden("pattern:checker", "checker", kVis); }
TEST(Golden, VerticalStripesVisibility) { golden("pattern:stripes-v", "stripes_v", kVis); }
TEST(Golden, RotatedNoiseVisibility) { golden("pattern:noise@30", "noise_30", kVis); }
TEST(Golden, WaterBottleVisibility) { golden(test::source_path("data/scenes/WaterBottle/WaterBottle.gltf"), "waterbottle", kVis); }

// The feature models of issue 30: transparency, the file's lights, each material extension.
TEST(Golden, AlphaBlendModeTest) { feature_golden("AlphaBlendModeTest"); }
TEST(Golden, LightsPunctualLamp) { feature_golden("LightsPunctualLamp"); }
TEST(Golden, TransmissionTest) { feature_golden("TransmissionTest"); }
TEST(Golden, AttenuationTest) { feature_golden("AttenuationTest"); }
TEST(Golden, ClearCoatTest) { feature_golden("ClearCoatTest"); }
TEST(Golden, SheenChair) { feature_golden("SheenChair"); }
TEST(Golden, SpecularTest) { feature_golden("SpecularTest"); }
TEST(Golden, AnisotropyStrengthTest) { feature_golden("AnisotropyStrengthTest"); }
TEST(Golden, IridescenceSuzanne) { feature_golden("IridescenceSuzanne"); }
