#pragma once
// `auto` for gaze (--source auto) and head pose (--head auto): whichever live device is
// present, chosen again at every open() so that a replug (or another device plugged in)
// is picked up. One template; a Side says how its devices are listed, made and named.
#include <chrono>
#include <optional>
#include <string>
#include <utility>

#include "driver_entry.hpp"

namespace foveal::probe {

template <class Side>
class AutoDevice final : public Side::Interface {
 public:
  using Opened = typename Side::Opened;

  explicit AutoDevice(SourceOptions options) : options_(std::move(options)) {}

  Status open() override {
    close();
    auto rows = Side::list();
    if (!rows) return rows.error();
    std::string problems;
    for (const auto& row : *rows) {
      const std::string& text = Side::row_spec(row);
      auto spec = Side::parse(text);
      if (!spec) continue;
      auto made = Side::make(*spec, options_);
      if (!made) {
        problems += "; " + text + ": " + made.error().message;
        continue;
      }
      if (Status s = Side::device(*made).open(); !s) {
        problems += "; " + text + ": " + s.error().message;
        continue;
      }
      current_.emplace(std::move(*made));
      return {};
    }
    return io_error(std::string("auto: ") + Side::kNoneOpened + " (" + std::to_string(rows->size()) + " found" +
                    problems + ")");
  }

  void close() override {
    if (current_) Side::device(*current_).close();
    // Keep the last device's counters readable until the next open() chooses again.
  }

  Status start() override {
    if (!current_) return io_error("auto: start() before a successful open()");
    return Side::device(*current_).start();
  }

  void stop() override {
    if (current_) Side::device(*current_).stop();
  }

  typename Side::Reading next(std::chrono::nanoseconds timeout) override {
    if (!current_) {
      typename Side::Reading r;
      r.status = ReadStatus::disconnected;
      return r;
    }
    return Side::device(*current_).next(timeout);
  }

  typename Side::Info info() const override {
    if (current_) return Side::device(*current_).info();
    typename Side::Info i;
    i.driver = "auto";
    i.name = Side::kNoDeviceYet;
    return i;
  }

  /// The chosen device's counters (empty object before the first open).
  nlohmann::json counters() const {
    if (!current_) return nlohmann::json::object();
    nlohmann::json j = current_->counters();
    j[Side::kSpecKey] = current_->spec.text();
    return j;
  }

  /// The chosen device as its driver made it (nullopt before the first open).
  const std::optional<Opened>& current() const { return current_; }

 private:
  SourceOptions options_;
  std::optional<Opened> current_;
};

/// --source auto: the live eye trackers of `foveal devices`.
struct GazeSide {
  using Interface = GazeSource;
  using Reading = ReadResult;
  using Info = SourceInfo;
  using Opened = OpenedSource;
  static constexpr const char* kNoneOpened = "no eye tracker could be opened";
  static constexpr const char* kNoDeviceYet = "no tracker yet";
  static constexpr const char* kSpecKey = "spec";
  static Result<std::vector<DeviceRow>> list() { return list_devices(false); }
  static const std::string& row_spec(const DeviceRow& r) { return r.spec; }
  static Result<SourceSpec> parse(const std::string& text) { return parse_source_spec(text); }
  static Result<OpenedSource> make(const SourceSpec& s, const SourceOptions& o) { return make_source(s, o); }
  static GazeSource& device(const OpenedSource& o) { return *o.source; }
};
using AutoSource = AutoDevice<GazeSide>;

/// --head auto: the headsets with a pose (list_hmds).
struct PoseSide {
  using Interface = PoseDevice;
  using Reading = PoseReading;
  using Info = PoseDeviceInfo;
  using Opened = OpenedPoseDevice;
  static constexpr const char* kNoneOpened = "no headset could be opened for its pose";
  static constexpr const char* kNoDeviceYet = "no headset yet";
  static constexpr const char* kSpecKey = "head";
  static Result<std::vector<HmdRow>> list() { return list_hmds(); }
  static const std::string& row_spec(const HmdRow& r) { return r.pose_spec; }
  static Result<PoseSpec> parse(const std::string& text) { return parse_pose_spec(text); }
  static Result<OpenedPoseDevice> make(const PoseSpec& s, const SourceOptions& o) { return make_pose_device(s, o); }
  static PoseDevice& device(const OpenedPoseDevice& o) { return *o.device; }
};
using AutoPoseDevice = AutoDevice<PoseSide>;

}  // namespace foveal::probe
