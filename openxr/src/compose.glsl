// The quad views' composition (composer.hpp), one source for both APIs: gl_composer.cpp
// compiles it at run time behind "#version 330 core", the build compiles it to SPIR-V for
// vk_composer.cpp (glslangValidator, FOVEAL_VULKAN). FOVEAL_VERTEX picks the stage.
// Vulkan's framebuffer and images run top-down where OpenGL's run bottom-up; VkComposer
// passes the up/down tangents and the rectangles' vertical terms flipped, so the math
// below is the same for both.
#ifdef FOVEAL_VULKAN
#define VERTEX_ID gl_VertexIndex
#define P(name) params.name
#else
#define VERTEX_ID gl_VertexID
#define P(name) name
#endif

#ifdef FOVEAL_VERTEX
void main() {
  // One triangle over the whole target.
  vec2 p = vec2(float((VERTEX_ID << 1) & 2), float(VERTEX_ID & 2));
  gl_Position = vec4(p * 2.0 - 1.0, 0.0, 1.0);
}
#else

#ifdef FOVEAL_VULKAN
layout(set = 0, binding = 0) uniform sampler2D outer_tex;
layout(set = 0, binding = 1) uniform sampler2D inner_tex;
layout(push_constant) uniform Params {
  vec4 out_tan, outer_tan, inner_tan, outer_uv, inner_uv;
  vec2 out_size;
  float band;
} params;
layout(location = 0) out vec4 color;
#define OUTER(uv) texture(outer_tex, uv)
#define INNER(uv) texture(inner_tex, uv)
#define OUTER_SIZE vec2(textureSize(outer_tex, 0))
#define INNER_SIZE vec2(textureSize(inner_tex, 0))
#else
// A view in a layer of an array swapchain (GL_TEXTURE_2D_ARRAY): the GL composer defines
// FOVEAL_OUTER_ARRAY / FOVEAL_INNER_ARRAY and sets the layer. Vulkan needs neither: its
// image view names the layer and is sampled as a plain 2D image.
#ifdef FOVEAL_OUTER_ARRAY
uniform sampler2DArray outer_tex;
uniform float outer_layer;
#define OUTER(uv) texture(outer_tex, vec3(uv, outer_layer))
#define OUTER_SIZE vec2(textureSize(outer_tex, 0).xy)
#else
uniform sampler2D outer_tex;
#define OUTER(uv) texture(outer_tex, uv)
#define OUTER_SIZE vec2(textureSize(outer_tex, 0))
#endif
#ifdef FOVEAL_INNER_ARRAY
uniform sampler2DArray inner_tex;
uniform float inner_layer;
#define INNER(uv) texture(inner_tex, vec3(uv, inner_layer))
#define INNER_SIZE vec2(textureSize(inner_tex, 0).xy)
#else
uniform sampler2D inner_tex;
#define INNER(uv) texture(inner_tex, uv)
#define INNER_SIZE vec2(textureSize(inner_tex, 0))
#endif
uniform vec4 out_tan, outer_tan, inner_tan;  // left, right, down, up
uniform vec4 outer_uv, inner_uv;             // the sub-image: offset.xy, size.zw in texture units
uniform vec2 out_size;
uniform float band;                          // radians
out vec4 color;
#endif

// The bilinear taps stay inside the sub-image `rect` (offset.xy, size.zw; Vulkan's size.w
// is negative): its edge texels repeat, as CLAMP_TO_EDGE does for a whole image, so a view
// that shares its image or array layer with others shows none of their pixels at its edge.
vec2 inside(vec2 uv, vec4 rect, vec2 size) {
  vec2 a = rect.xy, b = rect.xy + rect.zw, h = 0.5 / size;
  return clamp(uv, min(a, b) + h, max(a, b) - h);
}

// Tangent space: the output pixel's direction (x/-z, y/-z) in the eye's view, where the
// outer and inner views are both rectangles (their poses are identical).
void main() {
  vec2 p = gl_FragCoord.xy / P(out_size);
  vec2 t = vec2(mix(P(out_tan).x, P(out_tan).y, p.x), mix(P(out_tan).z, P(out_tan).w, p.y));
  vec2 ou = (t - P(outer_tan).xz) / (P(outer_tan).yw - P(outer_tan).xz);
  vec4 c = OUTER(inside(P(outer_uv).xy + ou * P(outer_uv).zw, P(outer_uv), OUTER_SIZE));
  // The angle inside the inner view's nearest edge, per axis as the field of view states it.
  vec2 a = atan(t);
  vec4 e = atan(P(inner_tan));
  float d = min(min(a.x - e.x, e.y - a.x), min(a.y - e.z, e.w - a.y));
  if (d > 0.0) {
    vec2 iu = (t - P(inner_tan).xz) / (P(inner_tan).yw - P(inner_tan).xz);
    vec4 ci = INNER(inside(P(inner_uv).xy + iu * P(inner_uv).zw, P(inner_uv), INNER_SIZE));
    c = mix(c, ci, P(band) > 0.0 ? smoothstep(0.0, P(band), d) : 1.0);
  }
  color = c;
}
#endif
