#pragma once
// What an OpenXR application started now would get from foveal (`foveal openxr`,
// docs/openxr.md): the layer's manifests the loader finds, whether the environment
// turns the layer on, the runtime the loader would pick, whether that runtime has eye
// gaze of its own, and whether foveald is serving.
#include <optional>
#include <string>
#include <vector>

namespace foveal::openxr {

/// One layer manifest of foveal's where the loader looks.
struct LayerManifest {
  std::string path;
  bool implicit = false;
  std::string library;  ///< resolved as the loader resolves it
  bool library_exists = false;
  std::string disable_environment, enable_environment;
  std::string problem;  ///< non-empty: the loader cannot use this manifest (names file and field)
};

/// The runtime the loader would load, and how it was chosen.
struct RuntimeChoice {
  std::string manifest;  ///< empty: none found
  std::string chosen_by; ///< "XR_RUNTIME_JSON" or the active_runtime.json searched
  std::string library;
  bool library_exists = false;
  std::string problem;  ///< non-empty: the manifest is unusable (not a regular file, not JSON, a bad field)
};

/// The runtime's own answer for the HMD system, foveal's layer off.
struct RuntimeGaze {
  bool probed = false;      ///< false: the probe could not run (the message says why)
  bool runtime_failed = false;  ///< the runtime crashed, hung or refused: an app would fail too
  std::string message;
  std::string log;          ///< what the loader and the runtime printed during the probe (its end)
  std::string runtime_name, system_name;
  bool lists_eye_gaze_interaction = false;
  bool supports_eye_gaze_interaction = false;
};

struct OpenXRStatus {
  std::vector<LayerManifest> layers;  ///< in the loader's search order
  bool enabled = false;               ///< an implicit manifest whose environment turns it on
  std::string enabled_reason;
  std::string gaze_mode;              ///< FOVEAL_OPENXR_GAZE: auto, foveal or runtime
  RuntimeChoice runtime;
  RuntimeGaze runtime_gaze;
  bool foveald_serving = false;
  std::string foveald_message;
};

/// The default for how long the probe waits for the runtime's answer.
inline constexpr double kDefaultProbeTimeoutS = 10;

/// Looks at the files and the environment; with probe_runtime, also loads the runtime
/// to ask for its system's eye gaze. The runtime is loaded in a child process, with
/// foveal's layer disabled, and stopped after probe_timeout_s: a runtime that crashes or
/// hangs is reported, never taking this process with it. Never fails: what could not be
/// found is said in the fields.
OpenXRStatus openxr_status(bool probe_runtime, double probe_timeout_s = kDefaultProbeTimeoutS);

}  // namespace foveal::openxr
