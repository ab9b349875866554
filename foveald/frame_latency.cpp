#include "frame_latency.hpp"

#include <cinttypes>
#include <cstdio>

namespace foveal::daemon {

const char* FrameLatency::csv_header() {
  return "sample_device_t_ns,sample_arrival_ns,frame_start_ns,latch_ns,gpu_done_ns,shown_ns,display_target_ns,"
         "gaze_to_photon_ms,tracker_to_host_ms,host_to_latch_ms,latch_to_gpu_ms,gpu_to_shown_ms";
}

std::string FrameLatency::csv_cells() const {
  char buf[320];
  if (!has_sample()) {
    std::snprintf(buf, sizeof buf, ",,%" PRId64 ",%" PRId64 ",%" PRId64 ",%" PRId64 ",%" PRId64 ",,,,,",
                  static_cast<std::int64_t>(start_ns), static_cast<std::int64_t>(latch_ns),
                  static_cast<std::int64_t>(gpu_done_ns), static_cast<std::int64_t>(shown_ns),
                  static_cast<std::int64_t>(display_target_ns));
    return buf;
  }
  // Microsecond resolution: the parts add up to the total within 0.002 ms as printed.
  std::snprintf(buf, sizeof buf,
                "%" PRId64 ",%" PRId64 ",%" PRId64 ",%" PRId64 ",%" PRId64 ",%" PRId64 ",%" PRId64 ",%.3f,%.3f,%.3f,%.3f,%.3f",
                static_cast<std::int64_t>(sample_device_t_ns), static_cast<std::int64_t>(arrival_ns),
                static_cast<std::int64_t>(start_ns), static_cast<std::int64_t>(latch_ns),
                static_cast<std::int64_t>(gpu_done_ns), static_cast<std::int64_t>(shown_ns),
                static_cast<std::int64_t>(display_target_ns), gaze_to_photon_ms(), tracker_to_host_ms(),
                host_to_latch_ms(), latch_to_gpu_ms(), gpu_to_shown_ms());
  return buf;
}

void LatencyStats::Part::add(TimeNs ns) {
  if (ns < 0) {
    ++negative;
    ns = 0;
  }
  h.add(ns);
}

nlohmann::json LatencyStats::Part::json() const {
  auto ms = [](std::int64_t ns) { return static_cast<double>(ns) * 1e-6; };
  nlohmann::json j = {{"p50", ms(h.percentile(0.5))},
                      {"p95", ms(h.percentile(0.95))},
                      {"p99", ms(h.percentile(0.99))},
                      {"max", ms(h.max())}};
  if (negative) j["negative"] = negative;
  return j;
}

void LatencyStats::add(const FrameLatency& f) {
  if (!f.has_sample()) return;
  ++frames_;
  total_.add(f.shown_ns - f.sample_t_ns);
  tracker_host_.add(f.arrival_ns - f.sample_t_ns);
  host_latch_.add(f.latch_ns - f.arrival_ns);
  latch_gpu_.add(f.gpu_done_ns - f.latch_ns);
  gpu_shown_.add(f.shown_ns - f.gpu_done_ns);
}

nlohmann::json LatencyStats::json(const char* shown_clock) const {
  return {{"frames", frames_},
          {"shown_clock", shown_clock},
          {"gaze_to_photon_ms", total_.json()},
          {"parts_ms",
           {{"tracker_to_host", tracker_host_.json()},
            {"host_to_latch", host_latch_.json()},
            {"latch_to_gpu", latch_gpu_.json()},
            {"gpu_to_shown", gpu_shown_.json()}}}};
}

}  // namespace foveal::daemon
