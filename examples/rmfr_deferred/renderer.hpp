#pragma once
// The example's own deferred renderer: a G-buffer of its own layout (albedo + gloss,
// normal, an integer object id, depth), a Blinn-Phong lighting shader of its own, and
// RMFR + EFR through foveal-rmfr. Both eyes side by side, left eye on the left.
#include <array>
#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <foveal/rmfr.hpp>

class Renderer {
 public:
  /// Needs a current GL 4.5 context. Errors: "" on success, else what failed.
  static std::unique_ptr<Renderer> create(int eye_width, int eye_height, std::string& error);
  ~Renderer();

  /// One frame: full resolution when `plans` is empty, else each eye through its plan.
  std::string render(const std::optional<std::array<foveal::rmfr::Plan, 2>>& plans);
  /// The side-by-side output, 8-bit sRGB RGBA, top row first.
  std::vector<std::uint8_t> read_rgba() const;
  int eye_width() const { return w_; }
  int eye_height() const { return h_; }
  foveal::rmfr::Frustum frustum() const { return {-tan_x_, tan_x_, -tan_y_, tan_y_}; }

 private:
  struct Gl;
  Renderer() = default;
  int w_ = 0, h_ = 0;
  double tan_x_ = 0, tan_y_ = 0;
  std::unique_ptr<Gl> gl_;
};
