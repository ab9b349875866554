#pragma once
// foveal-rmfr: Rectangular-Mapping Foveated Rendering (RMFR) with per-eye levels chosen by
// eye dominance (EFR), for an application's own deferred renderer (docs/rmfr-library.md).
//
// Per eye and frame:
//   1. plan_eye / plan_efr: the reduced buffer's size from σ and the viewport, the
//      mapping's f and the fovea (estimate_f: f from one full-resolution frame);
//   2. Foveator::map: the application's full-resolution G-buffer textures (any number,
//      any formats) into the reduced G-buffer (EyeBuffers holds one);
//   3. the application's lighting shader runs on the reduced buffer, finding each texel's
//      screen position and eccentricity with the GLSL of glsl_source() (set_uniforms);
//   4. Foveator::resolve: the lit reduced buffer to the eye's full-resolution viewport,
//      optionally through a lens distortion.
//
// Errors are values (foveal::Result, foveal/core/error.hpp), never exceptions: each
// function lists the kinds it returns. Thread safety is given per function, GLFW style.
// GL functions need a current OpenGL 4.5 core context; "GL thread" below means the thread
// on which that context is current, and every GL object must be destroyed there while it
// is current. Texture and framebuffer names are plain GL names (GLuint), so this header
// needs no GL header.
#include <array>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <span>
#include <string>
#include <string_view>

#include "foveal/core/error.hpp"

#define FOVEAL_RMFR_API __attribute__((visibility("default")))

namespace foveal::rmfr {

/// "MAJOR.MINOR.PATCH" of the library loaded at run time.
/// Thread safety: any thread.
FOVEAL_RMFR_API const char* version();

/// One eye's projection: tangents of the frustum's half-angles (left and bottom negative).
struct Frustum {
  double tan_left = -1, tan_right = 1, tan_bottom = -1, tan_top = 1;
};

/// A fovea in an eye's viewport, normalised: origin top-left, y down (foveal-client's
/// foveal_fovea x / eye_width, y / eye_height).
struct Fovea {
  double x = 0.5, y = 0.5;
};

/// What an application asks of one eye.
struct EyeParams {
  int width = 0, height = 0;  ///< the eye's full-resolution viewport, pixels, >= 1
  double sigma = 1.0;         ///< level >= 1: the reduced buffer is round(W/σ) × round(H/σ)
  double fx = 0.3, fy = 0.3;  ///< f per axis, fractions of W and H, > 0 (estimate_f finds them)
  Fovea fovea{};              ///< NaN/Inf -> centre, outside [0,1] -> clamped onto the viewport
  Frustum frustum{};          ///< for eccentricities and the lens; tan_left < tan_right, tan_bottom < tan_top
};

/// One eye's frame: what the passes and the shader uniforms need.
struct Plan {
  int screen_w = 0, screen_h = 0;   ///< W×H
  int buffer_w = 0, buffer_h = 0;   ///< w×h of the reduced buffer
  double sigma = 1.0;
  double fovea_x = 0.5, fovea_y = 0.5;  ///< normalised, GL frame (origin bottom-left), sanitised
  double fx = 0.3, fy = 0.3;        ///< effective f: 1e30 at σ = 1 (the identity, full rate), else the
                                    ///< asked f raised to rmfr_f_floor (the periphery floor) where below it
  Frustum frustum{};

  /// Samples the lighting pass shades (w·h).
  std::size_t shaded_samples() const { return static_cast<std::size_t>(buffer_w) * static_cast<std::size_t>(buffer_h); }
};

/// Plans one eye. Errors: bad_input for a viewport below 1×1 or above 16384, σ < 1, f <= 0,
/// any of them not finite, or a degenerate frustum. Thread safety: any thread.
FOVEAL_RMFR_API Result<Plan> plan_eye(const EyeParams& eye);

/// EFR: the dominant eye at σ_d, the other at σ_nd >= σ_d (foveal-client's foveal_settings).
struct EfrSettings {
  double sigma_d = 2.0, sigma_nd = 3.0;
  int dominant_eye = 1;  ///< 0 left, 1 right
  double fx = 0.3, fy = 0.3;
};

/// Plans both eyes (index 0 left) with EFR's levels and f; each eye's viewport, fovea and
/// frustum from `eyes` (their sigma, fx, fy are ignored). Errors: bad_input for σ_nd < σ_d,
/// a dominant eye other than 0 or 1, and everything plan_eye refuses (naming the eye).
/// Thread safety: any thread.
FOVEAL_RMFR_API Result<std::array<Plan, 2>> plan_efr(const EfrSettings& settings, const std::array<EyeParams, 2>& eyes);

/// 8-bit RGBA pixels in memory, rows top first (as glReadPixels gives them bottom first:
/// set bottom_up).
struct ImageView {
  const std::uint8_t* rgba = nullptr;
  int width = 0, height = 0;
  std::size_t stride = 0;  ///< bytes per row; 0: width·4
  bool bottom_up = false;
};

struct AutoF {
  double fx = 0.3, fy = 0.3;
  double predicted_fpsnr_db = 0;  ///< foveated PSNR of RMFR's predicted image against the frame
  int evaluations = 0;
  double ms = 0;  ///< CPU time of the estimate
};

/// Automatic f (docs/methods.md): from one full-resolution side-by-side frame (left eye
/// on the left; the lit output at σ = 1), the f_x, f_y in [0.05, 1] that maximise RMFR's
/// predicted foveated PSNR at the eyes' levels and foveae. pixels_per_degree: at the
/// centre of an eye (W / (tan_right - tan_left) · π/180 for a Frustum).
/// Errors: bad_input for an empty view, an odd width, σ < 1, ppd <= 0.
/// Thread safety: any thread (CPU only; a few hundred ms for 2880×1600).
FOVEAL_RMFR_API Result<AutoF> estimate_f(const ImageView& full_frame, std::array<double, 2> sigma,
                                         std::array<Fovea, 2> foveae, double pixels_per_degree);

/// Lens distortion folded into the resolve (docs/display-model.md): channel c of panel
/// point p (normalised, origin top-left) shows the rendered image at
/// center + x·channel_scale[c]·(1 + k1 r² + k2 r⁴ + k3 r⁶), x = (p - center) in tangent
/// units of the plan's frustum. Points outside the image are black.
struct Lens {
  double center_x = 0.5, center_y = 0.5;
  double k1 = 0, k2 = 0, k3 = 0;
  std::array<double, 3> channel_scale{1.0, 1.0, 1.0};
};

/// The GL side: the library's programs and samplers. map and resolve change this GL
/// state and leave it so: the draw framebuffer, viewport, program, vertex array, the
/// textures of units 0..n-1 (samplers on them reset to 0), GL_FRAMEBUFFER_SRGB enabled
/// (values stay linear through sRGB targets), depth test, stencil test, blending,
/// scissor test and face culling disabled, and the colour mask set to all channels.
class FOVEAL_RMFR_API Foveator {
 public:
  /// Compiles the resolve programs. Errors: unsupported when the current context is not
  /// OpenGL 4.5 or has none, internal when a program does not build (with the log).
  /// Thread safety: GL thread.
  static Result<Foveator> create();
  Foveator(Foveator&&) noexcept;
  Foveator& operator=(Foveator&&) noexcept;
  ~Foveator();  ///< GL thread, context current

  /// Mapping pass: texel (i, j) of colour attachment k of `dst_framebuffer` receives
  /// texel floor(inverse((i + 0.5)/w)·W), floor(inverse((j + 0.5)/h)·H) of
  /// `gbuffer_textures[k]` (fetched, never filtered: a blend of two surfaces' normals or
  /// depths is not a surface), over the plan's w×h at the origin. Source textures are
  /// 2D, at least W×H; float, normalised, sRGB and integer formats are copied as they
  /// are, depth formats into a single-channel float (R32F) attachment. Attachment k must
  /// have a matching kind (integer for integer sources) and be at least w×h; the draw
  /// buffers of `dst_framebuffer` are set to attachments 0..n-1. The first call with a
  /// new combination of kinds compiles a program for it.
  /// Errors: bad_input for a plan whose sizes plan_eye would not give, no textures or
  /// more than GL_MAX_DRAW_BUFFERS, a name that is no 2D texture, a source smaller than
  /// the plan's screen, a stencil-only source, the default framebuffer, a destination
  /// attachment missing, of the wrong kind or smaller than the buffer, or an incomplete
  /// destination; internal when the program for a new layout does not build. GL errors
  /// are left to the caller's glGetError (the pass does not wait on GL).
  /// Thread safety: GL thread.
  Status map(const Plan& plan, std::span<const unsigned> gbuffer_textures, unsigned dst_framebuffer);

  /// Resolve pass: each pixel of the eye's W×H viewport at (x, y) in `dst_framebuffer`
  /// (0: the default framebuffer) reads `lit_texture` (2D, at least w×h, its w×h region
  /// at the origin used) bilinearly where RMFR's forward map sends it; through `lens`
  /// when given. Errors: bad_input for a plan plan_eye would not give, a name that is no
  /// 2D texture, an integer texture or one smaller than the buffer. GL errors are left to
  /// the caller's glGetError. Thread safety: GL thread.
  Status resolve(const Plan& plan, unsigned lit_texture, unsigned dst_framebuffer, int x, int y,
                 const Lens* lens = nullptr);

 private:
  struct Impl;
  explicit Foveator(std::unique_ptr<Impl> impl);
  std::unique_ptr<Impl> impl_;
};

/// Sets the uniforms of foveal/rmfr.glsl (foveal_rmfr_*) on `program` from `plan`
/// (glProgramUniform; uniforms the program does not use are skipped).
/// Thread safety: GL thread.
FOVEAL_RMFR_API void set_uniforms(unsigned program, const Plan& plan);

/// One eye's reduced buffers: a framebuffer with one texture per G-buffer attachment
/// (the source's format; depth formats as R32F), for Foveator::map, and a framebuffer
/// with the lit texture, for the lighting pass and Foveator::resolve. Textures are
/// nearest-filtered and clamped, the lit one linear-filtered.
class FOVEAL_RMFR_API EyeBuffers {
 public:
  /// Errors: bad_input for a size outside [1, 16384], no formats or more than
  /// GL_MAX_DRAW_BUFFERS, a stencil-only format; unsupported when GL refuses a format or
  /// a framebuffer is incomplete. Thread safety: GL thread.
  static Result<EyeBuffers> create(int width, int height, std::span<const unsigned> gbuffer_formats,
                                   unsigned lit_format);
  EyeBuffers(EyeBuffers&&) noexcept;
  EyeBuffers& operator=(EyeBuffers&&) noexcept;
  ~EyeBuffers();  ///< GL thread, context current

  /// Reallocates (same formats) when the plan's w×h differs from the current size;
  /// errors as create. Thread safety: GL thread.
  Status fit(const Plan& plan);

  int width() const;
  int height() const;
  std::size_t attachments() const;
  unsigned gbuffer_framebuffer() const;
  unsigned gbuffer_texture(std::size_t i) const;  ///< 0 past attachments()
  unsigned lit_framebuffer() const;
  unsigned lit_texture() const;

 private:
  struct Impl;
  explicit EyeBuffers(std::unique_ptr<Impl> impl);
  std::unique_ptr<Impl> impl_;
};

/// The GLSL for an application's lighting shader: foveal/rmfr.glsl with its #include
/// expanded, to paste after the #version line. Thread safety: any thread.
FOVEAL_RMFR_API std::string_view glsl_source();

/// One of the library's GLSL files by its include name ("foveal/rmfr.glsl",
/// "foveal/rmfr_mapping.glsl"), unexpanded; empty for any other name. For shader loaders
/// that resolve #include themselves. Thread safety: any thread.
FOVEAL_RMFR_API std::string_view glsl_file(std::string_view name);

/// Where the installed GLSL files lie (the folder holding foveal/rmfr.glsl), for loaders
/// that read #include files from disk. Thread safety: any thread.
FOVEAL_RMFR_API std::string glsl_directory();

}  // namespace foveal::rmfr
