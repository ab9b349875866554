// The compositor's render targets: made or grown when a frame needs them, and the
// bytes they hold (Compositor::memory).
#include <algorithm>
#include <cmath>
#include <cstddef>

#include "compositor_impl.hpp"

namespace foveal::render {

// Exact size for single-buffer methods; the layered methods' atlas changes shape with
// the fovea every frame, so it only grows.
void Compositor::Impl::ensure_transformed(std::size_t eye, int w, int h, bool grow_only) {
  const auto& t = transformed[eye];
  if (auto size = detail::realloc_size(t.has_value(), t ? t->width : 0, t ? t->height : 0, w, h, grow_only))
    transformed[eye] = detail::SurfaceTargets::create(size->first, size->second, true, layout);
}

void Compositor::Impl::ensure_undistorted() {
  if (!undistorted) undistorted = detail::ColorTarget::create(eye_w, eye_h, reduced_format(), true);
}

// What transmission reads (W×H with its mips): a copy of the output (copy_behind) or,
// at the kept samples, the eye's opaque reduced buffer resolved into it (samples_blend).
void Compositor::Impl::ensure_behind() {
  if (behind) return;
  const int levels = 1 + static_cast<int>(std::floor(std::log2(static_cast<double>(std::max(eye_w, eye_h)))));
  detail::ColorTarget t;
  t.width = eye_w, t.height = eye_h;
  t.bytes_per_pixel = opt.float_output ? 16 : 4;
  t.texture = gl::make_texture_2d(reduced_format(), eye_w, eye_h, levels);
  glTextureParameteri(t.texture.id(), GL_TEXTURE_MIN_FILTER, GL_LINEAR_MIPMAP_LINEAR);
  glTextureParameteri(t.texture.id(), GL_TEXTURE_MAG_FILTER, GL_LINEAR);
  glTextureParameteri(t.texture.id(), GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
  glTextureParameteri(t.texture.id(), GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
  t.fbo = gl::Framebuffer::create();
  glNamedFramebufferTexture(t.fbo.id(), GL_COLOR_ATTACHMENT0, t.texture.id(), 0);
  glNamedFramebufferDrawBuffer(t.fbo.id(), GL_COLOR_ATTACHMENT0);
  behind = std::move(t);
}

void Compositor::Impl::ensure_reduced(std::size_t eye, int w, int h, bool grow_only) {
  const auto& r = reduced[eye];
  if (auto size = detail::realloc_size(r.has_value(), r ? r->width : 0, r ? r->height : 0, w, h, grow_only))
    reduced[eye] = detail::ColorTarget::create(size->first, size->second, reduced_format(), true);
}

Result<const detail::SurfaceTargets*> Compositor::Impl::gbuffer_targets() {
  if (!gbuffer) {
    gbuffer = detail::SurfaceTargets::create(eye_w, eye_h, false, layout);
    if (glCheckNamedFramebufferStatus(gbuffer->fbo.id(), GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE)
      return Error{ErrorKind::unsupported, "the G-buffer framebuffer is incomplete on this GL implementation"};
  }
  return &*gbuffer;
}

TargetMemory Compositor::memory() const {
  TargetMemory t = memory(Pipeline::gbuffer);
  const TargetMemory v = memory(Pipeline::visibility);
  t.gbuffer += v.gbuffer;
  t.transformed += v.transformed;
  t.visibility = v.visibility;
  t.temporal = v.temporal;
  return t;
}

TargetMemory Compositor::memory(Pipeline p) const {
  const Impl& m = *impl_;
  TargetMemory t;
  for (std::size_t i = 0; i < 2; ++i)
    if (m.reduced[i]) t.reduced += m.reduced[i]->bytes();
  // The blend target under the lens, and the copy transmission reads (its mips: a third more).
  t.output = m.output.bytes() + (m.undistorted ? m.undistorted->bytes() : 0) + (m.behind ? m.behind->bytes() * 4 / 3 : 0);
  t.shadow = m.shadow.bytes();
  if (p == Pipeline::visibility) {
    t.visibility = m.visibility->visibility_bytes() + (m.transparent ? m.transparent->bytes() : 0);
    t.transformed = m.visibility->eye_surface_bytes();
    t.gbuffer = m.visibility->full_surface_bytes();
    t.temporal = m.temporal ? m.temporal->bytes() : 0;
    return t;
  }
  t.gbuffer = m.gbuffer ? m.gbuffer->bytes() : 0;
  for (std::size_t i = 0; i < 2; ++i)
    if (m.transformed[i]) t.transformed += m.transformed[i]->bytes();
  return t;
}

}  // namespace foveal::render
