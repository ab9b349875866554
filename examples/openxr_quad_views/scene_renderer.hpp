#pragma once
// A small forward renderer for the example: a glTF scene loaded by foveal::render, drawn
// with its base colour (texture, factor, vertex colour) under one light, into a texture
// of the app's swapchain for one view's pose and field of view.
#include <glm/mat4x4.hpp>
#include <string>
#include <utility>

#include "foveal/core/error.hpp"
#include "foveal/render/scene.hpp"

namespace example {

struct ViewParams {
  glm::mat4 eye_to_head{1.0f};  ///< the view's pose relative to the scene's viewer (metres)
  float tan_left, tan_right, tan_down, tan_up;
};

class SceneRenderer {
 public:
  static foveal::Result<SceneRenderer> create(const std::string& scene_path);
  SceneRenderer(SceneRenderer&& o) noexcept
      : scene_(std::move(o.scene_)), program_(std::exchange(o.program_, 0u)), fbo_(std::exchange(o.fbo_, 0u)),
        depth_(std::exchange(o.depth_, 0u)), depth_w_(o.depth_w_), depth_h_(o.depth_h_) {}
  SceneRenderer& operator=(SceneRenderer&&) = delete;
  ~SceneRenderer();
  /// Draws into `texture` (w×h, the sub-image at its origin), or into its layer `layer`
  /// when it is a GL_TEXTURE_2D_ARRAY (layer ≥ 0).
  void draw(unsigned texture, int w, int h, const ViewParams& v, int layer = -1);

 private:
  SceneRenderer() = default;
  foveal::render::Scene scene_;
  unsigned program_ = 0, fbo_ = 0, depth_ = 0;
  int depth_w_ = 0, depth_h_ = 0;
};

}  // namespace example
