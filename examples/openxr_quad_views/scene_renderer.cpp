#include "scene_renderer.hpp"

#include <glm/gtc/type_ptr.hpp>

#include "foveal/render/gl.hpp"

namespace example {

namespace {

const char* const kVertex = R"(#version 450 core
layout(location = 0) in vec3 position;
layout(location = 1) in vec3 normal;
layout(location = 2) in vec2 uv;
layout(location = 5) in vec4 color;
uniform mat4 model, view_proj;
out vec3 v_normal;
out vec2 v_uv;
out vec4 v_color;
void main() {
  v_normal = mat3(transpose(inverse(model))) * normal;
  v_uv = uv;
  v_color = color;
  gl_Position = view_proj * model * vec4(position, 1.0);
}
)";

const char* const kFragment = R"(#version 450 core
in vec3 v_normal;
in vec2 v_uv;
in vec4 v_color;
uniform sampler2D base_tex;
uniform bool has_tex;
uniform vec4 base_factor;
out vec4 color;
void main() {
  vec4 base = base_factor * v_color * (has_tex ? texture(base_tex, v_uv) : vec4(1.0));
  float light = 0.35 + 0.65 * max(dot(normalize(v_normal), normalize(vec3(0.3, 1.0, 0.4))), 0.0);
  color = vec4(base.rgb * light, 1.0);
}
)";

unsigned compile(GLenum type, const char* src) {
  const GLuint s = glCreateShader(type);
  glShaderSource(s, 1, &src, nullptr);
  glCompileShader(s);
  return s;
}

}  // namespace

foveal::Result<SceneRenderer> SceneRenderer::create(const std::string& scene_path) {
  auto scene = foveal::render::load_scene(scene_path);
  if (!scene) return scene.error();
  SceneRenderer r;
  r.scene_ = std::move(*scene);
  r.program_ = glCreateProgram();
  const GLuint vs = compile(GL_VERTEX_SHADER, kVertex), fs = compile(GL_FRAGMENT_SHADER, kFragment);
  glAttachShader(r.program_, vs);
  glAttachShader(r.program_, fs);
  glLinkProgram(r.program_);
  glDeleteShader(vs);
  glDeleteShader(fs);
  GLint ok = 0;
  glGetProgramiv(r.program_, GL_LINK_STATUS, &ok);
  if (!ok) return foveal::Error{foveal::ErrorKind::internal, "the example's scene shader does not link"};
  glCreateFramebuffers(1, &r.fbo_);
  return r;
}

SceneRenderer::~SceneRenderer() {
  if (program_) glDeleteProgram(program_);
  if (fbo_) glDeleteFramebuffers(1, &fbo_);
  if (depth_) glDeleteRenderbuffers(1, &depth_);
}

void SceneRenderer::draw(unsigned texture, int w, int h, const ViewParams& v, int layer) {
  if (w != depth_w_ || h != depth_h_) {
    if (depth_) glDeleteRenderbuffers(1, &depth_);
    glCreateRenderbuffers(1, &depth_);
    glNamedRenderbufferStorage(depth_, GL_DEPTH_COMPONENT32F, w, h);
    depth_w_ = w, depth_h_ = h;
  }
  if (layer >= 0)
    glNamedFramebufferTextureLayer(fbo_, GL_COLOR_ATTACHMENT0, texture, 0, layer);
  else
    glNamedFramebufferTexture(fbo_, GL_COLOR_ATTACHMENT0, texture, 0);
  glNamedFramebufferRenderbuffer(fbo_, GL_DEPTH_ATTACHMENT, GL_RENDERBUFFER, depth_);
  glBindFramebuffer(GL_FRAMEBUFFER, fbo_);
  glViewport(0, 0, w, h);
  glEnable(GL_DEPTH_TEST);
  glEnable(GL_FRAMEBUFFER_SRGB);
  glClearColor(0.05f, 0.05f, 0.08f, 1.0f);
  glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
  // The view in the scene: the scene's viewer, then the eye (metres scaled to scene units).
  const float upm = scene_.view.units_per_meter;
  glm::mat4 eye = v.eye_to_head;
  eye[3] = glm::vec4(glm::vec3(eye[3]) * upm, 1.0f);
  const glm::mat4 view = glm::inverse(scene_.view.head_to_world * eye);
  const float n = 0.05f * upm, f = 200.0f * upm;
  glm::mat4 proj(0.0f);  // an off-axis frustum from the four tangents
  proj[0][0] = 2.0f / (v.tan_right - v.tan_left);
  proj[1][1] = 2.0f / (v.tan_up - v.tan_down);
  proj[2][0] = (v.tan_right + v.tan_left) / (v.tan_right - v.tan_left);
  proj[2][1] = (v.tan_up + v.tan_down) / (v.tan_up - v.tan_down);
  proj[2][2] = -(f + n) / (f - n);
  proj[2][3] = -1.0f;
  proj[3][2] = -2.0f * f * n / (f - n);
  const glm::mat4 view_proj = proj * view;
  glUseProgram(program_);
  glUniformMatrix4fv(glGetUniformLocation(program_, "view_proj"), 1, GL_FALSE, glm::value_ptr(view_proj));
  const GLint u_model = glGetUniformLocation(program_, "model"), u_has = glGetUniformLocation(program_, "has_tex"),
              u_factor = glGetUniformLocation(program_, "base_factor");
  glUniform1i(glGetUniformLocation(program_, "base_tex"), 0);
  for (const auto& item : scene_.draws) {
    const auto& p = scene_.primitives[static_cast<std::size_t>(item.primitive)];
    const bool has_material = p.material >= 0 && static_cast<std::size_t>(p.material) < scene_.materials.size();
    const auto& m = has_material ? scene_.materials[static_cast<std::size_t>(p.material)] : foveal::render::Material{};
    if (m.blend) continue;
    const bool tex = m.base_color_tex >= 0 && static_cast<std::size_t>(m.base_color_tex) < scene_.textures.size();
    if (tex) glBindTextureUnit(0, scene_.textures[static_cast<std::size_t>(m.base_color_tex)].id());
    glUniform1i(u_has, tex ? 1 : 0);
    glUniform4fv(u_factor, 1, glm::value_ptr(m.base_color));
    glUniformMatrix4fv(u_model, 1, GL_FALSE, glm::value_ptr(item.world));
    glBindVertexArray(p.vao.id());
    glDrawElements(GL_TRIANGLES, p.index_count, GL_UNSIGNED_INT, nullptr);
  }
  glBindVertexArray(0);
  glBindFramebuffer(GL_FRAMEBUFFER, 0);
  glNamedFramebufferTexture(fbo_, GL_COLOR_ATTACHMENT0, 0, 0);
}

}  // namespace example
