#pragma once
// foveald's command-line options.
#include <cstdint>
#include <optional>
#include <string>

#include "foveal/render/compositor.hpp"

namespace foveal::daemon {

struct Options {
  std::string source;         ///< source spec (drivers/probe); empty = replay of `replay`
  std::string replay;         ///< gaze log; empty = the bundled recording
  std::optional<double> duration_s;  ///< stop after this many seconds, whatever the source
  std::string head;           ///< recorded, static or a pose spec (psvr2, vive[:PATH], auto); empty: recorded when the source has poses
  std::string display;        ///< display-model JSON; empty = from the profile / default
  std::string out = "foveald-out";
  std::string profile;        ///< empty = the active profile (or built-in defaults)
  std::string quality;        ///< jod:T or off, replacing the startup profile's `quality`; empty: the profile's
  std::string control;        ///< control socket path; empty = default
  bool no_control = false;
  bool shm = true;            ///< publish the fovea in shared memory
  double speed = 1.0;
  bool loop = false;
  std::optional<double> start_s, end_s;
  bool headless = true;
  bool render = true;         ///< run the compositor (false: gaze only)
  bool trace = true;          ///< write trace.csv (off for --service unless set)
  std::uint64_t frames = 0;   ///< stop after this many frames (0: when the replay ends)
  double fps = 0;             ///< headless frame pacing (0: as fast as the renderer goes)
  std::string scene;          ///< empty: the bundled Dungeon
  std::string method = "rmfr";
  std::string pipeline = render::kDefaultPipelineName;  ///< gbuffer or visibility
  std::string temporal;       ///< on or off: temporal accumulation; empty: the profile's (off by default)
  std::string blend_at = "output";  ///< output or samples: where blended surfaces are shaded (render::BlendAt)
  std::string pacing;         ///< asap or jit; empty: jit on a display, asap headless
  std::string latch = "late"; ///< late or early (docs/latency.md)
  std::string predict = "on"; ///< on or off: the fovea predicted to display time
  std::string size;           ///< WxH; empty: the display model's
  int save_every = 0;         ///< save every Nth frame as PNG (first and last always)
  std::string monitor;        ///< window mode: fullscreen on this monitor
  bool drm = false;           ///< direct mode on a DRM/KMS connector
  std::string drm_device;     ///< direct mode: /dev/dri/cardN; empty: the first that fits
  std::string connector;      ///< direct mode: connector name; empty: the headset's
  std::string mode;           ///< direct mode: WxH[@HZ]; empty: the display model's
  bool distortion = true;     ///< apply the display model's lens distortion
  bool json = false;
  int verbosity = 0;          ///< +1 per -v, -1 per -q
  int rt_priority = 0;        ///< > 0: SCHED_FIFO for the gaze thread
};

}  // namespace foveal::daemon
