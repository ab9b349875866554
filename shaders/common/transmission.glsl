// KHR_materials_transmission (+ _volume) in the forward passes (blend.frag at output,
// transparent_layer.frag at the kept samples; docs/scenes.md, "Materials"): the opaque
// result behind the surface, seen through it. The includer declares u_view_proj (the
// eye's) and includes common/material.glsl and common/gbuffer_texel.glsl first.

// The eye's lit opaque result before any blended surface (W×H, mipmapped, screen
// positions): a copy of the output, or the reduced buffer resolved for it.
layout(binding = 12) uniform sampler2D u_behind;

// Along the refracted ray to the back of a volume of the material's thickness (scaled
// into world units by the draw's scale per axis; straight through when thin-walled),
// blurred by the roughness as the ior spreads it, attenuated by Beer-Lambert
// c^(d / attenuationDistance), tinted by the base colour and weighted by the
// transmission and what Fresnel does not reflect.
vec3 transmitted(vec3 p, vec3 n, vec3 v, Surface s, Transmission t, vec3 model_scale) {
  vec3 ray = normalize(refract(-v, n, 1.0 / u_ior)) * t.thickness * model_scale;
  vec4 clip = u_view_proj * vec4(p + ray, 1.0);
  vec2 uv = clip.xy / clip.w * 0.5 + 0.5;
  float lod = log2(float(textureSize(u_behind, 0).x)) * s.roughness * clamp(u_ior * 2.0 - 2.0, 0.0, 1.0);
  vec3 behind = textureLod(u_behind, uv, lod).rgb;
  vec3 attenuation = vec3(1.0);
  if (u_transmission.z > 0.0) attenuation = pow(u_attenuation_color, vec3(length(ray) / u_transmission.z));
  float n_dot_v = clamp(dot(n, v), 0.0, 1.0);
  vec3 f = s.f0 + (s.f90 - s.f0) * pow(1.0 - n_dot_v, 5.0);
  return t.factor * (1.0 - s.metallic) * (1.0 - f) * s.albedo * attenuation * behind;
}

// The lit colour of a transmissive surface point: what it reflects and what it lets through.
vec3 lit_transmissive(ivec2 pixel, vec3 p, vec3 n, vec3 camera, Surface surface, SurfacePoint s, vec3 model_scale) {
  Transmission t = material_transmission(s);
  surface.transmission = t.factor;
  return lit_color(pixel, p, n, camera, surface) + transmitted(p, n, normalize(camera - p), surface, t, model_scale);
}
