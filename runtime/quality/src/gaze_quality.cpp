#include "foveal/quality/gaze_quality.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace foveal {

namespace {

double seconds(TimeNs ns) { return static_cast<double>(ns) / 1e9; }

double median_interval_s(std::span<const GazeSample> samples) {
  if (samples.size() < 2) return 0;
  std::vector<TimeNs> d(samples.size() - 1);
  for (std::size_t i = 1; i < samples.size(); ++i) d[i - 1] = samples[i].t_ns - samples[i - 1].t_ns;
  const auto mid = d.begin() + static_cast<std::ptrdiff_t>(d.size() / 2);
  std::nth_element(d.begin(), mid, d.end());
  if (d.size() % 2) return seconds(*mid);
  return 0.5 * (seconds(*mid) + seconds(*std::max_element(d.begin(), mid)));
}

AngleSample angles_of(const EyeSample& e) {
  if (!e.has(kValidDirection)) return {};
  return {true, fick_from_direction(glm::dvec3(e.direction))};
}

/// Binocular: the tracker's combined gaze, or else the mean of both eyes' unit
/// directions (valid only where both eyes are).
AngleSample binocular_of(const GazeSample& s, bool use_combined) {
  if (use_combined) return angles_of(s.combined);
  const EyeSample &l = s.eyes[0], &r = s.eyes[1];
  if (!l.has(kValidDirection) || !r.has(kValidDirection)) return {};
  const glm::dvec3 dl(l.direction), dr(r.direction);
  const double nl = std::sqrt(dl.x * dl.x + dl.y * dl.y + dl.z * dl.z);
  const double nr = std::sqrt(dr.x * dr.x + dr.y * dr.y + dr.z * dr.z);
  if (nl == 0 || nr == 0) return {};
  return {true, fick_from_direction(dl / nl + dr / nr)};
}

std::string format_s(double s) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.3f", s);
  return buf;
}

}  // namespace

const char* quality_channel_name(QualityChannel c) {
  switch (c) {
    case QualityChannel::left: return "left";
    case QualityChannel::right: return "right";
    case QualityChannel::binocular: return "binocular";
  }
  return "?";
}

Result<MarkerWindow> window_between_markers(std::span<const GazeSample> samples, std::span<const GazeMarker> markers,
                                            const std::string& from, const std::string& to) {
  auto known = [&] {
    std::string list;
    for (std::size_t i = 0; i < markers.size() && i < 10; ++i) list += (i ? "', '" : " (markers: '") + markers[i].text;
    return markers.empty() ? std::string(" (the log has no markers)") : list + (markers.size() > 10 ? "', ...)" : "')");
  };
  if (samples.empty()) return bad_input("quality: the log holds no samples");
  std::size_t i = 0;
  while (i < markers.size() && markers[i].text != from) ++i;
  if (i == markers.size()) return bad_input("quality: --between: no marker '" + from + "'" + known());
  std::size_t j = i + 1;
  while (j < markers.size() && markers[j].text != to) ++j;
  if (j == markers.size()) return bad_input("quality: --between: no marker '" + to + "' after '" + from + "'" + known());
  const TimeNs t0 = samples.front().t_ns;
  return MarkerWindow{seconds(markers[i].t_ns - t0), seconds(markers[j].t_ns - t0)};
}

Result<GazeQuality> compute_gaze_quality(std::span<const GazeSample> samples, double rate_hz,
                                         const QualityOptions& options) {
  if (samples.empty()) return bad_input("quality: the log holds no samples");
  if (!(rate_hz > 0)) return bad_input("quality: the nominal rate must be > 0");
  GazeQuality q;
  q.rate_hz = rate_hz;
  const double interval_s = median_interval_s(samples);
  q.median_interval_ms = interval_s * 1e3;
  const TimeNs t0 = samples.front().t_ns;
  // The recording spans its first sample to one interval past its last (each sample
  // stands for one interval), as ETDQualitizer counts it.
  const double log_end_s = seconds(samples.back().t_ns - t0) + (interval_s > 0 ? interval_s : 1.0 / rate_hz);
  q.start_s = std::max(0.0, options.start_s.value_or(0.0));
  q.end_s = std::min(log_end_s, options.end_s.value_or(log_end_s));
  if (!(q.end_s > q.start_s))
    return bad_input("quality: the window [" + format_s(q.start_s) + ", " + format_s(q.end_s) +
                     ") s is empty (the log spans [0, " + format_s(log_end_s) + ") s)");

  bool has_combined = false;
  for (const GazeSample& s : samples) has_combined |= s.combined.has(kValidDirection);
  q.binocular_source = has_combined ? "combined" : "mean of eyes";

  // Per channel, the samples of the window in recorded order, and their times.
  std::array<std::vector<AngleSample>, kQualityChannels> series;
  std::vector<double> t_s;
  for (const GazeSample& s : samples) {
    const double t = seconds(s.t_ns - t0);
    if (t < q.start_s || t >= q.end_s) continue;
    t_s.push_back(t);
    series[0].push_back(angles_of(s.eyes[0]));
    series[1].push_back(angles_of(s.eyes[1]));
    series[2].push_back(binocular_of(s, has_combined));
  }
  if (t_s.empty())
    return bad_input("quality: the window [" + format_s(q.start_s) + ", " + format_s(q.end_s) + ") s holds no samples");
  for (int c = 0; c < kQualityChannels; ++c) q.channels[c] = measure_channel(series[c], q.duration_s(), rate_hz);

  std::array<std::size_t, kQualityChannels> counted{};
  for (int c = 0; c < kQualityChannels; ++c) q.accuracy[c] = {0, 0, 0, 0};
  for (const QualityTarget& target : options.targets) {
    TargetQuality tq;
    tq.target = target;
    tq.start_s = std::max(target.start_s, q.start_s);
    tq.end_s = std::min(target.end_s, q.end_s);
    if (!(tq.end_s > tq.start_s))
      return bad_input(target.where + ": the target's window [" + format_s(target.start_s) + ", " +
                       format_s(target.end_s) + ") s lies outside the measured window [" + format_s(q.start_s) +
                       ", " + format_s(q.end_s) + ") s");
    const auto first = std::lower_bound(t_s.begin(), t_s.end(), tq.start_s) - t_s.begin();
    const auto last = std::lower_bound(t_s.begin(), t_s.end(), tq.end_s) - t_s.begin();
    for (int c = 0; c < kQualityChannels; ++c) {
      const std::span<const AngleSample> part(series[c].data() + first, static_cast<std::size_t>(last - first));
      tq.channels[c] = measure_channel(part, tq.end_s - tq.start_s, rate_hz);
      tq.offsets[c] = mean_offset(part, target.at);
      if (!tq.offsets[c]) continue;
      q.accuracy[c].offset_deg += tq.offsets[c]->offset_deg;
      q.accuracy[c].x_deg += tq.offsets[c]->x_deg;
      q.accuracy[c].y_deg += tq.offsets[c]->y_deg;
      ++counted[c];
    }
    q.targets.push_back(std::move(tq));
  }
  for (int c = 0; c < kQualityChannels; ++c) {
    Accuracy& a = q.accuracy[c];
    a.targets = counted[c];
    if (counted[c] == 0) a = Accuracy{};
    else {
      const auto n = static_cast<double>(counted[c]);
      a.offset_deg /= n;
      a.x_deg /= n;
      a.y_deg /= n;
    }
  }
  return q;
}

}  // namespace foveal
