// hidapi (hidraw) implementation of HidBackend. hidapi 0.13 (Debian 12) cannot return a
// report descriptor, so it is read from sysfs, where the kernel exposes it per hidraw node.
#include <hidapi/hidapi.h>

#include <cerrno>
#include <cstring>
#include <fstream>
#include <iterator>
#include <mutex>
#include <set>

#include "foveal/drivers/hid/hid_backend.hpp"

namespace foveal::hid {
namespace {

std::string narrow(const wchar_t* w) {
  std::string s;
  if (w == nullptr) return s;
  for (; *w; ++w) s += (*w > 0 && *w < 0x80) ? static_cast<char>(*w) : '?';
  return s;
}

std::string hid_error_text(hid_device* dev) {
  const std::string e = narrow(hid_error(dev));
  return e.empty() ? "unknown error" : e;
}

Status ensure_init() {
  static std::once_flag once;
  static int rc = 0;
  std::call_once(once, [] { rc = hid_init(); });
  if (rc != 0) return Error{ErrorKind::device, "hidapi: hid_init failed"};
  return {};
}

/// /dev/hidraw3 -> /sys/class/hidraw/hidraw3/device/report_descriptor
std::vector<std::uint8_t> read_descriptor(const std::string& path) {
  const auto slash = path.find_last_of('/');
  const std::string node = slash == std::string::npos ? path : path.substr(slash + 1);
  std::ifstream in("/sys/class/hidraw/" + node + "/device/report_descriptor", std::ios::binary);
  if (!in) return {};
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

class HidapiDevice final : public HidDevice {
 public:
  HidapiDevice(hid_device* dev, std::string path) : dev_(dev), path_(std::move(path)) {}
  ~HidapiDevice() override { hid_close(dev_); }
  HidapiDevice(const HidapiDevice&) = delete;
  HidapiDevice& operator=(const HidapiDevice&) = delete;

  Result<std::vector<std::uint8_t>> get_feature(std::uint8_t id, std::size_t length) override {
    std::vector<std::uint8_t> buf(std::max<std::size_t>(length, 1), 0);
    buf[0] = id;
    const int n = hid_get_feature_report(dev_, buf.data(), buf.size());
    if (n < 0) return fail("get feature report " + std::to_string(id));
    buf.resize(static_cast<std::size_t>(n));
    return buf;
  }

  Status send_feature(std::span<const std::uint8_t> report) override {
    if (hid_send_feature_report(dev_, report.data(), report.size()) < 0)
      return fail("send feature report " + std::to_string(report.empty() ? 0 : report[0]));
    return {};
  }

  Result<std::size_t> read(std::span<std::uint8_t> buffer, int timeout_ms) override {
    const int n = hid_read_timeout(dev_, buffer.data(), buffer.size(), timeout_ms);
    if (n < 0) return fail("read");
    return static_cast<std::size_t>(n);
  }

 private:
  Error fail(const std::string& what) {
    return Error{ErrorKind::device, path_ + ": " + what + ": " + hid_error_text(dev_)};
  }
  hid_device* dev_;
  std::string path_;
};

class HidapiBackend final : public HidBackend {
 public:
  Result<std::vector<HidDeviceEntry>> enumerate() override {
    if (Status s = ensure_init(); !s) return s.error();
    std::vector<HidDeviceEntry> out;
    std::set<std::string> seen;  // hidapi lists a device once per top-level usage
    hid_device_info* list = hid_enumerate(0, 0);
    for (hid_device_info* d = list; d != nullptr; d = d->next) {
      if (d->path == nullptr || !seen.insert(d->path).second) continue;
      HidDeviceEntry e;
      e.path = d->path;
      e.vendor_id = d->vendor_id;
      e.product_id = d->product_id;
      e.manufacturer = narrow(d->manufacturer_string);
      e.product = narrow(d->product_string);
      e.serial = narrow(d->serial_number);
      e.descriptor = read_descriptor(e.path);
      out.push_back(std::move(e));
    }
    hid_free_enumeration(list);
    return out;
  }

  Result<std::unique_ptr<HidDevice>> open(const std::string& path) override {
    if (Status s = ensure_init(); !s) return s.error();
    hid_device* dev = hid_open_path(path.c_str());
    if (dev == nullptr) return Error{ErrorKind::device, path + ": cannot open: " + hid_error_text(nullptr) +
                                                            " (" + std::strerror(errno) + ")"};
    return std::unique_ptr<HidDevice>(std::make_unique<HidapiDevice>(dev, path));
  }
};

}  // namespace

std::shared_ptr<HidBackend> make_hidapi_backend() { return std::make_shared<HidapiBackend>(); }

}  // namespace foveal::hid
