#pragma once
// Which connector and mode direct mode drives: plain data and pure functions, so the
// choice is testable without a DRM device (the libdrm calls are in drm_output.cpp).
#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "foveal/core/display_model.hpp"
#include "foveal/core/error.hpp"

namespace foveal::render {

struct KmsMode {
  int width = 0, height = 0;
  double refresh_hz = 0;   ///< from the pixel clock and totals, not the rounded vrefresh
  bool preferred = false;  ///< the sink's preferred mode (EDID)
};

struct KmsConnector {
  std::string name;          ///< as the kernel names it: "DP-1", "HDMI-A-1", "Virtual-1"
  std::uint32_t id = 0;
  bool connected = false;
  bool non_desktop = false;  ///< the kernel's "non-desktop" property: an HMD
  std::string edid_vendor;   ///< EDID manufacturer ID ("HVR"); empty without an EDID
  std::uint16_t edid_product = 0;
  std::string edid_name;     ///< EDID monitor name descriptor, if any
  std::vector<KmsMode> modes;
};

struct EdidIdentity {
  std::string vendor;  ///< three letters
  std::uint16_t product = 0;
  std::string name;    ///< monitor name descriptor (0xFC), trimmed; may be empty
};

/// Reads the identity from an EDID base block. nullopt when it is shorter than 128
/// bytes or lacks the fixed header.
std::optional<EdidIdentity> parse_edid_identity(std::span<const std::uint8_t> edid);

struct KmsWanted {
  std::string connector;   ///< this connector by name; empty: choose
  int width = 0, height = 0;
  double refresh_hz = 0;   ///< nearest rate; 0: the preferred mode of that size, else the fastest
  std::string edid_vendor; ///< prefer the connector whose EDID carries it
};

/// What the display model asks for: its side-by-side size, refresh rate and EDID vendor.
KmsWanted headset_output(const DisplayModel& model);

struct KmsChoice {
  std::size_t connector = 0, mode = 0;  ///< indices into the list and its modes
};

/// The named connector, else the first connected one with a mode of the wanted size that
/// is non-desktop or carries the wanted EDID vendor, else the first connected one with
/// such a mode. Errors (bad_input) name the reason and list every connector.
Result<KmsChoice> choose_output(const std::vector<KmsConnector>& connectors, const KmsWanted& wanted);

/// One line per connector for listings and errors: name, state, identity, modes.
std::string describe(const KmsConnector& c);
/// {"name", "connected", "non_desktop", "edid": {"vendor", "product", "name"} | null,
///  "modes": [{"width", "height", "refresh_hz", "preferred"}]}
nlohmann::json connector_json(const KmsConnector& c);

/// Parses "WxH" or "WxH@HZ" into `wanted`; bad_input names the text.
Status parse_mode(const std::string& text, KmsWanted& wanted);

}  // namespace foveal::render
