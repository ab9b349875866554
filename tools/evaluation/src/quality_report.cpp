#include "foveal/evaluation/quality_report.hpp"

#include <array>
#include <cmath>
#include <cstdio>

namespace foveal::evaluation {

namespace {

constexpr std::array<QualityChannel, kQualityChannels> kChannels = {QualityChannel::left, QualityChannel::right,
                                                                    QualityChannel::binocular};

nlohmann::json channel_json(const ChannelQuality& c) {
  return {{"samples", c.samples},
          {"valid", c.valid},
          {"expected_samples", c.expected_samples},
          {"data_loss_pct", c.data_loss_pct},
          {"invalid_pct", c.invalid_pct},
          {"effective_frequency_hz", c.effective_frequency_hz},
          {"s2s_pairs", c.s2s_pairs},
          {"rms_s2s_deg", c.rms_s2s_deg},
          {"rms_s2s_x_deg", c.rms_s2s_x_deg},
          {"rms_s2s_y_deg", c.rms_s2s_y_deg},
          {"std_deg", c.std_deg},
          {"std_x_deg", c.std_x_deg},
          {"std_y_deg", c.std_y_deg},
          {"bcea_deg2", c.bcea_deg2}};
}

}  // namespace

nlohmann::json quality_json(const std::string& path, const GazeQuality& q) {
  nlohmann::json channels, accuracy, targets = nlohmann::json::array();
  for (QualityChannel c : kChannels) {
    const auto i = static_cast<std::size_t>(c);
    channels[quality_channel_name(c)] = channel_json(q.channels[i]);
    const Accuracy& a = q.accuracy[i];
    accuracy[quality_channel_name(c)] = {
        {"offset_deg", a.offset_deg}, {"x_deg", a.x_deg}, {"y_deg", a.y_deg}, {"targets", a.targets}};
  }
  for (const TargetQuality& t : q.targets) {
    nlohmann::json per;
    for (QualityChannel c : kChannels) {
      const auto i = static_cast<std::size_t>(c);
      nlohmann::json j = channel_json(t.channels[i]);
      const auto& o = t.offsets[i];
      j["offset_deg"] = o ? o->offset_deg : ChannelQuality::kNaN;
      j["offset_x_deg"] = o ? o->x_deg : ChannelQuality::kNaN;
      j["offset_y_deg"] = o ? o->y_deg : ChannelQuality::kNaN;
      per[quality_channel_name(c)] = std::move(j);
    }
    targets.push_back({{"where", t.target.where},
                       {"azimuth_deg", t.target.at.azimuth_deg},
                       {"elevation_deg", t.target.at.elevation_deg},
                       {"start_s", t.start_s},
                       {"end_s", t.end_s},
                       {"channels", std::move(per)}});
  }
  nlohmann::json j = {{"file", path},
                      {"nominal_rate_hz", q.rate_hz},
                      {"median_interval_ms", q.median_interval_ms},
                      {"window", {{"start_s", q.start_s}, {"end_s", q.end_s}, {"duration_s", q.duration_s()}}},
                      {"binocular_source", q.binocular_source},
                      {"bcea_probability", kBceaProbability},
                      {"channels", channels},
                      {"targets", targets}};
  if (!q.targets.empty()) j["accuracy"] = accuracy;
  return j;
}

static void print_row(const char* label, const GazeQuality& q, double ChannelQuality::*field, const char* format) {
  std::printf("  %-24s", label);
  for (const ChannelQuality& c : q.channels) {
    const double v = c.*field;
    if (std::isnan(v)) std::printf("%12s", "-");
    else std::printf(format, v);
  }
  std::printf("\n");
}

void print_quality_text(const std::string& path, const GazeQuality& q) {
  std::printf("%s: %.3f-%.3f s (%.3f s), %.6g Hz nominal, median interval %.2f ms\n", path.c_str(), q.start_s,
              q.end_s, q.duration_s(), q.rate_hz, q.median_interval_ms);
  std::printf("  %-24s%12s%12s%12s  (binocular: %s)\n", "", "left", "right", "binocular", q.binocular_source.c_str());
  print_row("data loss %", q, &ChannelQuality::data_loss_pct, "%12.2f");
  print_row("effective frequency Hz", q, &ChannelQuality::effective_frequency_hz, "%12.2f");
  print_row("RMS-S2S deg", q, &ChannelQuality::rms_s2s_deg, "%12.4f");
  print_row("STD deg", q, &ChannelQuality::std_deg, "%12.4f");
  print_row("BCEA (68%) deg2", q, &ChannelQuality::bcea_deg2, "%12.4f");
  if (q.targets.empty()) return;
  std::printf("  %-24s", "accuracy deg");
  for (const Accuracy& a : q.accuracy) {
    if (std::isnan(a.offset_deg)) std::printf("%12s", "-");
    else std::printf("%12.4f", a.offset_deg);
  }
  std::printf("  (mean over %zu targets)\n", q.targets.size());
  for (const TargetQuality& t : q.targets) {
    std::printf("    target (%7.2f, %6.2f) deg  %7.3f-%7.3f s", t.target.at.azimuth_deg, t.target.at.elevation_deg,
                t.start_s, t.end_s);
    for (const auto& o : t.offsets) {
      if (o) std::printf("%10.4f", o->offset_deg);
      else std::printf("%10s", "-");
    }
    std::printf("\n");
  }
}


}  // namespace foveal::evaluation
