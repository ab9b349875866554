#pragma once
// Direct mode: the compositor's frames on a DRM/KMS connector with no display server,
// for headsets the kernel marks non-desktop (no desktop window ever reaches them).
// Opens /dev/dri/cardN, must be its DRM master, picks the connector and the mode the
// display model asks for (kms_select.hpp), makes an OpenGL 4.5 core context through EGL
// on GBM current, and shows each frame with a page flip at vblank. Create, use and
// destroy on one thread; the context is current on it. docs/headset.md has the set-up.
#include <memory>
#include <string>
#include <vector>

#include "foveal/core/error.hpp"
#include "foveal/render/gl.hpp"
#include "foveal/render/kms_select.hpp"
#include "foveal/render/present_stats.hpp"

namespace foveal::render {

struct DrmOutputOptions {
  std::string device;  ///< /dev/dri/cardN; empty: the first card with a matching connector
  KmsWanted wanted;    ///< connector, size, rate, EDID vendor
};

/// One DRM device as `foveal outputs` lists it.
struct DrmDeviceInfo {
  std::string path, driver;
  std::vector<KmsConnector> connectors;
  std::string error;  ///< why it could not be read (then no connectors)
};

class DrmOutput {
 public:
  /// Errors: ErrorKind::device when the node is missing, not a KMS device, or busy
  /// (another process, usually the desktop's compositor, is its DRM master);
  /// ErrorKind::io when opening it is not permitted (the message says which group);
  /// bad_input when no connector or mode matches (every connector is listed);
  /// unsupported when EGL on GBM offers no OpenGL 4.5 core context.
  static Result<DrmOutput> open(const DrmOutputOptions& options);
  DrmOutput(DrmOutput&&) noexcept;
  DrmOutput& operator=(DrmOutput&&) noexcept;
  /// Waits for a pending flip, puts back what the CRTC showed before (the console).
  ~DrmOutput();

  /// Blits `framebuffer` (width×height) scaled to the mode, swaps, and queues a page flip
  /// of the new buffer; waits for the previous flip first, so one is pending at most and
  /// the next frame renders while this one waits for vblank. A driver without vblank
  /// events (PresentStats::fake_vblank: bochs completes a flip at once) is paced here
  /// instead: the flip waits for the next refresh of the mode's period after the last
  /// one, and completes before present() returns (docs/latency.md, "Clocks").
  /// Errors: the kernel refused the flip (e.g. the master was lost on a VT switch) or no
  /// flip completed in 1 s.
  Status present(GLuint framebuffer, int width, int height);
  /// Waits until the last queued frame is on screen, so that stats() counts it.
  Status finish();

  const std::string& device() const;
  const KmsConnector& connector() const;
  const KmsMode& mode() const;
  const PresentStats& stats() const;
  /// The completed flips' timestamps since the last call (the kernel's, CLOCK_MONOTONIC;
  /// the mode set's own time for the first frame), oldest first.
  std::vector<std::int64_t> take_shown();
  /// When the last frame was in its GBM buffer, before any wait for a flip or refresh.
  std::int64_t last_ready_ns() const;

  /// Every /dev/dri/card* with its connectors (no master needed).
  static std::vector<DrmDeviceInfo> list_devices();

 private:
  struct Impl;
  explicit DrmOutput(std::unique_ptr<Impl> impl);
  std::unique_ptr<Impl> impl_;
};

/// The name of the connector direct mode would take on any card ("DP-2"), to find the
/// headset among the window system's monitors (X11 names them after the connectors).
/// bad_input, listing every connector, when none matches.
Result<std::string> find_headset_connector(const KmsWanted& wanted);

}  // namespace foveal::render
