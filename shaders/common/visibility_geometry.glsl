// The scene's triangles as the visibility pipeline's material pass reads them
// (SceneGeometry in render/scene/include/foveal/render/scene.hpp): interleaved GltfVertex
// data, 32-bit indices, one record per draw; and the surface point of a triangle seen
// through a screen pixel, with perspective-correct barycentrics.

struct DrawRecord {
  mat4 model;
  vec4 normal_matrix[3];  // columns of transpose(inverse(mat3(model)))
  uint first_index, base_vertex, material, pad;
};
layout(std430, binding = 0) readonly buffer Draws { DrawRecord draws[]; };
layout(std430, binding = 1) readonly buffer Vertices { float vertex_data[]; };
layout(std430, binding = 2) readonly buffer Indices { uint index_data[]; };

const uint VERTEX_FLOATS = 18u;  // position 3, normal 3, uv 2, tangent 4, uv1 2, colour 4

struct Vertex {
  vec3 position, normal;
  vec2 uv;
  vec4 tangent;
  vec2 uv1;
  vec4 color;
};

float vf(uint base, uint k) { return vertex_data[base + k]; }

Vertex fetch_vertex(uint v) {
  uint b = v * VERTEX_FLOATS;
  Vertex o;
  o.position = vec3(vf(b, 0u), vf(b, 1u), vf(b, 2u));
  o.normal = vec3(vf(b, 3u), vf(b, 4u), vf(b, 5u));
  o.uv = vec2(vf(b, 6u), vf(b, 7u));
  o.tangent = vec4(vf(b, 8u), vf(b, 9u), vf(b, 10u), vf(b, 11u));
  o.uv1 = vec2(vf(b, 12u), vf(b, 13u));
  o.color = vec4(vf(b, 14u), vf(b, 15u), vf(b, 16u), vf(b, 17u));
  return o;
}

// Perspective-correct barycentrics of the point of a triangle (clip-space vertices c0..c2)
// seen through NDC position p, and their derivatives along NDC x and y. The point on
// the triangle, sum(l_i c_i), projects to p: sum(l_i (c_i.x - p.x c_i.w)) = 0, likewise in
// y, and sum(l_i) = 1; l is the normalised cross product of the two constraint rows. No
// division by w: vertices behind the eye are fine.
struct Barycentrics {
  vec3 l, dx, dy;
};

Barycentrics barycentrics(vec4 c0, vec4 c1, vec4 c2, vec2 p) {
  vec3 X = vec3(c0.x, c1.x, c2.x), Y = vec3(c0.y, c1.y, c2.y), W = vec3(c0.w, c1.w, c2.w);
  vec3 a = X - p.x * W, b = Y - p.y * W;
  vec3 k = cross(a, b);
  vec3 kx = cross(-W, b), ky = cross(a, -W);  // d k / d p.x, d k / d p.y
  float s = k.x + k.y + k.z;
  float sx = kx.x + kx.y + kx.z, sy = ky.x + ky.y + ky.z;
  Barycentrics o;
  o.l = k / s;
  o.dx = (kx * s - k * sx) / (s * s);
  o.dy = (ky * s - k * sy) / (s * s);
  return o;
}

// Whether the rasteriser saw the triangle's front (counter-clockwise in window
// coordinates): the sign of the homogeneous 2D determinant, valid across the near plane.
bool front_facing(vec4 c0, vec4 c1, vec4 c2) {
  return determinant(mat3(c0.xyw, c1.xyw, c2.xyw)) > 0.0;
}

vec2 mix3(vec3 l, vec2 a, vec2 b, vec2 c) { return l.x * a + l.y * b + l.z * c; }
vec3 mix3(vec3 l, vec3 a, vec3 b, vec3 c) { return l.x * a + l.y * b + l.z * c; }
vec4 mix3(vec3 l, vec4 a, vec4 b, vec4 c) { return l.x * a + l.y * b + l.z * c; }
