// psvr2: the PlayStation VR2's gaze stream through libusb.
#include "driver_entry.hpp"
#include "foveal/drivers/psvr2/psvr2_discovery.hpp"
#include "foveal/drivers/psvr2/psvr2_pose_source.hpp"
#include "foveal/drivers/psvr2/psvr2_source.hpp"

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

PoseDriverEntry psvr2_pose_entry() {
  PoseDriverEntry e{"psvr2", "psvr2", "a PlayStation VR2's own tracking (SLAM, 6DoF) and IMU, over libusb", {}, {}};
  e.list = []() -> Result<std::vector<HmdRow>> {
    auto found = usb::find_psvr2_devices();
    if (!found) return found.error();
    std::vector<HmdRow> rows;
    for (const usb::UsbDeviceEntry& d : *found) {
      HmdRow row;
      row.driver = "psvr2";
      row.pose_spec = "psvr2";
      row.gaze_spec = "psvr2";
      row.path = d.path;
      row.vid_pid = hex4(d.vendor_id) + ":" + hex4(d.product_id);
      row.name = "PlayStation VR2";
      row.provides = {"gaze", "6dof pose (slam)", "imu 2000 Hz", "ipd dial"};
      rows.push_back(std::move(row));
    }
    return rows;
  };
  e.make = [](const std::string&, const SourceOptions& o) -> Result<OpenedPoseDevice> {
    usb::Psvr2PoseOptions opts;
    if (o.log) opts.log = o.log;
    auto dev = std::make_unique<usb::Psvr2PoseSource>(opts);
    const usb::Psvr2PoseSource* raw = dev.get();
    OpenedPoseDevice out{std::move(dev), {"psvr2", ""}, {}, [] { return std::optional<HeadsetDisplay>(); }};
    out.counters = [raw] {
      const usb::Psvr2PoseCounters& c = raw->counters();
      return nlohmann::json{{"status_transfers", c.status_transfers}, {"slam_transfers", c.slam_transfers},
                            {"imu_samples", c.imu_samples},           {"poses", c.poses},
                            {"malformed", c.malformed},               {"disconnects", c.disconnects},
                            {"ipd_mm", c.ipd_mm}};
    };
    return out;
  };
  return e;
}

}  // namespace foveal::probe
