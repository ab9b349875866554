// Material binding: a glTF material's uniforms and textures on a program
// (shaders/common/material.glsl), for the G-buffer, blend and visibility pipeline's passes.
#include <array>

#include <glm/glm.hpp>
#include <glm/gtc/type_ptr.hpp>

#include "foveal/render/scene.hpp"
#include "pass_uniforms.hpp"

namespace foveal::render {

namespace detail {

const Material& material_of(const Scene& scene, int material) {
  static const Material kDefault{};
  return material >= 0 ? scene.materials[static_cast<std::size_t>(material)] : kDefault;
}

bool has_forward_draws(const Scene& scene) {
  for (const DrawItem& d : scene.draws)
    if (material_of(scene, scene.primitives[static_cast<std::size_t>(d.primitive)].material).forward()) return true;
  return false;
}

void set_culling(const Material& m, const glm::mat4& world) {
  if (m.double_sided) {
    glDisable(GL_CULL_FACE);
    return;
  }
  glEnable(GL_CULL_FACE);
  glCullFace(GL_BACK);
  glFrontFace(glm::determinant(glm::mat3(world)) < 0.0f ? GL_CW : GL_CCW);
}

void set_material(GLuint p, const Scene& scene, const Material& m) {
  set(p, "u_base_color", m.base_color);
  set(p, "u_emissive", m.emissive);
  set(p, "u_metallic", m.metallic);
  set(p, "u_roughness", m.roughness);
  set(p, "u_normal_scale", m.normal_scale);
  set(p, "u_occlusion_strength", m.occlusion_strength);
  set(p, "u_alpha_cutoff", m.alpha_cutoff);
  set(p, "u_unlit", m.unlit ? 1 : 0);
  set(p, "u_double_sided", m.double_sided ? 1 : 0);
  set(p, "u_has_tex", glm::ivec4(m.base_color_tex >= 0, m.metal_rough_tex >= 0, m.normal_tex >= 0, m.occlusion_tex >= 0));
  set(p, "u_has_emissive_tex", m.emissive_tex >= 0 ? 1 : 0);
  // Per-slot texture coordinates and KHR_texture_transform matrices, the spec-gloss factors.
  std::array<glm::mat3, Material::slot_count> matrices;
  std::array<GLint, Material::slot_count> sets;
  for (std::size_t i = 0; i < m.uv.size(); ++i) matrices[i] = m.uv[i].matrix, sets[i] = m.uv[i].set;
  glProgramUniformMatrix3fv(p, loc(p, "u_uv_matrix"), Material::slot_count, GL_FALSE, glm::value_ptr(matrices[0]));
  glProgramUniform1iv(p, loc(p, "u_uv_set"), Material::slot_count, sets.data());
  set(p, "u_spec_gloss", m.spec_gloss ? 1 : 0);
  set(p, "u_specular", m.specular);
  set(p, "u_glossiness", m.glossiness);
  // The extensions' (material.glsl, FEATURE_*).
  int ext = 0;
  for (std::size_t i = 0; i < m.ext_tex.size(); ++i)
    if (m.ext_tex[i] >= 0) ext |= 1 << i;
  set(p, "u_ext_tex", ext);
  set(p, "u_clearcoat", glm::vec3(m.features & feature_clearcoat ? m.clearcoat : 0.0f, m.clearcoat_roughness, m.clearcoat_normal_scale));
  set(p, "u_sheen", glm::vec4(m.features & feature_sheen ? m.sheen_color : glm::vec3(0.0f), m.sheen_roughness));
  set(p, "u_specular_layer", glm::vec4(m.specular_color, m.specular_factor));
  set(p, "u_ior", m.ior);
  set(p, "u_blend", m.blend ? 1 : 0);
  set(p, "u_transmission", glm::vec4(m.features & feature_transmission ? m.transmission : 0.0f, m.thickness, m.attenuation_distance, 0.0f));
  set(p, "u_attenuation_color", m.attenuation_color);
  set(p, "u_anisotropy", glm::vec2(m.features & feature_anisotropy ? m.anisotropy : 0.0f, m.anisotropy_rotation));
  set(p, "u_iridescence", glm::vec4(m.features & feature_iridescence ? m.iridescence : 0.0f, m.iridescence_ior,
                                    m.iridescence_thickness_min, m.iridescence_thickness_max));
  const bool any_ext = ext != 0;
  for (int slot = 0; slot < (any_ext ? Material::slot_count : Material::kCoreSlots); ++slot) {
    const int t = m.texture(static_cast<Material::Slot>(slot));
    glBindTextureUnit(material_texture_unit(slot), t >= 0 ? scene.textures[static_cast<std::size_t>(t)].id() : 0);
  }
}

}  // namespace detail

}  // namespace foveal::render
