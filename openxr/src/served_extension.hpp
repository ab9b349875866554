#pragma once
// An extension the layer serves where the runtime lacks it: one row of the table in
// served_extensions.cpp, defined in the extension's own file. Adding an extension is
// that file, one row, and its name in the manifest (docs/conventions.md).
#include <openxr/openxr.h>

#include <cstddef>
#include <cstdint>

namespace foveal::openxr {

/// The served extensions, in table order.
enum class Ext : int { eye_gaze_interaction, fb_eye_tracking_social, varjo_quad_views, varjo_foveated_rendering, count };
constexpr int kExtCount = static_cast<int>(Ext::count);

struct Intercept {
  const char* name;
  PFN_xrVoidFunction fn;
  /// The extension's own function: an instance that did not enable the extension gets
  /// XR_ERROR_FUNCTION_UNSUPPORTED. Otherwise a core function the extension changes,
  /// passed to the runtime untouched for such an instance.
  bool extension_only;
};

struct ServedExtension {
  const char* name;
  std::uint32_t version;
  const Intercept* functions;
  std::size_t function_count;
  /// A struct of the extension's that apps chain to XrSystemProperties (0: none): hidden
  /// from a runtime that lacks the extension, then filled by fill_system_properties.
  XrStructureType system_properties_type;
  void (*fill_system_properties)(XrBaseOutStructure* props);
  /// Other served extensions it needs the app to enable as well (-1: none).
  int requires_ext;
};

/// Each extension's row, from its own file.
extern const ServedExtension kEyeGazeInteraction;
extern const ServedExtension kFbEyeTrackingSocial;
extern const ServedExtension kVarjoQuadViews;
extern const ServedExtension kVarjoFoveatedRendering;

/// The table: index by Ext.
const ServedExtension& served(Ext e);

#define FOVEAL_FN(f) reinterpret_cast<PFN_xrVoidFunction>(f)

}  // namespace foveal::openxr
