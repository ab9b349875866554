#include "auto_pose_device.hpp"

namespace foveal::probe {

Status AutoPoseDevice::open() {
  close();
  auto rows = list_hmds();
  if (!rows) return rows.error();
  std::string problems;
  for (const HmdRow& row : *rows) {
    auto spec = parse_pose_spec(row.pose_spec);
    if (!spec) continue;
    auto made = make_pose_device(*spec, options_);
    if (!made) {
      problems += "; " + row.pose_spec + ": " + made.error().message;
      continue;
    }
    if (Status s = made->device->open(); !s) {
      problems += "; " + row.pose_spec + ": " + s.error().message;
      continue;
    }
    current_.emplace(std::move(*made));
    return {};
  }
  return io_error("auto: no headset could be opened for its pose (" + std::to_string(rows->size()) + " found" + problems + ")");
}

void AutoPoseDevice::close() {
  if (current_) current_->device->close();
}

Status AutoPoseDevice::start() {
  if (!current_) return io_error("auto: start() before a successful open()");
  return current_->device->start();
}

void AutoPoseDevice::stop() {
  if (current_) current_->device->stop();
}

PoseReading AutoPoseDevice::next(std::chrono::nanoseconds timeout) {
  if (!current_) {
    PoseReading r;
    r.status = ReadStatus::disconnected;
    return r;
  }
  return current_->device->next(timeout);
}

PoseDeviceInfo AutoPoseDevice::info() const {
  if (current_) return current_->device->info();
  PoseDeviceInfo i;
  i.driver = "auto";
  i.name = "no headset yet";
  return i;
}

nlohmann::json AutoPoseDevice::counters() const {
  if (!current_) return nlohmann::json::object();
  nlohmann::json j = current_->counters();
  j["head"] = current_->spec.text();
  return j;
}

std::optional<HeadsetDisplay> AutoPoseDevice::display() const {
  if (!current_ || !current_->display) return std::nullopt;
  return current_->display();
}

}  // namespace foveal::probe
