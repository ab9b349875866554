// Quad views from an array swapchain (issue 37): engines such as Unreal and Godot's
// multiview render every view into one swapchain of arraySize ≥ 2, each view's
// XrSwapchainSubImage.imageArrayIndex naming its layer. The layer composes those as it
// composes one swapchain a view (docs/openxr.md, "Composition"); here examples/
// openxr_quad_views --array on Monado's null compositor, through the layer, against the
// same app with separate swapchains.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>

#include "foveal/image/image.hpp"
#include "quad_views_fixture.hpp"

namespace foveal {
namespace {

using test::QuadViews;

// The two runs draw the same pixels (--still, --no-foveated: the fixed inset), and the
// composer keeps its taps inside each sub-image, so the clear colour beyond a smaller
// view's rectangle in its layer never bleeds in: the images differ only by the rounding of
// the texture coordinates (a view's rectangle is a share of a larger layer). Measured on
// llvmpipe: 95.2 dB, 9 pixels off by 1. Without the taps kept inside, 49.9 dB (max 27,
// along each eye's top and right edges); without array swapchains, no composed image.
constexpr double kMinPsnr = 70.0;
constexpr int kMaxAbs = 2;

TEST_F(QuadViews, AnArraySwapchainIsComposedAsSeparateSwapchainsAre) {
  std::filesystem::create_directories(rig_.path("separate"));
  std::filesystem::create_directories(rig_.path("array"));
  const std::vector<std::string> args = {"--frames", "6", "--still", "--no-foveated"};
  const auto separate = run_app(args, "separate",
                                {"FOVEAL_OPENXR_CAPTURE_DIR=" + rig_.path("separate"), "FOVEAL_OPENXR_CAPTURE_FRAME=2"});
  std::vector<std::string> array_args = args;
  array_args.push_back("--array");
  const auto array = run_app(array_args, "array",
                             {"FOVEAL_OPENXR_CAPTURE_DIR=" + rig_.path("array"), "FOVEAL_OPENXR_CAPTURE_FRAME=2"});
  ASSERT_EQ(event(array, "views").value("configuration", ""), "quad") << rig_.err("array");
  ASSERT_EQ(event(array, "views"), event(separate, "views"));
  EXPECT_EQ(rig_.err("array").find("could not be composed"), std::string::npos)
      << "the layer fell back to the outer views alone:\n" << rig_.err("array");

  // The layer writes the capture only for a frame it composed (both eyes).
  auto a = image::load(rig_.path("array/composed.png"));
  ASSERT_TRUE(a) << a.error().message << " (no composed frame from the array swapchain)\n" << rig_.err("array");
  auto s = image::load(rig_.path("separate/composed.png"));
  ASSERT_TRUE(s) << s.error().message << "\n" << rig_.err("separate");
  ASSERT_EQ(a->width, s->width);
  ASSERT_EQ(a->height, s->height);
  const double p = image::psnr(*s, *a);
  const int max_abs = image::max_abs_diff(*s, *a);
  std::printf("array swapchain against separate swapchains: PSNR %.1f dB, max |diff| %d\n", p, max_abs);
  EXPECT_TRUE(std::isinf(p) || p >= kMinPsnr) << "PSNR " << p << " dB";
  EXPECT_LE(max_abs, kMaxAbs);
}

}  // namespace
}  // namespace foveal
