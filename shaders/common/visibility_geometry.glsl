// The scene's triangles as the visibility pipeline's material pass reads them
// (SceneGeometry in render/scene/include/foveal/render/scene.hpp): interleaved GltfVertex
// data, 32-bit indices, one record per draw; and the surface point of a triangle seen
// through a screen pixel, with perspective-correct barycentrics.

// Read through texture-buffer views (SceneGeometry): one gather per texel, where
// llvmpipe would read a storage buffer one scalar per lane at a time.
layout(binding = 8) uniform samplerBuffer u_vertex_pairs;  // GltfVertex: 9 RG32F texels
layout(binding = 9) uniform usamplerBuffer u_triangles;    // indices: one RGB32UI texel per triangle
layout(binding = 10) uniform samplerBuffer u_draw_floats;  // DrawRecord: 8 RGBA32F texels
// Unit 11 unless the includer moves it (transparent_layer.frag: lighting's sheen table is there).
#ifndef DRAW_UINTS_UNIT
#define DRAW_UINTS_UNIT 11
#endif
layout(binding = DRAW_UINTS_UNIT) uniform usamplerBuffer u_draw_uints;  // the same as RGBA32UI

struct DrawRecord {
  mat4 model;
  vec4 normal_matrix[3];  // columns of transpose(inverse(mat3(model)))
  uint first_index, base_vertex, material;
};

const int DRAW_TEXELS = 8;

DrawRecord fetch_draw(uint draw) {
  int b = int(draw) * DRAW_TEXELS;
  DrawRecord d;
  d.model = mat4(texelFetch(u_draw_floats, b), texelFetch(u_draw_floats, b + 1), texelFetch(u_draw_floats, b + 2),
                 texelFetch(u_draw_floats, b + 3));
  for (int c = 0; c < 3; ++c) d.normal_matrix[c] = texelFetch(u_draw_floats, b + 4 + c);
  uvec4 u = texelFetch(u_draw_uints, b + 7);
  d.first_index = u.x, d.base_vertex = u.y, d.material = u.z;
  return d;
}

uint draw_material(uint draw) { return texelFetch(u_draw_uints, int(draw) * DRAW_TEXELS + 7).z; }

// The vertex indices of triangle `t` of a draw (a primitive's indices start at a
// multiple of 3: every primitive is a triangle list).
uvec3 fetch_triangle(DrawRecord d, uint t) { return texelFetch(u_triangles, int(d.first_index / 3u + t)).xyz + d.base_vertex; }

const int VERTEX_PAIRS = 9;  // position 3, normal 3, uv 2, tangent 4, uv1 2, colour 4: 18 floats

struct Vertex {
  vec3 position, normal;
  vec2 uv;
  vec4 tangent;
  vec2 uv1;
  vec4 color;
};

Vertex fetch_vertex(uint v) {
  int b = int(v) * VERTEX_PAIRS;
  vec2 p[VERTEX_PAIRS];
  for (int k = 0; k < VERTEX_PAIRS; ++k) p[k] = texelFetch(u_vertex_pairs, b + k).xy;
  Vertex o;
  o.position = vec3(p[0], p[1].x);
  o.normal = vec3(p[1].y, p[2]);
  o.uv = p[3];
  o.tangent = vec4(p[4], p[5]);
  o.uv1 = p[6];
  o.color = vec4(p[7], p[8]);
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

// The depth a material's texels carry from a classification to its EQUAL-tested pass:
// exact in float for up to 2^20 materials (detail::material_depth in C++).
float material_depth(uint material) { return float(material + 1u) / 1048576.0; }
