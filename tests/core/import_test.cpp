// The importers on the real Vive Pro Eye recordings and on a Pupil Labs file.
#include <gtest/gtest.h>

#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>

#include "foveal/core/gaze_log.hpp"
#include "foveal/core/gaze_log_stats.hpp"
#include "foveal/core/text_fields.hpp"
#include "foveal/import/importers.hpp"
#include "test_support.hpp"

namespace foveal {
namespace {

// The SRanipal file's data rows, split, read independently of the importer.
std::vector<std::vector<std::string>> sranipal_rows(const std::string& path, std::vector<std::string>& header) {
  std::ifstream in(path);
  std::string line;
  std::vector<std::vector<std::string>> rows;
  auto split = [](std::string l) {
    if (!l.empty() && l.back() == '\r') l.pop_back();
    std::vector<std::string> f;
    std::stringstream ss(l);
    std::string x;
    while (std::getline(ss, x, ';')) f.push_back(x);
    return f;
  };
  std::getline(in, line);
  header = split(line);
  while (std::getline(in, line))
    if (line != "\r" && !line.empty()) rows.push_back(split(line));
  return rows;
}

std::size_t col(const std::vector<std::string>& header, const std::string& name) {
  return static_cast<std::size_t>(std::find(header.begin(), header.end(), name) - header.begin());
}

class ViveImport : public ::testing::TestWithParam<const char*> {};

TEST_P(ViveImport, OneSamplePerRowWithEyesTimesAndFramesRight) {
  test::TempDir dir;
  const std::string src = test::source_path(std::string("data/gaze/vive_pro_eye/") + GetParam() + ".csv");
  auto sum = import_sranipal(src, dir.path("log.csv"));
  ASSERT_TRUE(sum) << sum.error().message;
  std::vector<std::string> h;
  const auto rows = sranipal_rows(src, h);
  auto log = read_gaze_log(dir.path("log.csv"));
  ASSERT_TRUE(log) << log.error().message;
  ASSERT_EQ(log->size(), rows.size());
  EXPECT_EQ(sum->rows, rows.size());

  const long long tick0 = std::stoll(rows[0][col(h, "time(100ns)")]);
  int one_eye_only = 0;
  for (std::size_t i = 0; i < rows.size(); ++i) {
    const GazeSample& s = (*log)[i];
    EXPECT_EQ(s.t_ns, (std::stoll(rows[i][col(h, "time(100ns)")]) - tick0) * 100) << i;
    if (i > 0) {
      ASSERT_GT(s.t_ns, (*log)[i - 1].t_ns);
    }
    for (const char side : {'L', 'R'}) {
      const std::string sd(1, side);
      const bool dir_bit = (std::stoi(rows[i][col(h, "eye_valid_" + sd)]) & 2) != 0;
      const bool zero = std::stod(rows[i][col(h, "gaze_direct_" + sd + ".x")]) == 0 &&
                        std::stod(rows[i][col(h, "gaze_direct_" + sd + ".y")]) == 0 &&
                        std::stod(rows[i][col(h, "gaze_direct_" + sd + ".z")]) == 0;
      const EyeSample& e = s.eye(side == 'L' ? Eye::left : Eye::right);
      EXPECT_EQ(e.has(kValidDirection), dir_bit && !zero) << "row " << i << " eye " << side;
      if (e.has(kValidDirection)) {
        // SRanipal x left, +z forward -> foveal x right, -z forward.
        EXPECT_FLOAT_EQ(e.direction.x, -std::stof(rows[i][col(h, "gaze_direct_" + sd + ".x")]));
        EXPECT_FLOAT_EQ(e.direction.y, std::stof(rows[i][col(h, "gaze_direct_" + sd + ".y")]));
        EXPECT_FLOAT_EQ(e.direction.z, -std::stof(rows[i][col(h, "gaze_direct_" + sd + ".z")]));
      }
    }
    one_eye_only += s.eyes[0].has(kValidDirection) != s.eyes[1].has(kValidDirection);
  }
  EXPECT_GT(one_eye_only, 0) << "the recordings have rows invalid for one eye only";
  // The left eye sits at negative x in foveal's frame.
  EXPECT_LT((*log)[0].eyes[0].origin_mm.x, 0.0f);
  EXPECT_GT((*log)[0].eyes[1].origin_mm.x, 0.0f);

  auto st = compute_gaze_log_stats(dir.path("log.csv"));
  ASSERT_TRUE(st) << st.error().message;
  EXPECT_GE(st->estimated_rate_hz, 115.0);
  EXPECT_LE(st->estimated_rate_hz, 125.0);
  EXPECT_GT(st->blinks, 0u);
}

INSTANTIATE_TEST_SUITE_P(Recordings, ViveImport,
                         ::testing::Values("TESTNA01_2D_Fist3", "TESTNA05_360VR_Spread7", "TESTNA15_2D_Pen3"));

TEST(ViveImportTestna01, ValidateReportsTheBlinkAndTheLongRunAtTheEnd) {
  test::TempDir dir;
  ASSERT_TRUE(import_sranipal(test::source_path("data/gaze/vive_pro_eye/TESTNA01_2D_Fist3.csv"), dir.path("l.csv")));
  auto r = test::run(test::bin("foveal") + " log validate --json " + dir.path("l.csv"));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  EXPECT_EQ(j["samples"], 1518);
  EXPECT_NEAR(j["estimated_rate_hz"].get<double>(), 120.0, 1.0);
  const auto& runs = j["invalid_runs"];
  ASSERT_GE(runs.size(), 2u);
  EXPECT_EQ(runs.back()["kind"], "loss");
  EXPECT_EQ(runs.back()["at_end"], true);
  EXPECT_EQ(runs.back()["samples"], 199);
  EXPECT_EQ(j["blinks"], 1);
  for (const char* key : {"duration_s", "invalid_pct", "longest_gap_ms", "nominal_rate_hz", "format_version"})
    EXPECT_TRUE(j.contains(key)) << key;
}

TEST(BundledLog, EqualsAFreshImportByteForByte) {
  test::TempDir dir;
  ASSERT_TRUE(import_sranipal(test::source_path("data/gaze/vive_pro_eye/TESTNA01_2D_Fist3.csv"), dir.path("l.csv")));
  EXPECT_EQ(test::read_file(dir.path("l.csv")), test::read_file(test::source_path("data/gaze/vive_pro_eye_TESTNA01.csv")));
}

TEST(PupilImport, EyesConfidenceFramesAndTimes) {
  test::TempDir dir;
  // The documented gaze_positions.csv header; eye 0 is the right eye, eye 1 the left.
  test::write_file(dir.path("gaze_positions.csv"),
                   "gaze_timestamp,world_index,confidence,norm_pos_x,norm_pos_y,base_data,gaze_point_3d_x,"
                   "gaze_point_3d_y,gaze_point_3d_z,eye_center0_3d_x,eye_center0_3d_y,eye_center0_3d_z,gaze_normal0_x,"
                   "gaze_normal0_y,gaze_normal0_z,eye_center1_3d_x,eye_center1_3d_y,eye_center1_3d_z,gaze_normal1_x,"
                   "gaze_normal1_y,gaze_normal1_z\n"
                   "100.000,1,0.95,0.5,0.5,x,0,0,500,30,10,-20,0.1,0.2,0.9747,-30,10,-20,-0.1,0.2,0.9747\n"
                   "100.008,1,0.90,0.5,0.5,x,0,0,500,30,10,-20,0.0,0.0,1.0,,,,,,\n"
                   "100.017,2,0.50,0.5,0.5,x,0,0,500,30,10,-20,0.0,0.0,1.0,-30,10,-20,0.0,0.0,1.0\n");
  auto sum = import_pupil(dir.path("gaze_positions.csv"), dir.path("o.csv"));
  ASSERT_TRUE(sum) << sum.error().message;
  auto log = read_gaze_log(dir.path("o.csv"));
  ASSERT_TRUE(log) << log.error().message;
  ASSERT_EQ(log->size(), 3u);
  const GazeSample& a = (*log)[0];
  EXPECT_EQ(a.t_ns, 0);
  EXPECT_EQ((*log)[1].t_ns, 8'000'000);
  EXPECT_EQ((*log)[2].t_ns, 17'000'000);
  // Right eye = camera 0: (0.1, 0.2, 0.9747) -> y and z negated (after re-normalising).
  ASSERT_TRUE(a.eye(Eye::right).has(kValidDirection));
  EXPECT_GT(a.eye(Eye::right).direction.x, 0.09f);
  EXPECT_LT(a.eye(Eye::right).direction.y, -0.19f);
  EXPECT_LT(a.eye(Eye::right).direction.z, -0.97f);
  EXPECT_LT(a.eye(Eye::left).direction.x, -0.09f);
  EXPECT_FLOAT_EQ(a.eye(Eye::right).origin_mm.x, 30.0f);
  EXPECT_FLOAT_EQ(a.eye(Eye::right).origin_mm.y, -10.0f);
  // Monocular row: the left eye (camera 1) is empty, so invalid.
  EXPECT_TRUE((*log)[1].eye(Eye::right).has(kValidDirection));
  EXPECT_FALSE((*log)[1].eye(Eye::left).has(kValidDirection));
  // Confidence 0.5 < 0.6: both eyes invalid.
  EXPECT_FALSE((*log)[2].eye(Eye::right).has(kValidDirection));
  EXPECT_FALSE((*log)[2].eye(Eye::left).has(kValidDirection));
  EXPECT_EQ(sum->invalid[0], 2u);
  EXPECT_EQ(sum->invalid[1], 1u);
}

}  // namespace
}  // namespace foveal
