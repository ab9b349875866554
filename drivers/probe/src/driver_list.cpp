// The driver list: one line per driver; a driver this build does not have is named in
// drivers_left_out() so a spec naming it gets a clear error.
#include "driver_entry.hpp"

#include <cstdio>

namespace foveal::probe {

const std::vector<DriverEntry>& driver_list() {
  static const std::vector<DriverEntry> list = [] {
    std::vector<DriverEntry> l{replay_entry(), synthetic_entry()};
#ifdef FOVEAL_HAVE_HID
    l.push_back(hid_entry());
#endif
#ifdef FOVEAL_HAVE_USB
    l.push_back(psvr2_entry());
#endif
    return l;
  }();
  return list;
}

const std::vector<PoseDriverEntry>& pose_driver_list() {
  static const std::vector<PoseDriverEntry> list = [] {
    std::vector<PoseDriverEntry> l;
#ifdef FOVEAL_HAVE_USB
    l.push_back(psvr2_pose_entry());
#endif
#ifdef FOVEAL_HAVE_HID
    l.push_back(vive_pose_entry());
#endif
    return l;
  }();
  return list;
}

const std::vector<std::string>& drivers_left_out() {
  static const std::vector<std::string> out = [] {
    std::vector<std::string> o;
#ifndef FOVEAL_HAVE_HID
    o.emplace_back("hid");
#endif
#ifndef FOVEAL_HAVE_USB
    o.emplace_back("psvr2");
#endif
    return o;
  }();
  return out;
}

std::string hex4(std::uint16_t v) {
  char b[8];
  std::snprintf(b, sizeof b, "%04x", v);
  return b;
}

}  // namespace foveal::probe
