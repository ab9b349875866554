// hid[:ID|PATH]: HUTRR74 eye trackers (usage page 0x12) through hidapi.
#include <algorithm>

#include "driver_entry.hpp"
#include "foveal/drivers/hid/hid_tracker_source.hpp"

namespace foveal::probe {

namespace {

OpenedSource hid_source(const std::string& path, const SourceOptions& o, std::string arg) {
  hid::HidTrackerOptions opts;
  opts.device = path;
  if (o.log) opts.log = o.log;
  auto src = std::make_unique<hid::HidTrackerSource>(opts);
  const hid::HidTrackerSource* raw = src.get();
  return {std::move(src), {"hid", std::move(arg)}, true, [raw] {
            const hid::HidTrackerCounters& c = raw->counters();
            return nlohmann::json{{"reports", c.reports},
                                  {"malformed", c.malformed},
                                  {"unknown_reports", c.unknown_reports},
                                  {"feature_errors", c.feature_errors},
                                  {"opens", c.opens},
                                  {"disconnects", c.disconnects},
                                  {"sample_rate_hz", raw->status().sampling_frequency_hz}};
          }};
}

bool all_digits(const std::string& s) {
  return !s.empty() && std::all_of(s.begin(), s.end(), [](char c) { return c >= '0' && c <= '9'; });
}

}  // namespace

DriverEntry hid_entry() {
  DriverEntry e{"hid", "hid[:ID|PATH]",
                "a HID eye tracker (usage page 0x12): an id from `foveal devices`, a hidraw node, or the first one",
                DriverEntry::Arg::optional, true, {}, {}};
  e.list = [](bool probe_rate) -> Result<std::vector<DeviceRow>> {
    auto backend = hid::make_hidapi_backend();
    auto trackers = hid::find_eye_trackers(*backend);
    if (!trackers) return trackers.error();
    std::vector<DeviceRow> rows;
    for (const hid::TrackerEntry& t : *trackers) {
      const hid::HidDeviceEntry& d = t.device;
      DeviceRow row;
      row.driver = "hid";
      row.spec = "hid:" + d.path;
      row.path = d.path;
      row.vid_pid = hex4(d.vendor_id) + ":" + hex4(d.product_id);
      row.name = d.manufacturer.empty() ? d.product : d.manufacturer + " " + d.product;
      row.serial = d.serial;
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
    return rows;
  };
  e.make = [](const std::string& arg, const SourceOptions& o) -> Result<OpenedSource> {
    if (!all_digits(arg)) return hid_source(arg, o, arg);  // "" = the first tracker, at each open
    auto rows = list_devices(false);
    if (!rows) return rows.error();
    const auto index = std::stoull(arg);
    if (index >= rows->size())
      return bad_input("hid:" + arg + ": no such tracker (" + std::to_string(rows->size()) +
                       " found; see foveal devices)");
    const DeviceRow& row = (*rows)[index];
    if (row.driver != "hid") return bad_input("hid:" + arg + ": tracker " + arg + " is a " + row.driver + " device; use --source " + row.spec);
    return hid_source(row.path, o, arg);
  };
  return e;
}

}  // namespace foveal::probe
