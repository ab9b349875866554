#include <algorithm>
#include <cmath>
#include <cstring>

#include <glm/matrix.hpp>

#include "scene_internal.hpp"

namespace foveal::render::detail {

Primitive upload_primitive(const std::vector<GltfVertex>& vertices, const std::vector<std::uint32_t>& indices, int material) {
  Primitive p;
  p.vertices = gl::Buffer::create();
  p.indices = gl::Buffer::create();
  glNamedBufferStorage(p.vertices.id(), static_cast<GLsizeiptr>(vertices.size() * sizeof(GltfVertex)), vertices.data(), 0);
  glNamedBufferStorage(p.indices.id(), static_cast<GLsizeiptr>(indices.size() * sizeof(std::uint32_t)), indices.data(), 0);
  p.vao = gl::VertexArray::create();
  const GLuint vao = p.vao.id();
  glVertexArrayVertexBuffer(vao, 0, p.vertices.id(), 0, sizeof(GltfVertex));
  glVertexArrayElementBuffer(vao, p.indices.id());
  auto attrib = [vao](GLuint loc, GLint n, std::size_t offset) {
    glEnableVertexArrayAttrib(vao, loc);
    glVertexArrayAttribFormat(vao, loc, n, GL_FLOAT, GL_FALSE, static_cast<GLuint>(offset));
    glVertexArrayAttribBinding(vao, loc, 0);
  };
  attrib(0, 3, offsetof(GltfVertex, position));
  attrib(1, 3, offsetof(GltfVertex, normal));
  attrib(2, 2, offsetof(GltfVertex, uv));
  attrib(3, 4, offsetof(GltfVertex, tangent));
  attrib(4, 2, offsetof(GltfVertex, uv1));
  attrib(5, 4, offsetof(GltfVertex, color));
  p.index_count = static_cast<int>(indices.size());
  p.material = material;
  return p;
}

void upload_geometry(Scene& scene, const std::vector<GltfVertex>& vertices, const std::vector<std::uint32_t>& indices) {
  auto storage = [](const auto& v) {
    gl::Buffer b = gl::Buffer::create();
    // A zero-sized store is an error: keep one element so the binding is valid.
    const std::size_t bytes = std::max<std::size_t>(v.size() * sizeof(v[0]), 16);
    std::vector<std::uint8_t> data(bytes, 0);
    if (!v.empty()) std::memcpy(data.data(), v.data(), v.size() * sizeof(v[0]));
    glNamedBufferStorage(b.id(), static_cast<GLsizeiptr>(bytes), data.data(), 0);
    return b;
  };
  std::vector<DrawRecord> records;
  records.reserve(scene.draws.size());
  for (const DrawItem& d : scene.draws) {
    const Primitive& p = scene.primitives[static_cast<std::size_t>(d.primitive)];
    DrawRecord r;
    r.model = d.world;
    const glm::mat3 n = glm::mat3(glm::transpose(glm::inverse(d.world)));  // as the G-buffer pass
    for (int c = 0; c < 3; ++c) r.normal_matrix[c] = glm::vec4(n[c], 0.0f);
    r.first_index = p.first_index;
    r.base_vertex = p.base_vertex;
    r.material = p.material >= 0 ? static_cast<std::uint32_t>(p.material) : static_cast<std::uint32_t>(scene.materials.size());
    records.push_back(r);
  }
  scene.geometry.vertices = storage(vertices);
  scene.geometry.indices = storage(indices);
  scene.geometry.draws = storage(records);
  auto texels = [](const gl::Buffer& b, GLenum format) {
    GLuint id = 0;
    glCreateTextures(GL_TEXTURE_BUFFER, 1, &id);
    glTextureBuffer(id, format, b.id());
    return gl::Texture(id);
  };
  static_assert(sizeof(GltfVertex) == 9 * 8 && sizeof(DrawRecord) == 8 * 16, "texel views of the geometry");
  scene.geometry.vertex_pairs = texels(scene.geometry.vertices, GL_RG32F);
  scene.geometry.triangles = texels(scene.geometry.indices, GL_RGB32UI);
  scene.geometry.draw_floats = texels(scene.geometry.draws, GL_RGBA32F);
  scene.geometry.draw_uints = texels(scene.geometry.draws, GL_RGBA32UI);
}

gl::Sampler isotropic_sampler(GLenum wrap_s, GLenum wrap_t) {
  gl::Sampler s = gl::Sampler::create();
  glSamplerParameteri(s.id(), GL_TEXTURE_MIN_FILTER, GL_LINEAR_MIPMAP_LINEAR);
  glSamplerParameteri(s.id(), GL_TEXTURE_MAG_FILTER, GL_LINEAR);
  glSamplerParameteri(s.id(), GL_TEXTURE_WRAP_S, static_cast<GLint>(wrap_s));
  glSamplerParameteri(s.id(), GL_TEXTURE_WRAP_T, static_cast<GLint>(wrap_t));
  return s;
}

gl::Texture upload_rgba8(const std::uint8_t* rgba, int width, int height, bool srgb, GLenum wrap_s, GLenum wrap_t,
                         std::size_t* bytes) {
  const int levels = 1 + static_cast<int>(std::floor(std::log2(std::max(width, height))));
  gl::Texture t = gl::make_texture_2d(srgb ? GL_SRGB8_ALPHA8 : GL_RGBA8, width, height, levels);
  glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
  glTextureSubImage2D(t.id(), 0, 0, 0, width, height, GL_RGBA, GL_UNSIGNED_BYTE, rgba);
  glGenerateTextureMipmap(t.id());
  glTextureParameteri(t.id(), GL_TEXTURE_MIN_FILTER, GL_LINEAR_MIPMAP_LINEAR);
  glTextureParameteri(t.id(), GL_TEXTURE_MAG_FILTER, GL_LINEAR);
  glTextureParameteri(t.id(), GL_TEXTURE_WRAP_S, static_cast<GLint>(wrap_s));
  glTextureParameteri(t.id(), GL_TEXTURE_WRAP_T, static_cast<GLint>(wrap_t));
  glTextureParameterf(t.id(), GL_TEXTURE_MAX_ANISOTROPY, 8.0f);  // core since 4.6, EXT in Mesa/NVIDIA
  if (bytes) *bytes += static_cast<std::size_t>(width) * static_cast<std::size_t>(height) * 4 * 4 / 3;
  return t;
}

}  // namespace foveal::render::detail
