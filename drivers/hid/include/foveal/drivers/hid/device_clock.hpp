#pragma once
// The device clock mapping moved to foveal/core (every driver with device timestamps
// uses it); the HID driver keeps its name for it.
#include "foveal/core/device_clock.hpp"

namespace foveal::hid {
using DeviceClock = foveal::DeviceClock;
}  // namespace foveal::hid
