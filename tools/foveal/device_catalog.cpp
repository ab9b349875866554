#include "device_catalog.hpp"

#include <algorithm>
#include <cstdio>

#include "foveal/drivers/hid/hid_tracker_source.hpp"
#ifdef FOVEAL_HAVE_USB
#include "foveal/drivers/usb/psvr2_discovery.hpp"
#include "foveal/drivers/usb/psvr2_source.hpp"
#endif

namespace foveal::cmd {
namespace {

std::string hex4(std::uint16_t v) {
  char b[8];
  std::snprintf(b, sizeof b, "%04x", v);
  return b;
}

OpenedDevice hid_device(const std::string& path) {
  hid::HidTrackerOptions opts;
  opts.device = path;
  auto src = std::make_unique<hid::HidTrackerSource>(opts);
  const hid::HidTrackerSource* raw = src.get();
  return {std::move(src), [raw] {
            const hid::HidTrackerCounters& c = raw->counters();
            return nlohmann::json{{"reports", c.reports},         {"malformed", c.malformed},
                                  {"unknown_reports", c.unknown_reports}, {"feature_errors", c.feature_errors},
                                  {"disconnects", c.disconnects}, {"sample_rate_hz", raw->status().sampling_frequency_hz}};
          }};
}

#ifdef FOVEAL_HAVE_USB
OpenedDevice usb_device() {
  auto src = std::make_unique<usb::Psvr2Source>();
  const usb::Psvr2Source* raw = src.get();
  return {std::move(src), [raw] {
            const usb::Psvr2Counters& c = raw->counters();
            return nlohmann::json{{"transfers", c.transfers}, {"malformed", c.malformed}, {"disconnects", c.disconnects}};
          }};
}
#endif

}  // namespace

Result<std::vector<DeviceRow>> list_devices(bool probe_rate) {
  auto backend = hid::make_hidapi_backend();
  auto trackers = hid::find_eye_trackers(*backend);
  if (!trackers) return trackers.error();
  std::vector<DeviceRow> rows;
  for (const hid::TrackerEntry& t : *trackers) {
    const hid::HidDeviceEntry& d = t.device;
    DeviceRow row{rows.size(), "hid", d.path, hex4(d.vendor_id) + ":" + hex4(d.product_id),
                  d.manufacturer.empty() ? d.product : d.manufacturer + " " + d.product, d.serial, "", 0};
    if (probe_rate) {
      // The rate needs the device open; a device we may not open is still listed.
      hid::HidTrackerOptions opts;
      opts.device = d.path;
      opts.log = [](const std::string&) {};
      hid::HidTrackerSource src(opts, backend);
      if (Status s = src.open(); s) {
        src.wait_for_rate(std::chrono::milliseconds(600));
        row.rate_hz = src.status().sampling_frequency_hz;
      } else {
        row.problem = s.error().message;
      }
    }
    rows.push_back(std::move(row));
  }
#ifdef FOVEAL_HAVE_USB
  if (auto usb_list = usb::find_psvr2_devices(); usb_list) {
    for (const usb::UsbDeviceEntry& d : *usb_list)
      rows.push_back({rows.size(), "usb", d.path, hex4(d.vendor_id) + ":" + hex4(d.product_id), d.name, "", "", 0});
  }
#endif
  return rows;
}

Result<OpenedDevice> make_device_source(const std::string& id) {
#ifdef FOVEAL_HAVE_USB
  if (id == "psvr2") return usb_device();
#endif
  const bool numeric = !id.empty() && std::all_of(id.begin(), id.end(), [](char c) { return c >= '0' && c <= '9'; });
  if (!numeric) return hid_device(id == "auto" ? std::string() : id);
  auto rows = list_devices(false);
  if (!rows) return rows.error();
  const auto index = std::stoull(id);
  if (index >= rows->size())
    return bad_input("--device " + id + ": no such tracker (" + std::to_string(rows->size()) + " found; see foveal devices)");
  const DeviceRow& row = (*rows)[index];
#ifdef FOVEAL_HAVE_USB
  if (row.driver == "usb") return usb_device();
#endif
  return hid_device(row.path);
}

}  // namespace foveal::cmd
