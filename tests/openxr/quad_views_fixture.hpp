#pragma once
// The quad-views tests' fixture (openxr_quad_views_test.cpp and the other quad test files):
// runs examples/openxr_quad_views on Monado through the layer and reads its JSON lines.
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "foveal/core/gaze_log.hpp"
#include "openxr_harness.hpp"

namespace foveal::test {

using nlohmann::json;

inline constexpr const char* kLayerShare = FOVEAL_TEST_LAYER_SHARE;
inline constexpr int kQuad = 1000037000;  // XR_VIEW_CONFIGURATION_TYPE_PRIMARY_QUAD_VARJO

/// A view's field as tangents: left, right, down, up.
struct Tan {
  double l, r, d, u;
  double cx() const { return 0.5 * (l + r); }
  double cy() const { return 0.5 * (d + u); }
};
inline Tan tangents(const json& view) {
  const json& f = view["fov"];  // angles left, right, up, down
  return {std::tan(f[0].get<double>()), std::tan(f[1].get<double>()), std::tan(f[3].get<double>()),
          std::tan(f[2].get<double>())};
}

/// A native gaze log that looks along (tan_x, tan_y, -1) for `seconds` at 120 Hz, both
/// eyes open: a gaze that never moves, so whatever moves the inset is the layer's doing.
inline void write_fixation_log(const std::string& path, double seconds, double tan_x, double tan_y) {
  GazeLogHeader header;
  header.rate_hz = 120;
  auto w = GazeLogWriter::create(path, header);
  ASSERT_TRUE(w) << w.error().message;
  const glm::vec3 look = glm::normalize(glm::vec3(static_cast<float>(tan_x), static_cast<float>(tan_y), -1.0f));
  for (long i = 0; i < std::lround(seconds * 120); ++i) {
    GazeSample s;
    s.t_ns = i * 1'000'000'000 / 120;
    for (EyeSample* e : {&s.eyes[0], &s.eyes[1]}) *e = {kValidDirection | kValidOpenness, look, {}, 0.0f, 1.0f};
    s.combined = {kValidDirection, look};
    ASSERT_TRUE(w->write(s));
  }
  ASSERT_TRUE(w->commit());
}

class QuadViews : public test::OpenXRTest {
 protected:
  /// Runs the example to its end; its lines.
  std::vector<json> run_app(const std::vector<std::string>& args, const std::string& name,
                            const std::vector<std::string>& env = {}) {
    auto app = rig_.quad_app(args, env, name, kLayerShare);
    EXPECT_EQ(app->wait(240000), 0) << rig_.err(name);
    return rig_.lines(name);
  }
  static json event(const std::vector<json>& lines, const std::string& name) {
    for (const json& l : lines)
      if (l.is_object() && l.value("event", "") == name) return l;
    return json::object();
  }
  static std::vector<json> frames(const std::vector<json>& lines) {
    std::vector<json> f;
    for (const json& l : lines)
      if (l.is_object() && l.value("event", "") == "frame") f.push_back(l);
    return f;
  }
  /// The fixed inset's centre is the outer view's: true when every frame's inner views sit there.
  static int frames_at_the_fixed_place(const std::vector<json>& fs) {
    int n = 0;
    for (const json& f : fs) {
      bool fixed = true;
      for (int e = 0; e < 2; ++e) {
        const Tan o = tangents(f["views"][e]), i = tangents(f["views"][e + 2]);
        fixed &= std::abs(i.cx() - o.cx()) < 1e-4 && std::abs(i.cy() - o.cy()) < 1e-4 &&
                 std::abs((i.r - i.l) / (o.r - o.l) - 0.5) < 1e-3;
      }
      n += fixed;
    }
    return n;
  }

};

}  // namespace foveal::test
