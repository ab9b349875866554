// The inset's levels chosen by perception (foveal/runtime/inset_levels.hpp): the table's
// checks, the cheapest (extent, σ) for a target, the quality key applied to a display
// model, and the tables committed for the bundled display models.
#include <gtest/gtest.h>

#include <cmath>

#include "foveal/core/display_model.hpp"
#include "foveal/runtime/inset_levels.hpp"

#include "test_support.hpp"

namespace foveal {
namespace {

constexpr double kPi = 3.14159265358979323846;

nlohmann::json table_json() {
  // A narrow inner view (10°) loses JOD fast with σ; a wide one (20°) holds it longer
  // but costs 0.26 of an eye's pixels for both eyes' inner views on the Vive.
  return {{"format", "foveal-jod-inset-levels v1"},
          {"display", "test"},
          {"sigmas", {2.0, 3.0, 4.0}},
          {"extents_deg", {10.0, 20.0}},
          {"jod", {{9.5, 9.1, 8.6}, {9.8, 9.6, 9.4}}}};
}

InsetLevelTable table() {
  auto t = InsetLevelTable::from_json(table_json(), "t");
  EXPECT_TRUE(t) << t.error().message;
  return *t;
}

const EyeFrustum kVive = DisplayModel::vive_pro_eye().eye(Eye::left);

double share(double deg, double span) { return 2 * std::tan(deg * kPi / 180) / span; }

TEST(InsetLevels, TheCheapestExtentAndLevelHoldTheTarget) {
  const double span_x = kVive.tan_right - kVive.tan_left, span_y = kVive.tan_top - kVive.tan_bottom;
  // 9.2: the 10° row reaches σ 2.75 (cost 2/2.75² + 0.061 = 0.326), the 20° row σ 4
  // (0.125 + 0.261 = 0.386): the narrow inset is cheaper.
  auto lo = choose_inset_levels(table(), 9.2, 1.0, kVive);
  ASSERT_TRUE(lo) << lo.error().message;
  EXPECT_DOUBLE_EQ(lo->extent_deg, 10);
  EXPECT_NEAR(lo->sigma_d, 2.75, 1e-12);
  EXPECT_NEAR(lo->sigma_nd, 2.75, 1e-12);
  EXPECT_NEAR(lo->jod_d, 9.2, 1e-12);
  EXPECT_NEAR(lo->share_x, share(10, span_x), 1e-9);
  EXPECT_NEAR(lo->share_y, share(10, span_y), 1e-9);
  EXPECT_NEAR(lo->cost, 2 / (2.75 * 2.75) + 2 * lo->share_x * lo->share_y, 1e-12);
  // 9.5: the 10° row stops at σ 2 (0.561), the 20° row reaches 3.5 (0.424): the wide one.
  auto hi = choose_inset_levels(table(), 9.5, 1.5, kVive);
  ASSERT_TRUE(hi);
  EXPECT_DOUBLE_EQ(hi->extent_deg, 20);
  EXPECT_NEAR(hi->sigma_d, 3.5, 1e-12);
  EXPECT_NEAR(hi->sigma_nd, 5.25, 1e-12);  // EFR: the profile's ratio
  EXPECT_TRUE(std::isnan(hi->jod_nd));     // past the grid's σ 4
}

TEST(InsetLevels, AHigherTargetNeverCostsLess) {
  double last = 0;
  for (double t : {8.0, 8.8, 9.0, 9.2, 9.4, 9.5, 9.7, 9.9, 10.0}) {
    auto l = choose_inset_levels(table(), t, 1.5, kVive);
    ASSERT_TRUE(l);
    EXPECT_GE(l->cost, last - 1e-12) << t;
    EXPECT_GE(l->jod_d, t - 1e-9) << t;
    last = l->cost;
  }
  EXPECT_DOUBLE_EQ(choose_inset_levels(table(), 10.0, 1.5, kVive)->sigma_d, 1.0);  // only full rendering holds 10
}

TEST(InsetLevels, AnExtentWiderThanTheViewIsTheWholeView) {
  auto j = table_json();
  j["extents_deg"] = {55.0};  // tan 55° = 1.43 > the Vive's 0.96 half-width
  j["jod"] = {{9.8, 9.6, 9.4}};
  auto t = InsetLevelTable::from_json(j, "t");
  ASSERT_TRUE(t);
  auto l = choose_inset_levels(*t, 9.5, 1.0, kVive);
  ASSERT_TRUE(l);
  EXPECT_DOUBLE_EQ(l->share_x, 1.0);
  EXPECT_DOUBLE_EQ(l->share_y, 1.0);
}

TEST(InsetLevels, BadTablesAndTargetsAreRefusedByName) {
  auto refused = [](nlohmann::json j, const std::string& what) {
    auto t = InsetLevelTable::from_json(j, "T.inset-levels.json");
    ASSERT_FALSE(t) << what;
    EXPECT_NE(t.error().message.find("T.inset-levels.json"), std::string::npos) << t.error().message;
    EXPECT_NE(t.error().message.find(what), std::string::npos) << t.error().message;
  };
  auto j = table_json();
  j["format"] = "foveal-jod-levels v1";  // an RMFR table is not an inset table
  refused(j, "format");
  j = table_json();
  j["extents_deg"] = {20.0, 10.0};
  refused(j, "increasing");
  j = table_json();
  j["extents_deg"] = {0.0, 10.0};
  refused(j, "extents_deg");
  j = table_json();
  j["sigmas"] = {1.0, 2.0, 4.0};
  refused(j, "sigmas");
  j = table_json();
  j["jod"][1] = {9.8, 9.4};
  refused(j, "jod[1]");
  j = table_json();
  j["jod"][0][0] = -1;
  refused(j, "[0, 10]");
  j = table_json();
  j["f"] = {0.3};
  refused(j, "unknown key 'f'");
  EXPECT_FALSE(choose_inset_levels(table(), 0, 1.5, kVive));
  EXPECT_FALSE(choose_inset_levels(table(), 10.5, 1.5, kVive));
  EXPECT_FALSE(choose_inset_levels(table(), 9, 0.5, kVive));
}

TEST(InsetLevels, TheQualityKeyChoosesFromTheModelsTableAndRefusesAnotherDisplays) {
  test::TempDir dir;
  const std::string model = dir.path("m.json");
  auto m = nlohmann::json::parse(test::read_file(test::source_path("data/display/htc_vive_pro_eye.json")));
  m["name"] = "test";
  test::write_file(model, m.dump());
  EXPECT_EQ(inset_levels_path(model), dir.path("m.inset-levels.json"));
  auto none = inset_quality("off", model, 1.5);
  ASSERT_TRUE(none);
  EXPECT_FALSE(none->has_value());
  auto missing = inset_quality("jod:9.5", model, 1.5);
  ASSERT_FALSE(missing);
  EXPECT_NE(missing.error().message.find("m.inset-levels.json"), std::string::npos) << missing.error().message;
  test::write_file(dir.path("m.inset-levels.json"), table_json().dump());
  auto l = inset_quality("jod:9.5", model, 1.5);
  ASSERT_TRUE(l) << l.error().message;
  ASSERT_TRUE(l->has_value());
  EXPECT_DOUBLE_EQ((*l)->extent_deg, 20);
  EXPECT_EQ((*l)->table, dir.path("m.inset-levels.json"));
  EXPECT_FALSE(inset_quality("jod:11", model, 1.5));
  auto t = table_json();
  t["display"] = "hires_3800_35ppd";
  test::write_file(dir.path("m.inset-levels.json"), t.dump());
  auto other = inset_quality("jod:9.5", model, 1.5);
  ASSERT_FALSE(other);
  EXPECT_NE(other.error().message.find("is the inset levels table of display 'hires_3800_35ppd', but the display model in use is 'test'"),
            std::string::npos)
      << other.error().message;
}

TEST(InsetLevels, TheBundledModelsTablesLoadAndChoose) {
  for (const char* name : {"htc_vive_pro_eye", "hires_3800_35ppd"}) {
    const std::string model = test::source_path(std::string("data/display/") + name + ".json");
    auto hi = inset_quality("jod:9.5", model, 1.5), lo = inset_quality("jod:9.0", model, 1.5);
    ASSERT_TRUE(hi) << hi.error().message;
    ASSERT_TRUE(lo) << lo.error().message;
    EXPECT_GT((*hi)->sigma_d, 1.0) << name;  // some foveation holds 9.5
    EXPECT_LE((*lo)->cost, (*hi)->cost) << name;
    EXPECT_GT((*hi)->share_x, 0.0) << name;
    EXPECT_LE((*hi)->share_x, 1.0) << name;
  }
}

}  // namespace
}  // namespace foveal
