// Levels chosen by perception (foveal/runtime/jod_levels.hpp): the table's checks, the
// choice of the cheapest levels, the profile key, and the tables committed for the
// bundled display models.
#include <gtest/gtest.h>

#include <cmath>

#include "foveal/core/display_model.hpp"
#include "foveal/runtime/jod_levels.hpp"

#include "test_support.hpp"

namespace foveal {
namespace {

nlohmann::json table_json() {
  // Two f: the second holds JOD longer; JOD falls linearly in σ.
  return {{"format", "foveal-jod-levels v1"},
          {"display", "test"},
          {"sigmas", {2.0, 3.0, 4.0}},
          {"f", {0.2, 0.4}},
          {"jod", {{9.5, 9.0, 8.5}, {9.8, 9.4, 9.0}}}};
}

// A display model file named `name` (the bundled Vive's, renamed) at `path`.
void write_model(const std::string& path, const std::string& name) {
  auto j = nlohmann::json::parse(test::read_file(test::source_path("data/display/htc_vive_pro_eye.json")));
  j["name"] = name;
  test::write_file(path, j.dump());
}

JodLevelTable table() {
  auto t = JodLevelTable::from_json(table_json(), "t");
  EXPECT_TRUE(t) << t.error().message;
  return *t;
}

TEST(JodLevels, TheCheapestLevelsAreWherePredictedJodCrossesTheTarget) {
  auto l = choose_jod_levels(table(), 9.2, 1.5);
  ASSERT_TRUE(l) << l.error().message;
  // f 0.4 crosses 9.2 halfway between σ 3 (9.4) and σ 4 (9.0); f 0.2 already at σ 2.6.
  EXPECT_DOUBLE_EQ(l->f, 0.4);
  EXPECT_NEAR(l->sigma_d, 3.5, 1e-12);
  EXPECT_NEAR(l->jod_d, 9.2, 1e-12);
  EXPECT_NEAR(l->sigma_nd, 5.25, 1e-12);
  EXPECT_TRUE(std::isnan(l->jod_nd));  // past the grid's σ 4: the table does not say
}

TEST(JodLevels, AHigherTargetNeverChoosesCheaperLevels) {
  double last = 16;
  for (double t : {8.0, 8.6, 9.0, 9.2, 9.5, 9.7, 9.9, 10.0}) {
    auto l = choose_jod_levels(table(), t, 1.0);
    ASSERT_TRUE(l);
    EXPECT_LE(l->sigma_d, last) << t;
    EXPECT_GE(l->jod_d, t - 1e-9) << t;
    last = l->sigma_d;
  }
  EXPECT_DOUBLE_EQ(last, 1.0);  // JOD 10: only full rendering holds it
}

TEST(JodLevels, BetweenOneAndTheFirstLevelTheReferenceIsJodTen) {
  auto l = choose_jod_levels(table(), 9.9, 1.0);
  ASSERT_TRUE(l);
  EXPECT_NEAR(l->sigma_d, 1 + (10 - 9.9) / (10 - 9.8) * 1.0, 1e-12);  // f 0.4: 10 at σ 1, 9.8 at σ 2
  EXPECT_NEAR(table().predict(1, 1.5), 9.9, 1e-12);
}

TEST(JodLevels, BadTablesAndTargetsAreRefusedByName) {
  auto refused = [](nlohmann::json j, const std::string& what) {
    auto t = JodLevelTable::from_json(j, "T.levels.json");
    ASSERT_FALSE(t) << what;
    EXPECT_NE(t.error().message.find("T.levels.json"), std::string::npos) << t.error().message;
    EXPECT_NE(t.error().message.find(what), std::string::npos) << t.error().message;
  };
  auto j = table_json();
  j["format"] = "v0";
  refused(j, "format");
  j = table_json();
  j["sigmas"] = {3.0, 2.0, 4.0};
  refused(j, "increasing");
  j = table_json();
  j["sigmas"] = {1.0, 2.0, 4.0};
  refused(j, "sigmas");
  j = table_json();
  j["jod"][1] = {9.8, 9.4};
  refused(j, "jod[1]");
  j = table_json();
  j["jod"][0][0] = 10.5;
  refused(j, "[0, 10]");
  j = table_json();
  j["colour"] = 1;
  refused(j, "unknown key 'colour'");
  EXPECT_FALSE(choose_jod_levels(table(), 0, 1.5));
  EXPECT_FALSE(choose_jod_levels(table(), 10.5, 1.5));
  EXPECT_FALSE(choose_jod_levels(table(), 9, 0.5));
}

TEST(JodLevels, TheQualityKeyParsesJodTargetsOnly) {
  EXPECT_FALSE(parse_quality("", "p").value());
  EXPECT_FALSE(parse_quality("off", "p").value());
  EXPECT_DOUBLE_EQ(*parse_quality("jod:9.5", "p").value(), 9.5);
  for (const char* bad : {"jod:", "jod:11", "jod:0", "jod:nan", "9.5", "jod:9.5x", "psnr:30"}) {
    auto q = parse_quality(bad, "p");
    ASSERT_FALSE(q) << bad;
    EXPECT_NE(q.error().message.find("quality"), std::string::npos);
  }
  Profile p;
  EXPECT_FALSE(p.set("quality", "jod:12"));
  ASSERT_TRUE(p.set("quality", "jod:9"));
  EXPECT_EQ(p.quality, "jod:9");
  EXPECT_EQ(p.to_json()["quality"], "jod:9");
  ASSERT_TRUE(p.set("quality", "off"));
  EXPECT_TRUE(p.quality.empty());
  EXPECT_FALSE(p.to_json().contains("quality"));  // profiles written before the key read alike
}

TEST(JodLevels, AProfilesQualityReplacesItsLevelsAndKeepsItsEfrRatio) {
  test::TempDir dir;
  const std::string model = dir.path("m.json");
  write_model(model, "test");  // the table's display
  test::write_file(dir.path("m.levels.json"), table_json().dump());
  EXPECT_EQ(jod_levels_path(model), dir.path("m.levels.json"));
  Profile p;  // σ 2 / 3: ratio 1.5
  p.quality = "jod:9.4";
  JodLevels chosen;
  auto r = apply_quality(p, model, &chosen);
  ASSERT_TRUE(r) << r.error().message;
  EXPECT_NEAR(r->sigma_d, 3.0, 1e-12);
  EXPECT_NEAR(r->sigma_nd, 4.5, 1e-12);
  EXPECT_DOUBLE_EQ(*r->f_x, 0.4);
  EXPECT_DOUBLE_EQ(*r->f_y, 0.4);
  EXPECT_EQ(chosen.table, dir.path("m.levels.json"));
  p.quality.clear();
  EXPECT_DOUBLE_EQ(apply_quality(p, model)->sigma_d, 2.0);  // off: the profile's own
  p.quality = "jod:9";
  auto missing = apply_quality(p, dir.path("other.json"));
  ASSERT_FALSE(missing);
  EXPECT_NE(missing.error().message.find("other.levels.json"), std::string::npos) << missing.error().message;
}

// Issue 38, item 17: RMFR's f stays where the compositor is tested (docs/stability.md:
// 0.01 to 10); f = 1e-300 was chosen as it stood.
TEST(JodLevels, AnFOutsideTheTestedRangeIsRefused) {
  for (const nlohmann::json& fs : {nlohmann::json{1e-300, 0.4}, nlohmann::json{0.005, 0.4}, nlohmann::json{0.4, 50.0}}) {
    auto j = table_json();
    j["f"] = fs;
    auto t = JodLevelTable::from_json(j, "T.levels.json");
    ASSERT_FALSE(t) << fs.dump();
    EXPECT_NE(t.error().message.find("T.levels.json: f: expected numbers in [0.01, 10] (RMFR's f where the compositor is tested)"),
              std::string::npos)
        << t.error().message;
  }
  auto j = table_json();
  j["f"] = {0.01, 10.0};  // the ends are tested
  EXPECT_TRUE(JodLevelTable::from_json(j, "T.levels.json"));
}

// Issue 38, item 17: a table measured on another display was used for the Vive's model.
TEST(JodLevels, ATableOfAnotherDisplayIsRefusedNamingBoth) {
  test::TempDir dir;
  const std::string model = dir.path("vive.json");
  write_model(model, "htc_vive_pro_eye");
  auto t = table_json();
  t["display"] = "hires_3800_35ppd";
  test::write_file(dir.path("vive.levels.json"), t.dump());
  Profile p;
  p.quality = "jod:9";
  auto r = apply_quality(p, model);
  ASSERT_FALSE(r);
  EXPECT_EQ(r.error().kind, ErrorKind::bad_input);
  EXPECT_NE(r.error().message.find(dir.path("vive.levels.json") + " is the levels table of display 'hires_3800_35ppd', but the "
                                   "display model in use is 'htc_vive_pro_eye' (" + model + ")"),
            std::string::npos)
      << r.error().message;
}

TEST(JodLevels, TheBundledModelsTablesLoadAndChoose) {
  for (const char* name : {"htc_vive_pro_eye", "hires_3800_35ppd"}) {
    auto t = JodLevelTable::load(jod_levels_path(test::source_path(std::string("data/display/") + name + ".json")));
    ASSERT_TRUE(t) << t.error().message;
    EXPECT_EQ(t->display, name);
    auto hi = choose_jod_levels(*t, 9.5, 1.5), lo = choose_jod_levels(*t, 9.0, 1.5);
    ASSERT_TRUE(hi && lo);
    EXPECT_GT(hi->sigma_d, 1.0) << name;  // some foveation holds 9.5
    EXPECT_GE(lo->sigma_d, hi->sigma_d) << name;
  }
}

}  // namespace
}  // namespace foveal
