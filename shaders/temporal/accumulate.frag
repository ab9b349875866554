// Temporal accumulation (docs/rmfr.md, "Temporal accumulation"): one eye's lit reduced
// buffer, drawn on a jittered grid, resolved to full resolution and blended into the
// eye's history, which is reprojected by the camera's motion and rejected where it no
// longer applies. Writes the new history (rgb, frames accumulated) and the depth the next
// frame tests against. Viewport: the eye's W×H, origin 0.
#include "foveal/rmfr_mapping.glsl"
#include "temporal/jitter.glsl"

layout(binding = 0) uniform sampler2D u_reduced;     // lit reduced buffer
layout(binding = 1) uniform sampler2D u_history;     // the previous frame's history
layout(binding = 2) uniform sampler2D u_prev_depth;  // the previous frame's view depth per pixel (-1: background)
layout(binding = 3) uniform sampler2D u_depth;       // this frame's depth buffer (D32F), W×H
layout(binding = 4) uniform sampler2D u_sample_depth;  // each reduced-buffer sample's depth-buffer value

uniform vec2 u_screen_size;
uniform vec2 u_buffer_size;
uniform vec2 u_fovea, u_f;
uniform vec2 u_prev_buffer_size, u_prev_fovea, u_prev_f;  // the previous frame's plan
uniform mat4 u_view_proj, u_inv_view_proj, u_prev_view_proj;
uniform int u_history_valid;  // 0: no history (first frame, reset, saccade, other plan)
uniform int u_has_depth;      // 0: a pattern, fixed on the screen: no motion, no depth
uniform float u_min_blend;    // the smallest weight of the current frame

layout(location = 0) out vec4 o_history;
layout(location = 1) out float o_depth;

// Frames the history may stand for (the jitter sequence's period).
const float MAX_FRAMES = 16.0;
// Relative view-depth difference above which the reprojected history shows another surface.
const float DEPTH_TOLERANCE = 0.02;
// The same between a sample and a pixel up to a few pixels away (a sloped surface).
const float SAMPLE_TOLERANCE = 0.1;

// Reduced-buffer samples per screen pixel (area) at normalised screen point p under a plan.
float samples_per_pixel(vec2 p, vec2 buffer_size, vec2 c, vec2 f) {
  vec2 d = p - c;
  vec2 D = foveal_rmfr_side(c, d);
  vec2 g = f + abs(d);
  vec2 du_dp = (f / g) * ((f + D) / g);  // the forward map's slope, normalised units
  vec2 per_axis = du_dp * buffer_size / u_screen_size;
  return per_axis.x * per_axis.y;
}

// View depth (clip w) of a depth-buffer value, -1 for the background (depth 1): the last
// row of the inverse projection does not depend on x and y.
float view_depth_of(float d) {
  return d >= 1.0 ? -1.0 : 1.0 / (u_inv_view_proj * vec4(0.0, 0.0, d * 2.0 - 1.0, 1.0)).w;
}

// Whether view depths a and b (-1: background) are one surface, within `tolerance` of b.
bool same_surface(float a, float b, float tolerance) {
  return (a < 0.0 || b < 0.0) ? (a < 0.0 && b < 0.0) : abs(a - b) <= tolerance * b;
}

void main() {
  vec2 p = gl_FragCoord.xy;
  vec2 pn = p / u_screen_size;

  // This pixel's surface now, and where it was on the previous frame.
  float view_depth = -1.0;  // this frame's view depth (-1: background)
  float expected = -1.0;    // the same point's view depth on the previous frame
  vec2 prev_p = p;
  bool on_screen = true;
  if (u_has_depth != 0) {
    float depth = texelFetch(u_depth, ivec2(p), 0).r;
    vec2 ndc = pn * 2.0 - 1.0;
    vec4 prev_clip;
    if (depth >= 1.0) {  // the background lies at infinity: only the camera's rotation moves it
      vec4 far = u_inv_view_proj * vec4(ndc, 1.0, 1.0);
      vec4 near = u_inv_view_proj * vec4(ndc, -1.0, 1.0);
      prev_clip = u_prev_view_proj * vec4(far.xyz / far.w - near.xyz / near.w, 0.0);
    } else {
      vec4 w = u_inv_view_proj * vec4(ndc, depth * 2.0 - 1.0, 1.0);
      vec4 world = vec4(w.xyz / w.w, 1.0);
      view_depth = (u_view_proj * world).w;
      prev_clip = u_prev_view_proj * world;
      expected = prev_clip.w;
    }
    on_screen = prev_clip.w > 0.0;
    prev_p = (prev_clip.xy / prev_clip.w * 0.5 + 0.5) * u_screen_size;
    on_screen = on_screen && all(greaterThanEqual(prev_p, vec2(0.0))) && all(lessThanEqual(prev_p, u_screen_size));
  }

  // This frame: where p lands on the jittered grid, bilinear between the samples of its
  // own surface (the full-resolution depth says which): a foreground's samples bleeding
  // over its silhouette would otherwise build up in the history as a halo.
  vec2 b = foveal_rmfr_forward(pn, u_fovea, u_f) * u_buffer_size;
  vec2 t = clamp(rmfr_unjittered(b, u_jitter, u_buffer_size, u_screen_size, u_fovea, u_f), vec2(0.5), u_buffer_size - 0.5);
  ivec2 last = ivec2(u_buffer_size) - 1;
  vec2 tc = t - 0.5;
  ivec2 t0 = ivec2(floor(tc));
  vec2 ft = tc - vec2(t0);
  vec3 plain = vec3(0.0), own = vec3(0.0);
  float own_weight = 0.0;
  for (int k = 0; k < 4; ++k) {
    ivec2 o = ivec2(k & 1, k >> 1);
    ivec2 texel = clamp(t0 + o, ivec2(0), last);
    float w = (o.x == 1 ? ft.x : 1.0 - ft.x) * (o.y == 1 ? ft.y : 1.0 - ft.y);
    vec3 c = texelFetch(u_reduced, texel, 0).rgb;
    plain += w * c;
    if (u_has_depth == 0 || same_surface(view_depth_of(texelFetch(u_sample_depth, texel, 0).r), view_depth, SAMPLE_TOLERANCE)) {
      own += w * c;
      own_weight += w;
    }
  }
  vec3 current = own_weight > 1e-4 ? own / own_weight : plain;

  // How much of the history still applies, 0 to 1, and its value: the bilinear read at
  // the reprojected point over only those of its 2×2 pixels that showed this surface
  // (disocclusion: none of them did; at an edge, the other surface's pixels are left out).
  float keep = (u_history_valid != 0 && on_screen) ? 1.0 : 0.0;
  vec2 q = prev_p - 0.5;
  ivec2 q0 = ivec2(floor(q));
  vec2 fq = q - vec2(q0);
  vec4 history = vec4(0.0);
  float found = 0.0;
  for (int k = 0; k < 4 && keep > 0.0; ++k) {  // no reads where there is no history
    ivec2 o = ivec2(k & 1, k >> 1);
    ivec2 pix = clamp(q0 + o, ivec2(0), ivec2(u_screen_size) - 1);
    float w = (o.x == 1 ? fq.x : 1.0 - fq.x) * (o.y == 1 ? fq.y : 1.0 - fq.y);
    bool same = true;
#ifndef TEMPORAL_NO_DISOCCLUSION
    if (u_has_depth != 0) {
      float d = texelFetch(u_prev_depth, pix, 0).r;
      same = same_surface(d, expected, DEPTH_TOLERANCE);
    }
#endif
    if (same) {
      history += w * texelFetch(u_history, pix, 0);
      found += w;
    }
  }
  if (found < 1e-3) keep = 0.0;
  history = keep > 0.0 ? history / found : vec4(current, 0.0);  // never a rejected or unwritten value
#ifndef TEMPORAL_NO_DENSITY_WEIGHT
  // The mapping moved (the fovea): history made of sparser samples than this frame's
  // counts only in their ratio, so a pixel the fovea comes to is this frame's at once.
  float density = samples_per_pixel(pn, u_buffer_size, u_fovea, u_f);
  float prev_density = samples_per_pixel(prev_p / u_screen_size, u_prev_buffer_size, u_prev_fovea, u_prev_f);
  keep *= clamp(prev_density / max(density, 1e-9), 0.0, 1.0);
#else
  float density = samples_per_pixel(pn, u_buffer_size, u_fovea, u_f);
#endif

  float frames = min(keep * history.a + 1.0, MAX_FRAMES);
  // The current frame's weight: the running mean's 1/frames, but never below the samples
  // a pixel gets per frame (at a sample per pixel or more, in the fovea, the current
  // frame alone: accumulation could only blur it) nor below u_min_blend.
  float alpha = max(1.0 / frames, clamp(density, u_min_blend, 1.0));
  alpha = keep > 0.0 ? 1.0 - (1.0 - alpha) * keep : 1.0;
  o_history = vec4(current, frames);
  o_depth = view_depth;
  // The current frame alone (no history, or a sample per pixel): the box below could not
  // change the result, and its 18 reads are half of the pass's.
  if (alpha >= 1.0) return;

  // The samples around it on the same surface: the box the history is clamped into (in
  // samples, not pixels: a peripheral texel spans several pixels, whose 3×3 would hold
  // one sample).
  ivec2 n = ivec2(floor(t));
  vec3 lo = current, hi = current;
  for (int y = -1; y <= 1; ++y)
    for (int x = -1; x <= 1; ++x) {
      ivec2 texel = clamp(n + ivec2(x, y), ivec2(0), last);
      if (u_has_depth != 0 && !same_surface(view_depth_of(texelFetch(u_sample_depth, texel, 0).r), view_depth, SAMPLE_TOLERANCE))
        continue;
      vec3 s = texelFetch(u_reduced, texel, 0).rgb;
      lo = min(lo, s);
      hi = max(hi, s);
    }
#ifndef TEMPORAL_NO_CLAMP
  vec3 past = clamp(history.rgb, lo, hi);
#else
  vec3 past = history.rgb;
#endif
  o_history.rgb = mix(past, current, alpha);
}
