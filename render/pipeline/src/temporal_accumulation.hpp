#pragma once
// Foveated temporal accumulation (docs/rmfr.md, "Temporal accumulation"; FrameParams::
// temporal): RMFR's reduced-buffer grid jittered every frame (shaders/temporal/jitter.glsl)
// and each eye's resolved frame blended into a full-resolution history, reprojected by
// the camera's motion and rejected at disocclusions, outside the current samples' range
// and where the fovea moved (shaders/temporal/accumulate.frag).
#include <array>
#include <cstddef>
#include <cstdint>

#include <glm/mat4x4.hpp>
#include <glm/vec2.hpp>

#include "foveal/core/error.hpp"
#include "foveal/render/gl_objects.hpp"
#include "foveal/render/shader_loader.hpp"
#include "foveal/rmfr.hpp"

namespace foveal::render {
struct EyeView;
}

namespace foveal::render::detail {

/// Frame k's offset of the reduced buffer's grid, in texels, each axis in (-0.5, 0.5):
/// Halton(2, 3) over a period of 16 frames.
glm::vec2 temporal_jitter(std::uint64_t frame);

/// Degrees the fovea may move from one frame to the next before the history is dropped
/// as a saccade's (smooth pursuit stays under 0.4° a frame at 90 Hz, saccades pass 1°).
inline constexpr double kSaccadeDeg = 1.0;

/// Degrees between the view rays through two normalised fovea points of one frustum.
double fovea_step_deg(const rmfr::Plan& a, const rmfr::Plan& b);

class TemporalAccumulation {
 public:
  /// Compiles the pass. Targets are made on first use. Errors: the shader's.
  static Result<TemporalAccumulation> create(const gl::ShaderLoader& shaders);

  /// This frame's jitter (texels); next_frame() moves to the next one.
  glm::vec2 jitter() const { return temporal_jitter(frame_); }
  void next_frame() { ++frame_; }

  /// Drops the history of both eyes (the next frame shows its own samples only), or of one.
  void reset();
  void drop(std::size_t eye) { eyes_[eye].valid = false; }

  /// Blends eye `eye`'s lit reduced buffer `reduced` (drawn with jitter() under `plan`) into its history and returns the texture that now
  /// holds the eye's frame (RGBA16F, linear, the plan's screen size). `depth`: the eye's
  /// full-resolution depth (D32F), 0 for a pattern (fixed on the screen); `sample_depth`:
  /// the depth-buffer value of each reduced-buffer sample (the surface's R32F depth).
  GLuint accumulate(std::size_t eye, const rmfr::Plan& plan, GLuint reduced, GLuint depth, GLuint sample_depth,
                    const EyeView& view);

  /// Bytes of the histories held.
  std::size_t bytes() const;

 private:
  struct History {
    gl::Texture color, depth;  // RGBA16F (rgb, frames), R32F view depth (-1: background)
    gl::Framebuffer fbo;
  };
  struct EyeState {
    std::array<History, 2> history;  // read one, write the other
    int written = 0;                 // which holds the last frame
    int width = 0, height = 0;
    bool valid = false;
    rmfr::Plan plan;
    glm::mat4 view_proj{1.0f};
  };
  gl::Program program_;
  gl::Sampler nearest_;
  gl::VertexArray vao_;
  std::array<EyeState, 2> eyes_;
  std::uint64_t frame_ = 0;
};

}  // namespace foveal::render::detail
