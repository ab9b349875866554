// The synthetic driver: determinism, truth that lines up, the main sequence, vergence.
#include <gtest/gtest.h>

#include <cmath>

#include "foveal/drivers/synthetic_source.hpp"

namespace foveal {
namespace {

struct Generated {
  std::vector<GazeSample> samples;
  std::vector<GazeTruth> truth;
};

Generated generate(std::uint64_t seed, double seconds = 60) {
  SyntheticOptions o;
  o.seed = seed;
  o.duration_s = seconds;
  SyntheticGenerator g(o);
  Generated r;
  GazeSample s;
  GazeTruth t;
  while (g.next(s, t)) {
    r.samples.push_back(s);
    r.truth.push_back(t);
  }
  return r;
}

double angle_deg(glm::vec3 a, glm::vec3 b) {
  const double d = std::clamp(static_cast<double>(a.x * b.x + a.y * b.y + a.z * b.z), -1.0, 1.0);
  return std::acos(d) * 180.0 / 3.14159265358979;
}

TEST(Synthetic, SameSeedSameOutputDifferentSeedDifferent) {
  const Generated a = generate(7), b = generate(7), c = generate(8);
  ASSERT_EQ(a.samples.size(), 7200u);
  EXPECT_EQ(a.samples, b.samples);
  for (std::size_t i = 0; i < a.truth.size(); ++i) {
    ASSERT_EQ(a.truth[i].event, b.truth[i].event);
    ASSERT_EQ(a.truth[i].azimuth_deg, b.truth[i].azimuth_deg);
  }
  EXPECT_NE(a.samples, c.samples);
}

TEST(Synthetic, TruthLinesUpWithTheSamples) {
  const Generated r = generate(3);
  int blinks = 0, saccades = 0, pursuits = 0;
  for (std::size_t i = 0; i < r.samples.size(); ++i) {
    const GazeSample& s = r.samples[i];
    const GazeTruth& t = r.truth[i];
    ASSERT_EQ(s.t_ns, t.t_ns);
    const bool blink = t.event == GazeEvent::blink;
    blinks += blink;
    saccades += t.event == GazeEvent::saccade;
    pursuits += t.event == GazeEvent::pursuit;
    for (int e = 0; e < 2; ++e) {
      ASSERT_EQ(s.eyes[e].has(kValidDirection), !blink) << i;
      if (!blink) {
        // Noise 0.5 deg RMS (2-D): 5 sigma is about 2.5 deg.
        EXPECT_LT(angle_deg(s.eyes[e].direction, t.direction[e]), 2.5) << i;
      } else {
        EXPECT_FLOAT_EQ(s.eyes[e].openness, 0.0f);
      }
    }
  }
  EXPECT_GT(blinks, 0);
  EXPECT_GT(saccades, 0);
  EXPECT_GT(pursuits, 0);
}

TEST(Synthetic, SaccadesFollowTheMainSequence) {
  SyntheticOptions o;
  o.seed = 11;
  o.duration_s = 120;
  o.noise_deg = 0;
  SyntheticGenerator g(o);
  GazeSample s;
  GazeTruth t, prev;
  std::vector<GazeTruth> all;
  while (g.next(s, t)) all.push_back(t);
  // Each saccade event (one event_index) moves by A degrees in 2.2 ms/deg * A + 21 ms.
  int checked = 0;
  for (std::size_t i = 1; i < all.size(); ++i) {
    if (!(all[i].event == GazeEvent::saccade && all[i - 1].event != GazeEvent::saccade)) continue;
    std::size_t j = i;
    while (j + 1 < all.size() && all[j + 1].event_index == all[i].event_index) ++j;
    const std::size_t start = i - 1;  // the sample before the fast part: where it left
    while (i < all.size() && all[i].event_index == all[start].event_index) ++i;
    const std::size_t end = std::min(j + 1, all.size() - 1);  // first sample of the next event
    const double amp = std::hypot(all[end].azimuth_deg - all[start].azimuth_deg, all[end].elevation_deg - all[start].elevation_deg);
    // Samples of this event, start included, span its duration to within one period.
    std::size_t first = start;
    while (first > 0 && all[first - 1].event_index == all[start].event_index) --first;
    const double dur_ms = static_cast<double>(all[end].t_ns - all[first].t_ns) / 1e6;
    EXPECT_NEAR(dur_ms, 2.2 * amp + 21.0, 1000.0 / 120.0 + 0.5) << "amplitude " << amp;
    ++checked;
  }
  EXPECT_GT(checked, 50);
}

TEST(Synthetic, EyesConvergeOnTheTargetDepth) {
  const Generated r = generate(5, 20);
  SyntheticOptions o;
  for (const GazeTruth& t : r.truth) {
    // The two eyes' rays from +-IPD/2 meet at the target distance.
    const glm::vec3 l = t.direction[0], rr = t.direction[1];
    const double ipd = o.ipd_mm / 1000.0;
    // Solve for the crossing along x: -ipd/2 + a*lx == ipd/2 + b*rx, a*lz == b*rz.
    const double a = ipd / (static_cast<double>(l.x) - static_cast<double>(rr.x) * l.z / rr.z);
    const double depth = -a * l.z;  // distance along -z
    ASSERT_NEAR(depth, t.depth_m * std::cos(t.azimuth_deg * 3.14159265358979 / 180) *
                           std::cos(t.elevation_deg * 3.14159265358979 / 180), 0.02 * t.depth_m);
  }
}

TEST(Synthetic, BadOptionsAreRejected) {
  SyntheticOptions o;
  o.rate_hz = 0;
  EXPECT_FALSE(o.validate());
  o = SyntheticOptions{};
  o.noise_deg = -1;
  EXPECT_FALSE(o.validate());
  o = SyntheticOptions{};
  o.saccade_deg_max = 1;  // below the minimum
  EXPECT_FALSE(o.validate());
  EXPECT_TRUE(SyntheticOptions{}.validate());
}

}  // namespace
}  // namespace foveal
