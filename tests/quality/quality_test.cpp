// The data-quality measures on hand-made series whose values follow from the definitions
// in docs/quality.md.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "foveal/quality/gaze_quality.hpp"
#include "foveal/quality/quality_targets.hpp"
#include "test_support.hpp"
#include "turned_direction.hpp"

namespace foveal {
namespace {

AngleSample at(double az, double el) { return {true, {az, el}}; }

TEST(FickAngles, AxesFollowTheConventions) {
  const FickAngles f = fick_from_direction({0, 0, -1});
  EXPECT_DOUBLE_EQ(f.azimuth_deg, 0);
  EXPECT_DOUBLE_EQ(f.elevation_deg, 0);
  EXPECT_NEAR(fick_from_direction({1, 0, -1}).azimuth_deg, 45, 1e-12);   // right is positive
  EXPECT_NEAR(fick_from_direction({0, 2, -2}).elevation_deg, 45, 1e-12);  // up is positive, any length
  // Elevation is measured out of the horizontal plane after the azimuth turn.
  const FickAngles g = fick_from_direction({1, 1, -1});
  EXPECT_NEAR(g.azimuth_deg, 45, 1e-12);
  EXPECT_NEAR(g.elevation_deg, std::atan(1 / std::sqrt(2.0)) * 180 / std::numbers::pi, 1e-12);
  for (double az : {-40.0, -3.0, 0.0, 12.5})
    for (double el : {-30.0, 0.0, 7.25}) {
      const FickAngles r = fick_from_direction(direction_from_fick({az, el}));
      EXPECT_NEAR(r.azimuth_deg, az, 1e-12);
      EXPECT_NEAR(r.elevation_deg, el, 1e-12);
    }
}

TEST(ChannelQuality, MeasuresFollowTheirDefinitions) {
  // Azimuths 0, 1, (invalid), 3; elevation 0: one valid step of 1 degree.
  const std::vector<AngleSample> s = {at(0, 0), at(1, 0), AngleSample{}, at(3, 0)};
  const ChannelQuality q = measure_channel(s, 0.5, 10);
  EXPECT_EQ(q.samples, 4u);
  EXPECT_EQ(q.valid, 3u);
  EXPECT_EQ(q.s2s_pairs, 1u);  // steps across the invalid sample do not count
  EXPECT_DOUBLE_EQ(q.rms_s2s_deg, 1.0);
  EXPECT_DOUBLE_EQ(q.rms_s2s_y_deg, 0.0);
  EXPECT_NEAR(q.std_deg, std::sqrt(14.0 / 9.0), 1e-12);  // population STD of 0, 1, 3
  EXPECT_DOUBLE_EQ(q.bcea_deg2, 0.0);                    // no vertical spread: a line, no area
  EXPECT_DOUBLE_EQ(q.expected_samples, 5.0);
  EXPECT_DOUBLE_EQ(q.data_loss_pct, 40.0);  // 3 valid of 5 expected
  EXPECT_DOUBLE_EQ(q.invalid_pct, 25.0);    // 1 invalid of 4 recorded
  EXPECT_DOUBLE_EQ(q.effective_frequency_hz, 6.0);
}

TEST(ChannelQuality, BceaIsTheEllipseOfTheSampleCovariance) {
  // A cross: sample variances 2/3 each, no correlation.
  const std::vector<AngleSample> s = {at(1, 0), at(-1, 0), at(0, 1), at(0, -1)};
  const double k = -std::log(1 - 0.68);
  EXPECT_NEAR(measure_channel(s, 1, 4).bcea_deg2, 2 * k * std::numbers::pi * (2.0 / 3.0), 1e-12);
  // Perfectly correlated points lie on a line: rho = 1, no area.
  const std::vector<AngleSample> line = {at(0, 0), at(1, 2), at(2, 4)};
  EXPECT_NEAR(measure_channel(line, 1, 3).bcea_deg2, 0, 1e-12);
}

TEST(ChannelQuality, TooFewSamplesLeaveMeasuresUndefined) {
  const ChannelQuality none = measure_channel({}, 1, 120);
  EXPECT_TRUE(std::isnan(none.rms_s2s_deg));
  EXPECT_TRUE(std::isnan(none.std_deg));
  EXPECT_TRUE(std::isnan(none.bcea_deg2));
  EXPECT_DOUBLE_EQ(none.data_loss_pct, 100.0);
  const std::vector<AngleSample> one = {at(1, 1)};
  EXPECT_TRUE(std::isnan(measure_channel(one, 1, 120).bcea_deg2));
  EXPECT_DOUBLE_EQ(measure_channel(one, 1, 120).std_deg, 0.0);
}

TEST(MeanOffset, RecoversAKnownOffsetAndItsDirection) {
  const FickAngles target{10, -5};
  for (double toward : {0.0, 90.0, 180.0, 225.0}) {
    const std::vector<AngleSample> s = {{true, fick_from_direction(test::turned(target, 0.5, toward))}, AngleSample{}};
    const auto o = mean_offset(s, target);
    ASSERT_TRUE(o);
    EXPECT_EQ(o->samples, 1u);
    EXPECT_NEAR(o->offset_deg, 0.5, 1e-9) << toward;
    // The direction on the tangent screen through an off-axis target bends a little.
    EXPECT_NEAR(std::atan2(o->y_deg, o->x_deg) * 180 / std::numbers::pi, toward > 180 ? toward - 360 : toward, 1.5);
  }
  EXPECT_FALSE(mean_offset(std::vector<AngleSample>{AngleSample{}}, target));
}

GazeSample sample(TimeNs t, glm::vec3 l, glm::vec3 r) {
  GazeSample s;
  s.t_ns = t;
  s.eyes[0] = {kValidDirection, l};
  s.eyes[1] = {kValidDirection, r};
  return s;
}

TEST(GazeQuality, BinocularIsTheMeanOfTheEyesOrTheCombinedGaze) {
  const glm::vec3 fwd(0, 0, -1), right(std::sin(0.02f), 0, -std::cos(0.02f));
  std::vector<GazeSample> s;
  for (int i = 0; i < 10; ++i) s.push_back(sample(i * 10'000'000, fwd, i % 2 ? right : fwd));
  s[3].eyes[0].valid = 0;
  s[3].eyes[0].direction = {};
  auto q = compute_gaze_quality(s, 100, {});
  ASSERT_TRUE(q) << q.error().message;
  EXPECT_EQ(q->binocular_source, "mean of eyes");
  EXPECT_EQ(q->channels[2].valid, 9u);  // both eyes needed
  EXPECT_NEAR(q->duration_s(), 0.1, 1e-12);  // 10 samples, one interval each
  EXPECT_NEAR(q->channels[0].data_loss_pct, 10.0, 1e-9);
  // The right eye jumps 0.02 rad each sample; the mean direction half as far.
  EXPECT_NEAR(q->channels[1].rms_s2s_deg, 0.02 * 180 / std::numbers::pi, 1e-4);
  EXPECT_NEAR(q->channels[2].rms_s2s_deg, 0.01 * 180 / std::numbers::pi, 1e-4);

  for (auto& x : s) x.combined = {kValidDirection, fwd};
  q = compute_gaze_quality(s, 100, {});
  ASSERT_TRUE(q);
  EXPECT_EQ(q->binocular_source, "combined");
  EXPECT_EQ(q->channels[2].valid, 10u);
  EXPECT_DOUBLE_EQ(q->channels[2].rms_s2s_deg, 0.0);
}

TEST(GazeQuality, WindowsAndTargetsSelectTheirSamples) {
  std::vector<GazeSample> s;
  for (int i = 0; i < 100; ++i) s.push_back(sample(i * 10'000'000, {0, 0, -1}, {0, 0, -1}));
  QualityOptions o;
  o.start_s = 0.2;
  o.end_s = 0.5;
  o.targets = {{0.3, 0.4, {1, 0}, "t.csv:2"}, {0.45, 2.0, {0, 0}, "t.csv:3"}};
  auto q = compute_gaze_quality(s, 100, o);
  ASSERT_TRUE(q) << q.error().message;
  EXPECT_EQ(q->channels[0].samples, 30u);
  ASSERT_EQ(q->targets.size(), 2u);
  EXPECT_EQ(q->targets[0].channels[0].samples, 10u);
  EXPECT_NEAR(q->targets[0].offsets[0]->offset_deg, 1.0, 1e-9);
  EXPECT_NEAR(q->targets[0].offsets[0]->x_deg, -1.0, 1e-9);  // gaze left of the target
  EXPECT_DOUBLE_EQ(q->targets[1].end_s, 0.5);  // clipped to the window
  EXPECT_NEAR(q->accuracy[0].offset_deg, 0.5, 1e-9);  // mean of 1 and 0
  EXPECT_EQ(q->accuracy[0].targets, 2u);

  o.targets = {{2.0, 3.0, {0, 0}, "t.csv:7"}};
  q = compute_gaze_quality(s, 100, o);
  ASSERT_FALSE(q);
  EXPECT_NE(q.error().message.find("t.csv:7: the target's window"), std::string::npos) << q.error().message;

  o.targets.clear();
  o.start_s = 5;
  o.end_s = 6;
  q = compute_gaze_quality(s, 100, o);
  ASSERT_FALSE(q);
  EXPECT_NE(q.error().message.find("is empty"), std::string::npos) << q.error().message;
}

TEST(QualityTargets, ReadsTheFileAndNamesBadFields) {
  test::TempDir d;
  const std::string p = d.path("t.csv");
  test::write_file(p, "# fixation targets\nstart_s,end_s,azimuth_deg,elevation_deg,label\n1,2.5,-10,5,a\n3,4,0,0,b\n");
  auto t = read_quality_targets(p);
  ASSERT_TRUE(t) << t.error().message;
  ASSERT_EQ(t->size(), 2u);
  EXPECT_DOUBLE_EQ((*t)[0].end_s, 2.5);
  EXPECT_DOUBLE_EQ((*t)[0].at.azimuth_deg, -10);
  EXPECT_EQ((*t)[1].where, p + ":4");

  auto error_of = [&](const std::string& text) {
    test::write_file(p, text);
    auto r = read_quality_targets(p);
    return r ? std::string("(no error)") : r.error().message;
  };
  EXPECT_EQ(error_of("start_s,end_s,azimuth_deg\n"),
            p + ":1: column 'elevation_deg' is missing from the header (expected start_s,end_s,azimuth_deg,elevation_deg)");
  EXPECT_EQ(error_of("start_s,end_s,azimuth_deg,elevation_deg\n1,2,x,0\n"), p + ":2: azimuth_deg: 'x' is not a finite number");
  EXPECT_EQ(error_of("start_s,end_s,azimuth_deg,elevation_deg\n1,2,3\n"), p + ":2: row has 3 fields, header has 4");
  EXPECT_EQ(error_of("start_s,end_s,azimuth_deg,elevation_deg\n2,1,0,0\n"), p + ":2: end_s: must be greater than start_s");
  EXPECT_EQ(error_of("start_s,end_s,azimuth_deg,elevation_deg\n1,2,0,95\n"), p + ":2: elevation_deg: must lie in (-90, 90)");
  EXPECT_EQ(error_of("start_s,end_s,azimuth_deg,elevation_deg\n"), p + ": no targets: the file has a header only");
  EXPECT_EQ(error_of(""), p + ": file is empty; expected the header start_s,end_s,azimuth_deg,elevation_deg");
}

}  // namespace
}  // namespace foveal
