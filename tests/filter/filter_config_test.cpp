#include <gtest/gtest.h>

#include "foveal/runtime/filter_config.hpp"

namespace foveal {
namespace {

TEST(FilterConfig, DefaultsAreValidAndRoundTrip) {
  FilterConfig c;
  EXPECT_TRUE(c.validate("x"));
  auto back = FilterConfig::from_json(c.to_json(), "x");
  ASSERT_TRUE(back) << back.error().message;
  EXPECT_EQ(back->to_json(), c.to_json());
}

struct Bad {
  const char* name;
  const char* json;
  const char* expect;
};
class FilterConfigRejects : public ::testing::TestWithParam<Bad> {};

TEST_P(FilterConfigRejects, AtLoadWithAClearMessage) {
  auto c = FilterConfig::from_json(nlohmann::json::parse(GetParam().json), "alice.json");
  ASSERT_FALSE(c) << GetParam().name;
  EXPECT_NE(c.error().message.find("alice.json"), std::string::npos) << c.error().message;
  EXPECT_NE(c.error().message.find(GetParam().expect), std::string::npos) << c.error().message;
}

INSTANTIATE_TEST_SUITE_P(
    Cases, FilterConfigRejects,
    ::testing::Values(Bad{"negative_cutoff", R"({"min_cutoff_hz": -1})", "min_cutoff_hz"},
                      Bad{"zero_cutoff", R"({"d_cutoff_hz": 0})", "d_cutoff_hz"},
                      Bad{"zero_threshold", R"({"saccade_velocity_deg_s": 0})", "saccade_velocity_deg_s"},
                      Bad{"zero_deviation", R"({"saccade_deviation_deg": 0})", "saccade_deviation_deg"},
                      Bad{"negative_beta", R"({"beta": -0.1})", "beta"},
                      Bad{"negative_hold", R"({"hold_ms": -5})", "hold_ms"},
                      Bad{"openness_one", R"({"min_openness": 1})", "min_openness"},
                      Bad{"min_samples_zero", R"({"saccade_min_samples": 0})", "saccade_min_samples"},
                      Bad{"min_samples_fraction", R"({"saccade_min_samples": 1.5})", "integer"},
                      Bad{"prediction_too_far", R"({"predict_ms": 500})", "predict_ms"},
                      Bad{"not_a_number", R"({"beta": "high"})", "expected a number"},
                      Bad{"unknown", R"({"smoothness": 3})", "unknown key 'smoothness'"},
                      Bad{"aware_not_bool", R"({"saccade_aware": 1})", "true or false"}),
    [](const auto& param_info) { return std::string(param_info.param.name); });

TEST(FilterConfig, NanIsRejected) {
  FilterConfig c;
  c.one_euro.min_cutoff_hz = std::nan("");
  EXPECT_FALSE(c.validate("x"));
  c = FilterConfig{};
  c.saccade_velocity_deg_s = std::numeric_limits<double>::infinity();
  EXPECT_FALSE(c.validate("x"));
}

}  // namespace
}  // namespace foveal
