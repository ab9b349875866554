// Geometry pass: world-space normal and tangent frame for the G-buffer.
layout(location = 0) in vec3 a_position;
layout(location = 1) in vec3 a_normal;
layout(location = 2) in vec2 a_uv;
layout(location = 3) in vec4 a_tangent;
layout(location = 4) in vec2 a_uv1;
layout(location = 5) in vec4 a_color;

uniform mat4 u_model;
uniform mat3 u_normal_matrix;
uniform mat4 u_view_proj;

out vec3 v_normal;
out vec4 v_tangent;
out vec2 v_uv;
out vec2 v_uv1;
out vec4 v_color;

void main() {
  v_normal = u_normal_matrix * a_normal;
  v_tangent = vec4(mat3(u_model) * a_tangent.xyz, a_tangent.w);
  v_uv = a_uv;
  v_uv1 = a_uv1;
  v_color = a_color;
  gl_Position = u_view_proj * (u_model * vec4(a_position, 1.0));
}
