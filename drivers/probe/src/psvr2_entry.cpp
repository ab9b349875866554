// psvr2: the PlayStation VR2's gaze stream through libusb.
#include "driver_entry.hpp"
#include "foveal/drivers/usb/psvr2_discovery.hpp"
#include "foveal/drivers/usb/psvr2_source.hpp"

namespace foveal::probe {

DriverEntry psvr2_entry() {
  DriverEntry e{"psvr2", "psvr2", "a PlayStation VR2 headset's gaze stream over libusb", DriverEntry::Arg::none, true,
                {}, {}};
  e.list = [](bool) -> Result<std::vector<DeviceRow>> {
    auto found = usb::find_psvr2_devices();
    if (!found) return found.error();
    std::vector<DeviceRow> rows;
    for (const usb::UsbDeviceEntry& d : *found) {
      DeviceRow row;
      row.driver = "psvr2";
      row.spec = "psvr2";
      row.path = d.path;
      row.vid_pid = hex4(d.vendor_id) + ":" + hex4(d.product_id);
      row.name = d.name;
      rows.push_back(std::move(row));
    }
    return rows;
  };
  e.make = [](const std::string&, const SourceOptions& o) -> Result<OpenedSource> {
    usb::Psvr2Options opts;
    if (o.log) opts.log = o.log;
    auto src = std::make_unique<usb::Psvr2Source>(opts);
    const usb::Psvr2Source* raw = src.get();
    return OpenedSource{std::move(src), {"psvr2", ""}, true, [raw] {
                          const usb::Psvr2Counters& c = raw->counters();
                          return nlohmann::json{{"transfers", c.transfers}, {"samples", c.samples},
                                                {"malformed", c.malformed}, {"disconnects", c.disconnects}};
                        }};
  };
  return e;
}

}  // namespace foveal::probe
