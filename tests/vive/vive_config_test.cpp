#include <gtest/gtest.h>

#include <fstream>
#include <sstream>

#include <nlohmann/json.hpp>

#include "foveal/drivers/vive/vive_config.hpp"

namespace foveal::vive {
namespace {

std::string example() {
  std::ifstream in(FOVEAL_SOURCE_DIR "/data/headset/vive_pro_config_example.json");
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

TEST(ViveConfig, ReadsDisplayLensAndImuCalibration) {
  auto c = parse_config(example());
  ASSERT_TRUE(c) << c.error().message;
  EXPECT_EQ(c->model_number, "VIVE_Pro MV");
  EXPECT_EQ(c->variant, Variant::vive_pro);
  EXPECT_EQ(c->eye_width, 1440);
  EXPECT_EQ(c->eye_height, 1600);
  EXPECT_DOUBLE_EQ(c->ipd_m, 0.0635);
  EXPECT_DOUBLE_EQ(c->eyes[0].fx, 0.90);
  EXPECT_DOUBLE_EQ(c->eyes[1].cx, -0.02);
  EXPECT_DOUBLE_EQ(c->eyes[0].grow_for_undistort, 0.6);
  EXPECT_DOUBLE_EQ(c->eyes[0].rgb[0].coeffs[0], 0.28);  // red
  EXPECT_DOUBLE_EQ(c->eyes[0].rgb[2].coeffs[1], 0.20);  // blue
  EXPECT_DOUBLE_EQ(c->eyes[1].rgb[1].center_x, -0.02);  // green
  EXPECT_FLOAT_EQ(c->gyro_bias.y, -0.003f);
  EXPECT_FLOAT_EQ(c->acc_scale.x, 1.001f);
}

std::string without(const std::string& pointer) {
  nlohmann::json j = nlohmann::json::parse(example());
  j.at(nlohmann::json::json_pointer(pointer.substr(0, pointer.rfind('/'))))
      .erase(pointer.substr(pointer.rfind('/') + 1));
  return j.dump();
}

std::string with(const std::string& pointer, const nlohmann::json& v) {
  nlohmann::json j = nlohmann::json::parse(example());
  j[nlohmann::json::json_pointer(pointer)] = v;
  return j.dump();
}

void expect_error(const std::string& json, const std::string& needle) {
  auto c = parse_config(json);
  ASSERT_FALSE(c) << needle;
  EXPECT_EQ(c.error().kind, ErrorKind::bad_input);
  EXPECT_NE(c.error().message.find(needle), std::string::npos) << c.error().message;
}

TEST(ViveConfig, ErrorsNameTheKey) {
  expect_error("{not json", "not valid JSON");
  expect_error(without("/model_number"), "model_number");
  expect_error(without("/device/eye_target_width_in_pixels"), "device.eye_target_width_in_pixels: missing");
  expect_error(with("/device/eye_target_height_in_pixels", 0), "eye_target_height_in_pixels");
  expect_error(with("/tracking_to_eye_transform/1/intrinsics", nlohmann::json::array({1, 2})),
               "tracking_to_eye_transform[1].intrinsics: expected a 3x3");
  expect_error(with("/tracking_to_eye_transform/0/distortion/coeffs", nlohmann::json::array({1})),
               "tracking_to_eye_transform[0].distortion.coeffs");
  expect_error(with("/tracking_to_eye_transform/0/distortion_red/type", "DISTORT_POLY9"), "DISTORT_DPOLY3");
  expect_error(with("/lens_separation", 3.0), "lens_separation");
  expect_error(with("/imu/gyro_bias", nlohmann::json::array({1, 2})), "imu.gyro_bias");
  expect_error(with("/tracking_to_eye_transform", nlohmann::json::array()), "tracking_to_eye_transform");
}

TEST(ViveConfig, ImuCalibrationAndAxes) {
  auto c = parse_config(example());
  ASSERT_TRUE(c);
  ImuRawSample s;
  s.gyro = {16384, 0, 0};  // half the range about sensor x
  s.accel = {0, 8192, 0};  // a quarter of the range along sensor y
  const ImuRange range;   // ±500 °/s, ±4 g
  const ImuSample out = imu_to_sample(s, *c, range);
  // Vive Pro: x and z flip (Monado's mapping), after scale and bias.
  EXPECT_NEAR(out.gyro_rad_s.x, -(range.gyro_rad_s / 2 - 0.002), 1e-4);
  EXPECT_NEAR(out.gyro_rad_s.y, 0.003, 1e-6);
  EXPECT_NEAR(out.accel_m_s2.y, range.accel_m_s2 / 4 * 0.998 + 0.1, 1e-3);
}

}  // namespace
}  // namespace foveal::vive
