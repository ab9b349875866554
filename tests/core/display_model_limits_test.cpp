// Display models at the edges (issue 27, item 7): a frustum of ±1e-30 tangents and
// refresh rates between 0 and 1 Hz are refused naming the file; 0 Hz stays "any".
#include <gtest/gtest.h>

#include "foveal/core/display_model.hpp"
#include "test_support.hpp"

namespace foveal {
namespace {

std::string model_with(const std::string& extra) {
  return R"({"format":"foveal-display-model v1","eye_width":1440,"eye_height":1600,"ipd_mm":63)" + extra + "}";
}

Result<DisplayModel> load_text(const test::TempDir& d, const std::string& text) {
  test::write_file(d.path("m.json"), text);
  return DisplayModel::load(d.path("m.json"));
}

TEST(DisplayModelLimits, AFrustumNarrowerThanAHundredthOfATangentIsRefused) {
  test::TempDir d;
  for (const char* tangents : {R"({"left":-1e-30,"right":1e-30,"bottom":-1,"top":1})",
                               R"({"left":-1,"right":1,"bottom":-1e-30,"top":1e-30})",
                               R"({"left":0.5,"right":0.504,"bottom":-1,"top":1})"}) {
    SCOPED_TRACE(tangents);
    auto m = load_text(d, model_with(std::string(R"(,"right":{"tangents":)") + tangents + "}"));
    ASSERT_FALSE(m);
    EXPECT_EQ(m.error().kind, ErrorKind::bad_input);
    EXPECT_NE(m.error().message.find(d.path("m.json") + ": right frustum spans "), std::string::npos) << m.error().message;
    EXPECT_NE(m.error().message.find("must be at least 0.01"), std::string::npos) << m.error().message;
  }
  auto ok = load_text(d, model_with(R"(,"left":{"tangents":{"left":-0.006,"right":0.006,"bottom":-1,"top":1}})"));
  EXPECT_TRUE(ok) << ok.error().message;  // 0.012 wide
}

TEST(DisplayModelLimits, RefreshZeroMeansAnyAndBetweenZeroAndOneHzIsRefused) {
  test::TempDir d;
  auto any = load_text(d, model_with(R"(,"refresh_hz":0)"));
  ASSERT_TRUE(any) << any.error().message;
  EXPECT_EQ(any->refresh_hz, 0.0);  // docs/display-model.md: 0 or absent, any mode
  auto absent = load_text(d, model_with(""));
  ASSERT_TRUE(absent) << absent.error().message;
  EXPECT_EQ(absent->refresh_hz, 0.0);
  for (const char* hz : {"1e-30", "0.5", "-0.0001", "1000.5", "1e308"}) {
    SCOPED_TRACE(hz);
    auto m = load_text(d, model_with(std::string(R"(,"refresh_hz":)") + hz));
    ASSERT_FALSE(m);
    EXPECT_NE(m.error().message.find(d.path("m.json") + ": refresh_hz "), std::string::npos) << m.error().message;
    EXPECT_NE(m.error().message.find("must be 0 (any) or in [1, 1000] Hz"), std::string::npos) << m.error().message;
  }
  for (const char* hz : {"1", "90", "1000"}) EXPECT_TRUE(load_text(d, model_with(std::string(R"(,"refresh_hz":)") + hz))) << hz;
}

}  // namespace
}  // namespace foveal
