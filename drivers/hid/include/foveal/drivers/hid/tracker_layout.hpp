#pragma once
// Where an eye tracker of the HID "Eye and Head Trackers" page (0x12, HUTRR74) keeps
// its reports, read off its parsed report descriptor: trackers are recognised by usage,
// never by a vendor/product list.
#include <cstdint>
#include <span>

#include "foveal/core/error.hpp"
#include "foveal/drivers/hid/report_descriptor.hpp"

namespace foveal::hid {

constexpr std::uint16_t kEyeTrackerPage = 0x12;

/// HUTRR74 usage IDs on page 0x12 (DESIGN.md §9).
namespace eye {
constexpr std::uint16_t kEyeTracker = 0x01;
constexpr std::uint16_t kTrackingData = 0x10;
constexpr std::uint16_t kCapabilities = 0x11;
constexpr std::uint16_t kConfiguration = 0x12;
constexpr std::uint16_t kTrackerStatus = 0x13;
constexpr std::uint16_t kTrackerControl = 0x14;
constexpr std::uint16_t kTimestamp = 0x20;
constexpr std::uint16_t kPositionX = 0x21;
constexpr std::uint16_t kPositionY = 0x22;
constexpr std::uint16_t kPositionZ = 0x23;
constexpr std::uint16_t kGazeLocation = 0x24;
constexpr std::uint16_t kLeftEyePosition = 0x25;
constexpr std::uint16_t kRightEyePosition = 0x26;
constexpr std::uint16_t kTrackerQuality = 0x0100;
constexpr std::uint16_t kMinimumTrackingDistance = 0x0101;
constexpr std::uint16_t kOptimumTrackingDistance = 0x0102;
constexpr std::uint16_t kMaximumTrackingDistance = 0x0103;
constexpr std::uint16_t kMaximumScreenPlaneWidth = 0x0104;
constexpr std::uint16_t kMaximumScreenPlaneHeight = 0x0105;
constexpr std::uint16_t kDisplayManufacturerId = 0x0200;
constexpr std::uint16_t kDisplayProductId = 0x0201;
constexpr std::uint16_t kDisplaySerialNumber = 0x0202;
constexpr std::uint16_t kDisplayManufacturerDate = 0x0203;
constexpr std::uint16_t kCalibratedScreenWidth = 0x0204;
constexpr std::uint16_t kCalibratedScreenHeight = 0x0205;
constexpr std::uint16_t kSamplingFrequency = 0x0300;
constexpr std::uint16_t kConfigurationStatus = 0x0301;
constexpr std::uint16_t kModeRequest = 0x0400;
}  // namespace eye

/// Mode Request values (bit flags).
constexpr std::uint8_t kModeGazePoint = 1;
constexpr std::uint8_t kModeEyePosition = 2;
constexpr std::uint8_t kModeHeadPosition = 4;

/// One report of the tracker: its ID and its length on the wire (with the ID byte).
struct ReportRef {
  bool present = false;
  std::uint8_t id = 0;
  std::uint32_t bytes = 0;
};

struct TrackerLayout {
  ReportDescriptor descriptor;
  ReportRef tracking;        ///< input, required
  ReportRef capabilities;    ///< feature, optional
  ReportRef configuration;   ///< feature, optional
  ReportRef status_feature;  ///< feature, optional
  ReportRef status_input;    ///< input, optional (same ID as the feature one on real devices)
  ReportRef control;         ///< feature holding Mode Request, required to enable gaze
};

/// True if the descriptor has an application collection Eye Tracker (0x12:0x01).
bool is_eye_tracker(const ReportDescriptor& d);

/// Finds the tracker's reports by their logical collections. Errors (bad_input) when the
/// descriptor is no eye tracker or lacks a Tracking Data input or a Mode Request feature.
Result<TrackerLayout> make_tracker_layout(ReportDescriptor d);

/// Parses the raw descriptor bytes and builds the layout.
Result<TrackerLayout> make_tracker_layout(std::span<const std::uint8_t> descriptor_bytes);

}  // namespace foveal::hid
