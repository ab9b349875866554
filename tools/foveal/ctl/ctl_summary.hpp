#pragma once
// `foveal ctl`'s human lines: foveald's status, fovea and change replies in one line each
// (the whole record with --json).
#include <nlohmann/json.hpp>

#include <string>

namespace foveal::cmd {

/// "running · source replay:x.csv streaming, 120 Hz, 1520 samples · profile default: right
/// dominant, sigma 2/3 · render visibility rmfr 2880x1600, 300 frames, gaze to photon p50
/// 35 ms · up 12.6 s". Fields a reply lacks (a recording's status) are left out.
std::string status_line(const nlohmann::json& status);

/// Each eye's fovea with its state, and the pixel space the figures are in.
std::string fovea_line(const nlohmann::json& fovea);

/// A change (`use`, `set`): what the running foveald now uses, and that it is not saved.
std::string change_line(const nlohmann::json& reply, const std::string& cmd);

}  // namespace foveal::cmd
