#pragma once
// Options shared by the commands that render (render, bench): scene, method, EFR levels,
// f, per-eye fovea, output size, display model.
#include <array>
#include <string>

#include "foveal/core/display_model.hpp"
#include "foveal/render/compositor.hpp"
#include "foveal/render/scene.hpp"

namespace CLI {
class App;
}

namespace foveal::cmd {

struct RenderArgs {
  std::string scene;  ///< default: the bundled Dungeon
  std::string variant;  ///< --variant: a KHR_materials_variants variant of the scene
  std::string method = "rmfr";
  std::string pipeline = render::kDefaultPipelineName;
  std::string temporal = "off";  ///< on: temporal accumulation (docs/rmfr.md)
  std::string blend_at = "output";  ///< --blend-at: where blended surfaces are shaded (render::BlendAt)
  double sigma_d = 2.0, sigma_nd = 3.0;
  std::string dominant = "right";
  double fx = 0.3, fy = 0.3;
  double kfr_alpha = 4.0, layer_scale = 0.0;
  double inset_deg = 0.0, inset_band_deg = 3.0;  ///< inset methods (docs/methods.md)
  std::string f;  ///< "auto": estimate f_x, f_y from a full frame (RMFR)
  std::string fovea_left, fovea_right;  ///< empty: the centre, or with `log` the log's fovea
  std::string head;  ///< --head X,Y,Z,QW,QX,QY,QZ (relative to the scene's view)
  std::string log, at;  ///< --log LOG --at SECONDS: the log's head pose and fovea then
  std::string size = "2880x1600";
  std::string display;
  bool no_distortion = false;
  std::string light_lists = "tiles";  ///< --light-lists: tiles or all
};

void add_render_options(CLI::App& sub, RenderArgs& a);

/// Where the frame's head pose and foveae came from.
struct HeadSource {
  std::string kind = "scene";  ///< "scene" (the identity: the scene's view), "head" (--head) or "log"
  std::string log;
  double at_s = 0, sample_s = 0;  ///< with a log: the time asked, and the sample's whose pose and fovea were used
  std::array<std::string, 2> fovea{"default", "default"};  ///< per eye: "default" (centre), "option" or "log"
};

/// What the options mean once checked: the compositor's options and the frame.
struct RenderSetup {
  std::string scene;
  render::SceneOptions scene_options;
  render::CompositorOptions compositor;
  render::FrameParams frame;
  bool auto_f = false;
  HeadSource head;
};
Result<RenderSetup> resolve(const RenderArgs& a);

/// The bundled default scene.
std::string default_scene();

}  // namespace foveal::cmd
