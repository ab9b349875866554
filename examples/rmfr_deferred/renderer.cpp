#include "renderer.hpp"

#include <algorithm>
#include <cstddef>
#include <cstdio>

#define GL_GLEXT_PROTOTYPES 1
#include <GL/glcorearb.h>

#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/type_ptr.hpp>

namespace {

constexpr const char* kFullscreenVert = R"(#version 450 core
void main() {
  vec2 p = vec2((gl_VertexID << 1) & 2, gl_VertexID & 2);
  gl_Position = vec4(p * 2.0 - 1.0, 0.0, 1.0);
})";

constexpr const char* kGeometryVert = R"(#version 450 core
layout(location = 0) in vec3 a_pos;
layout(location = 1) in vec3 a_normal;
layout(location = 2) in uint a_object;
uniform mat4 u_view_proj;
out vec3 v_world;
out vec3 v_normal;
flat out uint v_object;
void main() {
  v_world = a_pos, v_normal = a_normal, v_object = a_object;
  gl_Position = u_view_proj * vec4(a_pos, 1.0);
})";

// G-buffer: 0 albedo + gloss (RGBA8), 1 normal (RGB10_A2, n/2 + 1/2), 2 object id (R32UI), depth.
constexpr const char* kGeometryFrag = R"(#version 450 core
in vec3 v_world;
in vec3 v_normal;
flat in uint v_object;
layout(location = 0) out vec4 g_albedo;
layout(location = 1) out vec4 g_normal;
layout(location = 2) out uint g_object;
void main() {
  // Detail everywhere: a fine checker and thin lines in world units.
  vec3 n = normalize(v_normal);
  vec2 q = abs(n.y) > 0.5 ? v_world.xz : (abs(n.x) > 0.5 ? v_world.zy : v_world.xy);
  float checker = mod(floor(q.x * 5.0) + floor(q.y * 5.0), 2.0);
  float lines = step(0.92, fract(q.x * 23.0)) + step(0.92, fract(q.y * 17.0));
  vec3 palette = 0.5 + 0.45 * cos(6.2831 * (float(v_object) * 0.17 + vec3(0.0, 0.33, 0.67)));
  g_albedo = vec4(palette * mix(0.3, 1.0, checker) * (1.0 - 0.6 * min(lines, 1.0)), v_object == 0u ? 0.2 : 0.8);
  g_normal = vec4(n * 0.5 + 0.5, 0.0);
  g_object = v_object;
})";

// Lighting in view space from depth: 4 point lights and a sun, Blinn-Phong, a rim on
// every other object id, Reinhard tone map. FOVEATED: each texel's screen position comes
// from foveal-rmfr's GLSL; otherwise a texel is its pixel.
constexpr const char* kLightingFrag = R"(
layout(binding = 0) uniform sampler2D g_albedo;
layout(binding = 1) uniform sampler2D g_normal;
layout(binding = 2) uniform usampler2D g_object;
layout(binding = 3) uniform sampler2D g_depth;
uniform ivec2 u_origin;
uniform vec2 u_size;
uniform mat4 u_inv_proj;
uniform mat3 u_view_rot;
uniform vec4 u_light_pos[4];  // view space, radius
uniform vec3 u_light_color[4];
uniform vec3 u_sun_dir;       // view space, towards the sun
out vec4 o_color;

vec2 ndc_of(ivec2 t) {
#ifdef FOVEATED
  return foveal_rmfr_ndc(t);
#else
  return (vec2(t) + 0.5) / u_size * 2.0 - 1.0;
#endif
}

void main() {
  ivec2 t = ivec2(gl_FragCoord.xy) - u_origin;
  float depth = texelFetch(g_depth, t, 0).r;
  if (depth >= 1.0) {
    o_color = vec4(0.35, 0.45, 0.6, 1.0);
    return;
  }
  vec4 h = u_inv_proj * vec4(ndc_of(t), depth * 2.0 - 1.0, 1.0);
  vec3 p = h.xyz / h.w;
  vec3 n = normalize(u_view_rot * (texelFetch(g_normal, t, 0).xyz * 2.0 - 1.0));
  vec4 albedo = texelFetch(g_albedo, t, 0);
  vec3 v = normalize(-p);
  float shininess = mix(8.0, 96.0, albedo.a);
  vec3 c = 0.08 * albedo.rgb;
  for (int i = 0; i < 5; ++i) {
    vec3 l = i < 4 ? u_light_pos[i].xyz - p : u_sun_dir;
    float fall = i < 4 ? max(1.0 - dot(l, l) / (u_light_pos[i].w * u_light_pos[i].w), 0.0) : 1.0;
    vec3 color = i < 4 ? u_light_color[i] : vec3(0.6, 0.55, 0.5);
    l = normalize(l);
    float diffuse = max(dot(n, l), 0.0);
    float specular = diffuse > 0.0 ? pow(max(dot(n, normalize(l + v)), 0.0), shininess) * albedo.a : 0.0;
    c += color * fall * (albedo.rgb * diffuse + specular);
  }
  if ((texelFetch(g_object, t, 0).r & 1u) == 1u) c += vec3(0.25, 0.2, 0.1) * pow(1.0 - max(dot(n, v), 0.0), 3.0);
  o_color = vec4(c / (1.0 + c), 1.0);
})";

GLuint compile(std::initializer_list<std::pair<GLenum, std::string>> stages, std::string& error) {
  GLuint program = glCreateProgram();
  for (const auto& [type, text] : stages) {
    GLuint s = glCreateShader(type);
    const char* src = text.c_str();
    glShaderSource(s, 1, &src, nullptr);
    glCompileShader(s);
    GLint ok = 0;
    glGetShaderiv(s, GL_COMPILE_STATUS, &ok);
    if (!ok) {
      char log[4096] = {};
      glGetShaderInfoLog(s, sizeof log, nullptr, log);
      error = std::string("shader: ") + log;
    }
    glAttachShader(program, s);
    glDeleteShader(s);
  }
  glLinkProgram(program);
  GLint ok = 0;
  glGetProgramiv(program, GL_LINK_STATUS, &ok);
  if (!ok && error.empty()) error = "a program does not link";
  return program;
}

GLuint texture(GLenum format, int w, int h) {
  GLuint t = 0;
  glCreateTextures(GL_TEXTURE_2D, 1, &t);
  glTextureStorage2D(t, 1, format, w, h);
  glTextureParameteri(t, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
  glTextureParameteri(t, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
  return t;
}

struct Vertex {
  float pos[3], normal[3];
  std::uint32_t object;
};

// A floor and a grid of boxes.
std::vector<Vertex> scene() {
  std::vector<Vertex> v;
  auto quad = [&](glm::vec3 o, glm::vec3 a, glm::vec3 b, std::uint32_t id) {
    const glm::vec3 n = glm::normalize(glm::cross(a, b));
    const glm::vec3 c[6] = {o, o + a, o + a + b, o, o + a + b, o + b};
    for (const glm::vec3& p : c) v.push_back({{p.x, p.y, p.z}, {n.x, n.y, n.z}, id});
  };
  quad({-12, 0, 12}, {24, 0, 0}, {0, 0, -24}, 0);
  std::uint32_t id = 1;
  for (int row = 0; row < 3; ++row)
    for (int col = -2; col <= 2; ++col, ++id) {
      const float s = 0.35f + 0.12f * float((row + col + 3) % 3), x = 1.3f * float(col), z = -1.6f * float(row);
      const glm::vec3 lo(x - s, 0, z - s), e(2 * s, 0, 0), f(0, 2 * s * (1.0f + 0.4f * float(row)), 0), g(0, 0, 2 * s);
      quad(lo + g, e, f, id);          // front
      quad(lo + e, -e, f, id);         // back (from lo + e going -x)
      quad(lo, g, f, id);              // left ... normals from the winding
      quad(lo + e + g, -g, f, id);     // right
      quad(lo + f + g, e, -g, id);     // top
    }
  return v;
}

}  // namespace

struct Renderer::Gl {
  GLuint geometry = 0, lighting_full = 0, lighting_foveated = 0;
  GLuint vao = 0, vbo = 0, empty_vao = 0;
  GLsizei vertices = 0;
  GLuint albedo = 0, normal = 0, object = 0, depth = 0, gbuffer_fbo = 0;
  GLuint output = 0, output_fbo = 0;
  std::optional<foveal::rmfr::Foveator> foveator;
  std::array<std::optional<foveal::rmfr::EyeBuffers>, 2> eyes;
  ~Gl() {
    for (GLuint p : {geometry, lighting_full, lighting_foveated}) glDeleteProgram(p);
    for (GLuint t : {albedo, normal, object, depth, output}) glDeleteTextures(1, &t);
    for (GLuint f : {gbuffer_fbo, output_fbo}) glDeleteFramebuffers(1, &f);
    for (GLuint a : {vao, empty_vao}) glDeleteVertexArrays(1, &a);
    glDeleteBuffers(1, &vbo);
  }
};

Renderer::~Renderer() = default;

std::unique_ptr<Renderer> Renderer::create(int w, int h, std::string& error) {
  std::unique_ptr<Renderer> r(new Renderer);
  r->w_ = w, r->h_ = h;
  r->tan_y_ = 0.8, r->tan_x_ = 0.8 * w / h;
  auto g = std::make_unique<Gl>();
  g->geometry = compile({{GL_VERTEX_SHADER, kGeometryVert}, {GL_FRAGMENT_SHADER, kGeometryFrag}}, error);
  const std::string head = "#version 450 core\n";
  g->lighting_full = compile({{GL_VERTEX_SHADER, kFullscreenVert}, {GL_FRAGMENT_SHADER, head + kLightingFrag}}, error);
  // The foveated variant: foveal-rmfr's GLSL pasted after #version.
  g->lighting_foveated = compile({{GL_VERTEX_SHADER, kFullscreenVert},
                                  {GL_FRAGMENT_SHADER, head + "#define FOVEATED 1\n" + std::string(foveal::rmfr::glsl_source()) + kLightingFrag}},
                                 error);
  if (!error.empty()) return nullptr;
  auto foveator = foveal::rmfr::Foveator::create();
  if (!foveator) {
    error = foveator.error().message;
    return nullptr;
  }
  g->foveator = std::move(*foveator);

  const std::vector<Vertex> v = scene();
  g->vertices = static_cast<GLsizei>(v.size());
  glCreateBuffers(1, &g->vbo);
  glNamedBufferStorage(g->vbo, static_cast<GLsizeiptr>(v.size() * sizeof(Vertex)), v.data(), 0);
  glCreateVertexArrays(1, &g->vao);
  glCreateVertexArrays(1, &g->empty_vao);
  glVertexArrayVertexBuffer(g->vao, 0, g->vbo, 0, sizeof(Vertex));
  for (GLuint a = 0; a < 3; ++a) {
    glEnableVertexArrayAttrib(g->vao, a);
    glVertexArrayAttribBinding(g->vao, a, 0);
  }
  glVertexArrayAttribFormat(g->vao, 0, 3, GL_FLOAT, GL_FALSE, offsetof(Vertex, pos));
  glVertexArrayAttribFormat(g->vao, 1, 3, GL_FLOAT, GL_FALSE, offsetof(Vertex, normal));
  glVertexArrayAttribIFormat(g->vao, 2, 1, GL_UNSIGNED_INT, offsetof(Vertex, object));

  g->albedo = texture(GL_RGBA8, w, h), g->normal = texture(GL_RGB10_A2, w, h);
  g->object = texture(GL_R32UI, w, h), g->depth = texture(GL_DEPTH_COMPONENT24, w, h);
  glCreateFramebuffers(1, &g->gbuffer_fbo);
  glNamedFramebufferTexture(g->gbuffer_fbo, GL_COLOR_ATTACHMENT0, g->albedo, 0);
  glNamedFramebufferTexture(g->gbuffer_fbo, GL_COLOR_ATTACHMENT1, g->normal, 0);
  glNamedFramebufferTexture(g->gbuffer_fbo, GL_COLOR_ATTACHMENT2, g->object, 0);
  glNamedFramebufferTexture(g->gbuffer_fbo, GL_DEPTH_ATTACHMENT, g->depth, 0);
  const GLenum draw[] = {GL_COLOR_ATTACHMENT0, GL_COLOR_ATTACHMENT1, GL_COLOR_ATTACHMENT2};
  glNamedFramebufferDrawBuffers(g->gbuffer_fbo, 3, draw);
  g->output = texture(GL_SRGB8_ALPHA8, 2 * w, h);
  glCreateFramebuffers(1, &g->output_fbo);
  glNamedFramebufferTexture(g->output_fbo, GL_COLOR_ATTACHMENT0, g->output, 0);
  for (GLuint f : {g->gbuffer_fbo, g->output_fbo})
    if (glCheckNamedFramebufferStatus(f, GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE) {
      error = "a framebuffer is incomplete";
      return nullptr;
    }
  r->gl_ = std::move(g);
  return r;
}

std::string Renderer::render(const std::optional<std::array<foveal::rmfr::Plan, 2>>& plans) {
  Gl& g = *gl_;
  const glm::mat4 proj = glm::frustum(-tan_x_ * 0.1, tan_x_ * 0.1, -tan_y_ * 0.1, tan_y_ * 0.1, 0.1, 60.0);
  const glm::vec3 lights[4] = {{-3, 1.5f, 1}, {3, 1.2f, 0}, {0, 2.5f, -3}, {0, 0.6f, 2.5f}};
  const glm::vec3 colors[4] = {{1.0f, 0.6f, 0.3f}, {0.3f, 0.6f, 1.0f}, {0.8f, 0.8f, 0.8f}, {0.6f, 1.0f, 0.5f}};
  for (int e = 0; e < 2; ++e) {
    const glm::vec3 eye(e == 0 ? -0.032f : 0.032f, 1.7f, 4.5f);
    const glm::mat4 view = glm::lookAt(eye, eye + glm::vec3(0, -0.35f, -1), glm::vec3(0, 1, 0));
    // Geometry at full resolution.
    glBindFramebuffer(GL_FRAMEBUFFER, g.gbuffer_fbo);
    glViewport(0, 0, w_, h_);
    glEnable(GL_DEPTH_TEST);
    glDisable(GL_FRAMEBUFFER_SRGB);
    glClearColor(0, 0, 0, 0);
    glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
    glUseProgram(g.geometry);
    const glm::mat4 view_proj = proj * view;
    glProgramUniformMatrix4fv(g.geometry, glGetUniformLocation(g.geometry, "u_view_proj"), 1, GL_FALSE, glm::value_ptr(view_proj));
    glBindVertexArray(g.vao);
    glDrawArrays(GL_TRIANGLES, 0, g.vertices);
    glDisable(GL_DEPTH_TEST);

    // Lighting: on the full G-buffer into the output, or on the eye's reduced buffer.
    const GLuint lp = plans ? g.lighting_foveated : g.lighting_full;
    const int origin_x = e * w_;
    std::array<GLuint, 4> sources = {g.albedo, g.normal, g.object, g.depth};
    if (plans) {
      const foveal::rmfr::Plan& plan = (*plans)[static_cast<std::size_t>(e)];
      auto& buffers = g.eyes[static_cast<std::size_t>(e)];
      if (!buffers) {
        const unsigned formats[] = {GL_RGBA8, GL_RGB10_A2, GL_R32UI, GL_DEPTH_COMPONENT24};
        auto b = foveal::rmfr::EyeBuffers::create(plan.buffer_w, plan.buffer_h, formats, GL_RGBA16F);
        if (!b) return b.error().message;
        buffers = std::move(*b);
      }
      if (auto s = buffers->fit(plan); !s) return s.error().message;
      if (auto s = g.foveator->map(plan, sources, buffers->gbuffer_framebuffer()); !s) return s.error().message;
      for (std::size_t k = 0; k < sources.size(); ++k) sources[k] = buffers->gbuffer_texture(k);
      foveal::rmfr::set_uniforms(lp, plan);
      glBindFramebuffer(GL_FRAMEBUFFER, buffers->lit_framebuffer());
      glViewport(0, 0, plan.buffer_w, plan.buffer_h);
      glProgramUniform2i(lp, glGetUniformLocation(lp, "u_origin"), 0, 0);
    } else {
      glBindFramebuffer(GL_FRAMEBUFFER, g.output_fbo);
      glEnable(GL_FRAMEBUFFER_SRGB);
      glViewport(origin_x, 0, w_, h_);
      glProgramUniform2i(lp, glGetUniformLocation(lp, "u_origin"), origin_x, 0);
    }
    glProgramUniform2f(lp, glGetUniformLocation(lp, "u_size"), float(w_), float(h_));
    const glm::mat4 inv_proj = glm::inverse(proj);
    glProgramUniformMatrix4fv(lp, glGetUniformLocation(lp, "u_inv_proj"), 1, GL_FALSE, glm::value_ptr(inv_proj));
    const glm::mat3 rot(view);
    glProgramUniformMatrix3fv(lp, glGetUniformLocation(lp, "u_view_rot"), 1, GL_FALSE, glm::value_ptr(rot));
    glm::vec4 light_pos[4];
    for (int i = 0; i < 4; ++i) light_pos[i] = glm::vec4(glm::vec3(view * glm::vec4(lights[i], 1)), 6.0f);  // radius 6
    glProgramUniform4fv(lp, glGetUniformLocation(lp, "u_light_pos"), 4, glm::value_ptr(light_pos[0]));
    glProgramUniform3fv(lp, glGetUniformLocation(lp, "u_light_color"), 4, glm::value_ptr(colors[0]));
    const glm::vec3 sun = glm::normalize(rot * glm::vec3(0.4f, 1.0f, 0.3f));
    glProgramUniform3fv(lp, glGetUniformLocation(lp, "u_sun_dir"), 1, glm::value_ptr(sun));
    glUseProgram(lp);
    glBindTextures(0, 4, sources.data());
    glBindVertexArray(g.empty_vao);
    glDrawArrays(GL_TRIANGLES, 0, 3);

    if (plans) {  // the lit reduced buffer to this eye's half of the output
      auto s = g.foveator->resolve((*plans)[static_cast<std::size_t>(e)], g.eyes[static_cast<std::size_t>(e)]->lit_texture(),
                                   g.output_fbo, origin_x, 0);
      if (!s) return s.error().message;
    }
  }
  glFinish();
  if (GLenum err = glGetError(); err != GL_NO_ERROR) {
    char message[48];
    std::snprintf(message, sizeof message, "OpenGL error 0x%04x during the frame", err);
    return message;
  }
  return {};
}

std::vector<std::uint8_t> Renderer::read_rgba() const {
  const int W = 2 * w_;
  std::vector<std::uint8_t> bottom_up(static_cast<std::size_t>(W) * h_ * 4), out(bottom_up.size());
  glPixelStorei(GL_PACK_ALIGNMENT, 1);
  glGetTextureImage(gl_->output, 0, GL_RGBA, GL_UNSIGNED_BYTE, static_cast<GLsizei>(bottom_up.size()), bottom_up.data());
  const std::size_t row = static_cast<std::size_t>(W) * 4;
  for (int y = 0; y < h_; ++y)
    std::copy_n(bottom_up.data() + static_cast<std::size_t>(h_ - 1 - y) * row, row, out.data() + static_cast<std::size_t>(y) * row);
  return out;
}
