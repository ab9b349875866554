#pragma once
// foveald's gaze for the layer: a mapping of foveald's block through foveal-client,
// kept open by a background thread that notices foveald stop and come back, and read
// on the app's per-frame paths without a lock, an allocation or a system call.
#include <foveal/client.h>
#include <openxr/openxr.h>

#include <atomic>
#include <cstdint>
#include <functional>
#include <thread>
#include <vector>

namespace foveal::openxr {

/// One read of the latest sample, in the head (VIEW) frame.
struct GazeNow {
  bool eye_tracked[2] = {false, false};
  XrVector3f eye_dir[2] = {{0, 0, -1}, {0, 0, -1}};  ///< unit, x right, y up, -z forward
  float confidence[2] = {0, 0};
  bool tracked = false;          ///< at least one eye: `combined` is valid
  XrVector3f combined{0, 0, -1}; ///< the tracked eyes' directions averaged
  float ipd_m = 0.063f;
  std::int64_t t_ns = 0;         ///< CLOCK_MONOTONIC of the gaze sample
};

class GazeFeed {
 public:
  /// to_xr_time: the runtime's CLOCK_MONOTONIC -> XrTime conversion (called on the
  /// feed's thread only); log: one line per event (connected, lost).
  GazeFeed(std::function<bool(std::int64_t, XrTime&)> to_xr_time, std::function<void(const char*)> log);
  ~GazeFeed();
  GazeFeed(const GazeFeed&) = delete;
  GazeFeed& operator=(const GazeFeed&) = delete;

  /// The latest sample; false while no foveald serves (or it has published nothing).
  /// Lock-free, allocation-free, no system call (the clock is read through the vDSO).
  bool read(GazeNow& out) const;
  /// A sample's time on the runtime's clock (0 until the offset is known).
  XrTime to_xr_time(std::int64_t t_ns) const;
  bool connected() const { return current_.load(std::memory_order_acquire) != nullptr; }

 private:
  struct Connection {
    foveal_client* client;
    foveal_view view;
  };
  void run();
  void measure_offset(std::int64_t now_ns);
  void check_connection();

  std::function<bool(std::int64_t, XrTime&)> to_xr_time_;
  std::function<void(const char*)> log_;
  std::atomic<Connection*> current_{nullptr};
  // Replaced mappings stay mapped until the feed ends: a reader may still hold one.
  std::vector<Connection*> retired_;
  std::atomic<std::int64_t> xr_offset_ns_{0};
  std::atomic<bool> offset_known_{false};
  std::atomic<bool> stop_{false};
  bool said_lost_ = false, said_waiting_ = false;
  std::thread thread_;
};

}  // namespace foveal::openxr
