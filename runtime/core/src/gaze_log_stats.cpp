#include "foveal/core/gaze_log_stats.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <map>

namespace foveal {

const char* classify_invalid_run(double duration_ms) {
  if (duration_ms < 50.0) return "dropout";
  if (duration_ms <= 500.0) return "blink";
  return "loss";
}

Result<GazeLogStats> compute_gaze_log_stats(const std::string& path) {
  auto reader = GazeLogReader::open(path);
  if (!reader) return reader.error();
  GazeLogStats st;
  st.header = reader->header();

  // Interval histogram in 10 us bins: a median without storing every interval.
  std::map<std::int64_t, std::uint64_t> hist;
  std::uint64_t invalid[2] = {0, 0};
  TimeNs first_t = 0, prev_t = 0;
  bool in_run = false;
  InvalidRun run;
  TimeNs run_start_t = 0;
  GazeSample s;
  Pose first_head;
  std::vector<std::int64_t> intervals_sample;  // bounded reservoir for the rate estimate

  for (;;) {
    auto got = reader->next(s);
    if (!got) return got.error();
    if (!*got) break;
    if (st.samples == 0) first_t = s.t_ns;
    else {
      const TimeNs d = s.t_ns - prev_t;
      ++hist[d / 10'000];
      if (static_cast<double>(d) / 1e6 > st.longest_gap_ms) {
        st.longest_gap_ms = static_cast<double>(d) / 1e6;
        st.longest_gap_at_s = static_cast<double>(prev_t - first_t) / 1e9;
      }
    }
    bool any_valid = false;
    for (int e = 0; e < 2; ++e) {
      const bool v = s.eyes[e].has(kValidDirection);
      invalid[e] += v ? 0 : 1;
      any_valid |= v;
    }
    if (!any_valid && !in_run) {
      in_run = true;
      run = InvalidRun{};
      run.first_index = st.samples;
      run.start_s = static_cast<double>(s.t_ns - first_t) / 1e9;
      run_start_t = s.t_ns;
    }
    if (in_run) {
      if (any_valid) {
        run.duration_ms = static_cast<double>(s.t_ns - run_start_t) / 1e6;
        run.kind = classify_invalid_run(run.duration_ms);
        st.invalid_runs.push_back(run);
        in_run = false;
      } else {
        ++run.samples;
      }
    }
    if (s.head.valid) {
      if (st.head_pose_samples++ == 0) first_head = s.head.pose;
      const Pose moved = relative_to(first_head, s.head.pose);
      const double turn = 2.0 * std::acos(std::min(1.0, std::abs(static_cast<double>(moved.orientation.w)))) * 180.0 / std::numbers::pi;
      st.head_max_turn_deg = std::max(st.head_max_turn_deg, turn);
      st.head_max_travel_m = std::max(st.head_max_travel_m, static_cast<double>(glm::length(s.head.pose.position_m - first_head.position_m)));
    }
    prev_t = s.t_ns;
    ++st.samples;
  }
  if (in_run) {
    // Ends inside the run: count its duration to the last sample plus one median period.
    run.at_end = true;
    run.duration_ms = static_cast<double>(prev_t - run_start_t) / 1e6;
    st.invalid_runs.push_back(run);  // kind filled in below, once the median is known
  }

  st.duration_s = static_cast<double>(prev_t - first_t) / 1e9;
  std::uint64_t n = 0, total = 0;
  for (const auto& [bin, c] : hist) total += c;
  for (const auto& [bin, c] : hist) {
    n += c;
    if (2 * n >= total) {
      st.median_interval_ms = (static_cast<double>(bin) + 0.5) / 100.0;
      break;
    }
  }
  if (in_run) {
    st.invalid_runs.back().duration_ms += st.median_interval_ms;
    st.invalid_runs.back().kind = classify_invalid_run(st.invalid_runs.back().duration_ms);
  }
  // Rate: intervals up to 3x the median, over the time they span (gaps would bias it).
  double span_ms = 0;
  std::uint64_t count = 0;
  for (const auto& [bin, c] : hist) {
    const double ms = (static_cast<double>(bin) + 0.5) / 100.0;
    if (ms <= 3.0 * st.median_interval_ms) {
      span_ms += ms * static_cast<double>(c);
      count += c;
    }
  }
  st.estimated_rate_hz = span_ms > 0 ? 1000.0 * static_cast<double>(count) / span_ms : 0;
  for (int e = 0; e < 2; ++e)
    st.invalid_pct[e] = st.samples ? 100.0 * static_cast<double>(invalid[e]) / static_cast<double>(st.samples) : 0;
  st.blinks = static_cast<std::uint64_t>(
      std::count_if(st.invalid_runs.begin(), st.invalid_runs.end(), [](const InvalidRun& r) { return r.kind == "blink"; }));
  return st;
}

}  // namespace foveal
