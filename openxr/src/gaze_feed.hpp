#pragma once
// foveald's gaze for the layer: a mapping of foveald's block through foveal-client,
// kept open by a background thread that notices foveald stop and come back, and read
// on the app's per-frame paths without a lock, an allocation or a system call.
//
// The thread never blocks the app: foveal-client opens the block non-blocking and
// refuses what is not a plain block of the user's, the thread waits on a condition
// variable that the destructor signals (so the app's xrDestroyInstance returns at once),
// it logs through the layer's non-blocking log, and a block it cannot use is retried
// with a backoff (0.1 s doubling to 2 s), its mapping freed once no reader holds it.
#include <foveal/client.h>
#include <openxr/openxr.h>

#include <atomic>
#include <condition_variable>
#include <cstdint>
#include <functional>
#include <mutex>
#include <thread>
#include <vector>

namespace foveal::openxr {

/// One read of the latest sample, in the head (VIEW) frame. Plain data (LatchedGaze
/// copies it as words): the directions, and what predicting them to a time needs.
struct GazeNow {
  bool eye_tracked[2] = {false, false};
  XrVector3f eye_dir[2] = {{0, 0, -1}, {0, 0, -1}};  ///< unit, x right, y up, -z forward
  float confidence[2] = {0, 0};
  bool tracked = false;          ///< at least one eye: `combined` is valid
  XrVector3f combined{0, 0, -1}; ///< the tracked eyes' directions averaged
  float ipd_m = 0.063f;
  std::int64_t t_ns = 0;         ///< CLOCK_MONOTONIC of the gaze sample
  std::int64_t at_ns = 0;        ///< the time the directions are for: t_ns, or where gaze_at predicted them to
  // For gaze_at: the sample's pixels, the view that turns them into directions, and
  // the motion foveald published with them (paired by frame).
  foveal_fovea fovea{};
  foveal_view view{};
  foveal_motion motion{};
  bool predictable = false;      ///< the motion is this sample's and prediction is on
  bool offset_known = false;
  std::int64_t xr_offset_ns = 0; ///< XrTime - CLOCK_MONOTONIC when read
};

/// The gaze predicted to `time` (XrTime) by foveald's own rule (foveal_client_predict:
/// predictable eyes extrapolated by their velocity and lag, up to 50 ms; a saccade,
/// blink or loss held), directions recomputed from the predicted pixels; g unchanged
/// when it cannot be predicted (prediction off, an older foveald without motion, a
/// time not after the sample). Which eyes are tracked, confidences and t_ns stay the
/// sample's. Pure: no lock, allocation or system call.
GazeNow gaze_at(const GazeNow& g, XrTime time);

/// The EFR pair foveald serves (its active profile), for the quad views' sizes.
struct GazeSettings {
  float sigma[2] = {3.0f, 2.0f};  ///< per eye (0 left, 1 right): the default profile (right dominant) until foveald says
  bool from_foveald = false;
};

class GazeFeed {
 public:
  /// to_xr_time: the runtime's CLOCK_MONOTONIC -> XrTime conversion (called on the
  /// feed's thread only); log: one line per change of state (connected, lost, bad block).
  /// Prediction to the locate's time is on unless FOVEAL_OPENXR_PREDICT=off (read here, once).
  GazeFeed(std::function<bool(std::int64_t, XrTime&)> to_xr_time, std::function<void(const char*)> log);
  ~GazeFeed();
  GazeFeed(const GazeFeed&) = delete;
  GazeFeed& operator=(const GazeFeed&) = delete;

  /// The latest sample; false while no foveald serves (or it has published nothing).
  /// Lock-free, allocation-free, no system call (the clock is read through the vDSO).
  bool read(GazeNow& out) const;
  /// The EFR pair of foveald's profile (defaults without foveald). Lock-free.
  GazeSettings settings() const;
  /// A sample's time on the runtime's clock (0 until the offset is known, or for a time
  /// the runtime's clock cannot hold).
  XrTime to_xr_time(std::int64_t t_ns) const;
  bool connected() const { return current_.load(std::memory_order_acquire) != nullptr; }
  /// Mappings made and freed so far (tests: a reconnecting feed does not grow).
  int mappings_held() const { return held_.load(std::memory_order_relaxed); }

 private:
  struct Connection {
    foveal_client* client;
    foveal_view view;
  };
  enum class State { starting, waiting, serving, stopped, bad };
  void run();
  void measure_offset(std::int64_t now_ns);
  /// Checks the connection, reconnects when due; returns how long to wait before the next check.
  std::int64_t check_connection(std::int64_t now_ns);
  void retire(Connection* c);
  void free_retired();
  void say(State s, const char* detail);

  std::function<bool(std::int64_t, XrTime&)> to_xr_time_;
  std::function<void(const char*)> log_;
  std::atomic<Connection*> current_{nullptr};
  // Readers count themselves in before they load current_, so a retired mapping no
  // reader can still hold is freed once the count is seen at zero.
  mutable std::atomic<int> readers_{0};
  std::vector<Connection*> retired_;
  std::atomic<int> held_{0};
  std::atomic<std::int64_t> xr_offset_ns_{0};
  std::atomic<bool> offset_known_{false};
  bool predict_ = true;  ///< FOVEAL_OPENXR_PREDICT: on (the default, as foveald's own) or off
  std::atomic<std::uint64_t> settings_bits_{0};  ///< two floats: σ left, σ right (0: none)
  State state_ = State::starting;
  std::int64_t backoff_ns_ = 0, next_try_ns_ = 0;
  std::mutex stop_mutex_;
  std::condition_variable stop_wake_;
  bool stop_ = false;
  std::thread thread_;
};

}  // namespace foveal::openxr
