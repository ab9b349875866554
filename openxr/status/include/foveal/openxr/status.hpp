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
};

/// The runtime the loader would load, and how it was chosen.
struct RuntimeChoice {
  std::string manifest;  ///< empty: none found
  std::string chosen_by; ///< "XR_RUNTIME_JSON" or the active_runtime.json searched
  std::string library;
  bool library_exists = false;
};

/// The runtime's own answer for the HMD system, foveal's layer off.
struct RuntimeGaze {
  bool probed = false;      ///< false: the probe could not run (the message says why)
  std::string message;
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

/// Looks at the files and the environment; with probe_runtime, also loads the runtime
/// (in this process, with foveal's layer disabled) to ask for its system's eye gaze.
/// Never fails: what could not be found is said in the fields.
OpenXRStatus openxr_status(bool probe_runtime);

}  // namespace foveal::openxr
