#pragma once
// A scripted HidBackend: devices with descriptors, feature replies and queued input
// reports, which can be unplugged and plugged back, for the tracker driver's tests.
#include <deque>
#include <map>
#include <memory>
#include <mutex>

#include "foveal/drivers/hid/hid_backend.hpp"

namespace foveal::test {

struct FakeHidState {
  hid::HidDeviceEntry entry;
  bool present = true;
  std::map<std::uint8_t, std::vector<std::uint8_t>> features;  ///< GET_REPORT replies by ID
  /// Replies given once each, in order, before `features` (a device that streams a
  /// long value through repeated GET_REPORTs, as the Vive's configuration).
  std::map<std::uint8_t, std::deque<std::vector<std::uint8_t>>> feature_sequences;
  std::vector<std::vector<std::uint8_t>> sent;                  ///< SET_REPORT requests
  std::deque<std::vector<std::uint8_t>> inputs;
  /// Guards `inputs` where a test feeds them while a reader thread takes them
  /// (push_input); single-threaded tests may push directly.
  std::mutex inputs_mutex;
  void push_input(std::vector<std::uint8_t> report) {
    std::lock_guard lock(inputs_mutex);
    inputs.push_back(std::move(report));
  }
  int open_handles = 0;
};

class FakeHidDevice final : public hid::HidDevice {
 public:
  explicit FakeHidDevice(std::shared_ptr<FakeHidState> s) : s_(std::move(s)) { ++s_->open_handles; }
  ~FakeHidDevice() override { --s_->open_handles; }
  Result<std::vector<std::uint8_t>> get_feature(std::uint8_t id, std::size_t) override {
    if (!s_->present) return Error{ErrorKind::device, "gone"};
    if (auto seq = s_->feature_sequences.find(id); seq != s_->feature_sequences.end() && !seq->second.empty()) {
      auto r = seq->second.front();
      seq->second.pop_front();
      return r;
    }
    auto it = s_->features.find(id);
    if (it == s_->features.end()) return Error{ErrorKind::device, "stall"};
    return it->second;
  }
  Status send_feature(std::span<const std::uint8_t> report) override {
    if (!s_->present) return Error{ErrorKind::device, "gone"};
    s_->sent.emplace_back(report.begin(), report.end());
    return {};
  }
  Result<std::size_t> read(std::span<std::uint8_t> buffer, int) override {
    if (!s_->present) return Error{ErrorKind::device, "gone"};
    std::lock_guard lock(s_->inputs_mutex);
    if (s_->inputs.empty()) return std::size_t{0};
    const auto r = s_->inputs.front();
    s_->inputs.pop_front();
    const std::size_t n = std::min(r.size(), buffer.size());
    std::copy_n(r.begin(), n, buffer.begin());
    return n;
  }

 private:
  std::shared_ptr<FakeHidState> s_;
};

class FakeHidBackend final : public hid::HidBackend {
 public:
  std::shared_ptr<FakeHidState> add(hid::HidDeviceEntry e) {
    auto s = std::make_shared<FakeHidState>();
    s->entry = std::move(e);
    devices.push_back(s);
    return s;
  }
  Result<std::vector<hid::HidDeviceEntry>> enumerate() override {
    std::vector<hid::HidDeviceEntry> out;
    for (auto& d : devices)
      if (d->present) out.push_back(d->entry);
    return out;
  }
  Result<std::unique_ptr<hid::HidDevice>> open(const std::string& path) override {
    for (auto& d : devices)
      if (d->present && d->entry.path == path) return std::unique_ptr<hid::HidDevice>(std::make_unique<FakeHidDevice>(d));
    return Error{ErrorKind::device, path + ": no such device"};
  }
  std::vector<std::shared_ptr<FakeHidState>> devices;
};

}  // namespace foveal::test
