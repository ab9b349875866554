#include <gtest/gtest.h>

#include "foveal/drivers/vive/vive_reports.hpp"
#include "vive_report_builders.hpp"

namespace foveal::vive {
namespace {

using test::ViveImuBuilder;

ViveImuBuilder report(std::uint8_t first_seq, std::size_t first_slot) {
  ViveImuBuilder r;
  for (std::size_t k = 0; k < 3; ++k) {
    const std::int16_t a[3] = {static_cast<std::int16_t>(k), 2, 3}, g[3] = {4, 5, static_cast<std::int16_t>(-k)};
    r.sample((first_slot + k) % 3, a, g, 48000u * static_cast<std::uint32_t>(k), static_cast<std::uint8_t>(first_seq + k));
  }
  return r;
}

TEST(ViveImuReport, ParsesThreeSamples) {
  auto r = parse_imu_report(report(10, 0).b);
  ASSERT_TRUE(r) << r.error().message;
  EXPECT_EQ(r->samples[1].seq, 11);
  EXPECT_EQ(r->samples[2].accel[0], 2);
  EXPECT_EQ(r->samples[2].gyro[2], -2);
  EXPECT_EQ(r->samples[1].time, 48000u);
}

TEST(ViveImuReport, NewSamplesInOrderAcrossTheRoundRobin) {
  // Slots hold 254, 255, 0 starting at slot 1 (the sequence wraps).
  auto r = parse_imu_report(report(254, 1).b);
  ASSERT_TRUE(r) << r.error().message;
  auto all = new_imu_samples(*r, std::nullopt);
  ASSERT_EQ(all.size(), 3u);
  EXPECT_EQ(all[0].seq, 254);
  EXPECT_EQ(all[2].seq, 0);
  auto fresh = new_imu_samples(*r, std::uint8_t{255});  // 254 and 255 seen
  ASSERT_EQ(fresh.size(), 1u);
  EXPECT_EQ(fresh[0].seq, 0);
  EXPECT_TRUE(new_imu_samples(*r, std::uint8_t{0}).empty());
}

TEST(ViveImuReport, RejectsTruncatedAndMalformed) {
  const ViveImuBuilder good = report(1, 0);
  for (std::size_t n : {std::size_t{0}, std::size_t{1}, std::size_t{51}}) {
    auto r = parse_imu_report(std::span<const std::uint8_t>(good.b.data(), n));
    ASSERT_FALSE(r) << n;
    EXPECT_EQ(r.error().kind, ErrorKind::bad_input);
  }
  std::vector<std::uint8_t> longer = good.b;
  longer.push_back(0);
  EXPECT_FALSE(parse_imu_report(longer));
  ViveImuBuilder id = good;
  id.b[0] = 0x21;
  EXPECT_FALSE(parse_imu_report(id.b));
  ViveImuBuilder seq = good;
  seq.b[1 + 16] = 99;  // slot 0's sequence number no longer fits
  auto r = parse_imu_report(seq.b);
  ASSERT_FALSE(r);
  EXPECT_NE(r.error().message.find("sequence"), std::string::npos);
}

TEST(ViveRangeReport, DecodesCodesAndRejectsOthers) {
  std::vector<std::uint8_t> rep(kRangeReportBytes, 0);
  rep[0] = kRangeReportId, rep[1] = 1, rep[2] = 1;
  auto r = parse_range_report(rep);
  ASSERT_TRUE(r) << r.error().message;
  EXPECT_NEAR(r->gyro_rad_s, 500.0 * 3.14159265358979323846 / 180.0, 1e-9);
  EXPECT_NEAR(r->accel_m_s2, 4 * 9.80665, 1e-9);
  rep[2] = 5;
  EXPECT_FALSE(parse_range_report(rep));
  EXPECT_FALSE(parse_range_report(std::span<const std::uint8_t>(rep.data(), 2)));
}

TEST(ViveConfigReports, AssembleAndInflate) {
  std::string json = "{\"model_number\": \"VIVE_Pro MV\", \"pad\": \"";
  json += std::string(3000, 'x') + "\"}";
  ConfigAssembler a;
  for (const auto& rep : test::vive_config_reports(json)) ASSERT_TRUE(a.add(rep));
  ASSERT_TRUE(a.complete());
  auto text = a.json();
  ASSERT_TRUE(text) << text.error().message;
  EXPECT_EQ(*text, json);
}

TEST(ViveConfigReports, RejectsMalformedAndTruncated) {
  std::string numbers;  // numbers compress little, so the stream spans several reports
  for (int i = 0; i < 200; ++i) numbers += std::to_string(i * 7919 % 1000) + ",";
  auto reports = test::vive_config_reports(numbers);
  ASSERT_GE(reports.size(), 3u);
  {
    ConfigAssembler a;  // a length over 62
    auto bad = reports[0];
    bad[1] = 63;
    EXPECT_FALSE(a.add(bad));
  }
  {
    ConfigAssembler a;  // a report shorter than its length
    EXPECT_FALSE(a.add(std::span<const std::uint8_t>(reports[0].data(), 10)));
  }
  {
    ConfigAssembler a;  // the wrong id
    auto bad = reports[0];
    bad[0] = 0x10;
    EXPECT_FALSE(a.add(bad));
  }
  {
    ConfigAssembler a;  // ended early: a truncated zlib stream
    ASSERT_TRUE(a.add(reports[0]));
    std::vector<std::uint8_t> end(kConfigReportBytes, 0);
    end[0] = kConfigReadReportId;
    ASSERT_TRUE(a.add(end));
    auto text = a.json();
    ASSERT_FALSE(text);
    EXPECT_NE(text.error().message.find("zlib"), std::string::npos) << text.error().message;
  }
  {
    ConfigAssembler a;  // never ended
    ASSERT_TRUE(a.add(reports[0]));
    EXPECT_FALSE(a.json());
  }
  {
    ConfigAssembler a;  // corrupted bytes
    auto bad = reports[0];
    bad[2] ^= 0xff;
    ASSERT_TRUE(a.add(bad));
    for (std::size_t i = 1; i < reports.size(); ++i) ASSERT_TRUE(a.add(reports[i]));
    EXPECT_FALSE(a.json());
  }
}

}  // namespace
}  // namespace foveal::vive
