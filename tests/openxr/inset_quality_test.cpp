// The quad views' sizes from the inset's JOD levels table (openxr/src/inset_quality.cpp,
// FOVEAL_OPENXR_QUALITY): off by default, the table's choice for foveald's EFR ratio
// where on, each eye's outer density at its own level, and problems said, not fatal.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include "foveal/runtime/inset_levels.hpp"
#include "inset_quality.hpp"
#include "test_support.hpp"

namespace foveal::openxr {
namespace {

// A display model "test" (the Vive's field of view) with a two-extent inset table: 9.5
// chooses the 20° inset at σ 3.5 with ratio 1 (tests/levels/inset_levels_test.cpp).
struct Model {
  test::TempDir dir;
  std::string path = dir.path("m.json");
  nlohmann::json table = {{"format", "foveal-jod-inset-levels v1"}, {"display", "test"}, {"sigmas", {2.0, 3.0, 4.0}},
                          {"extents_deg", {10.0, 20.0}}, {"jod", {{9.5, 9.1, 8.6}, {9.8, 9.6, 9.4}}}};
  Model() {
    auto m = nlohmann::json::parse(test::read_file(test::source_path("data/display/htc_vive_pro_eye.json")));
    m["name"] = "test";
    test::write_file(path, m.dump());
    test::write_file(dir.path("m.inset-levels.json"), table.dump());
  }
};

TEST(InsetQuality, OffLeavesTheSettingsAndFovealdsLevels) {
  Model m;
  for (const char* off : {"", "off"}) {
    const InsetQuality q = InsetQuality::from(off, m.path);
    EXPECT_FALSE(q.on());
    EXPECT_TRUE(q.problem().empty()) << q.problem();
    InsetSettings s;
    const float sigma[2] = {3.0f, 2.0f};
    float density[2] = {0.25f, 0.5f};
    EXPECT_FALSE(q.apply(sigma, s, density));
    EXPECT_FLOAT_EQ(s.foveated_share_x, 0.35f);
    EXPECT_FLOAT_EQ(density[0], 0.25f);
  }
}

TEST(InsetQuality, TheTableChoosesTheInsetAndEachEyesDensity) {
  Model m;
  const InsetQuality q = InsetQuality::from("jod:9.5", m.path);
  ASSERT_TRUE(q.on()) << q.problem();
  auto table = InsetLevelTable::from_json(m.table, "t");
  ASSERT_TRUE(table);
  const EyeFrustum eye = DisplayModel::vive_pro_eye().eye(Eye::left);
  // foveald's default pair: the right eye dominant at 2, the left at 3 (ratio 1.5).
  auto want = choose_inset_levels(*table, 9.5, 1.5, eye);
  ASSERT_TRUE(want);
  InsetSettings s;
  const float right_dominant[2] = {3.0f, 2.0f};
  float density[2] = {0, 0};
  ASSERT_TRUE(q.apply(right_dominant, s, density));
  EXPECT_FLOAT_EQ(s.foveated_share_x, static_cast<float>(want->share_x));
  EXPECT_FLOAT_EQ(s.foveated_share_y, static_cast<float>(want->share_y));
  EXPECT_FLOAT_EQ(density[1], static_cast<float>(1 / want->sigma_d));
  EXPECT_FLOAT_EQ(density[0], static_cast<float>(1 / want->sigma_nd));
  EXPECT_FLOAT_EQ(s.fixed_share_x, 0.5f);  // the fixed inset (no gaze) is not the table's
  // The left eye dominant: the levels swap eyes.
  const float left_dominant[2] = {2.0f, 3.0f};
  ASSERT_TRUE(q.apply(left_dominant, s, density));
  EXPECT_FLOAT_EQ(density[0], static_cast<float>(1 / want->sigma_d));
  EXPECT_FLOAT_EQ(density[1], static_cast<float>(1 / want->sigma_nd));
  // The sizes the app is asked for follow: the dominant eye's outer view at 1/σ_d.
  const std::uint32_t w[2] = {1440, 1440}, h[2] = {1600, 1600};
  const QuadSizes sizes = quad_sizes(w, h, density, s.foveated_share_x, s.foveated_share_y);
  EXPECT_EQ(sizes.width[0], static_cast<std::uint32_t>(std::lround(1440 / want->sigma_d)));
  EXPECT_EQ(sizes.width[2], static_cast<std::uint32_t>(std::lround(1440 * static_cast<float>(want->share_x))));
}

TEST(InsetQuality, AProblemIsSaidAndLeavesTheQualityOff) {
  Model m;
  auto says = [](const InsetQuality& q, const std::string& what) {
    EXPECT_FALSE(q.on());
    EXPECT_NE(q.problem().find("FOVEAL_OPENXR_QUALITY"), std::string::npos) << q.problem();
    EXPECT_NE(q.problem().find(what), std::string::npos) << q.problem();
  };
  says(InsetQuality::from("jod:11", m.path), "jod:11");
  says(InsetQuality::from("jod:9.5", m.dir.path("none.json")), "none.json");
  m.table["display"] = "other";
  test::write_file(m.dir.path("m.inset-levels.json"), m.table.dump());
  says(InsetQuality::from("jod:9.5", m.path), "display 'other'");
}

TEST(InsetQuality, TheBundledVivesTableIsFoundByName) {
  const InsetQuality q = InsetQuality::from("jod:9.5", "htc_vive_pro_eye");
  ASSERT_TRUE(q.on()) << q.problem();
  InsetSettings s;
  const float sigma[2] = {3.0f, 2.0f};
  float density[2] = {0, 0};
  ASSERT_TRUE(q.apply(sigma, s, density));
  EXPECT_GT(s.foveated_share_x, 0.0f);
  EXPECT_LT(density[1], 1.0f);  // some foveation holds 9.5
}

}  // namespace
}  // namespace foveal::openxr
