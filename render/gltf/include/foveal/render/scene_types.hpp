#pragma once
// The GL-free parts of a scene: bounds, materials, draw items and the view pose, shared
// by the glTF loader (CPU only, gltf_loader.hpp) and the compositor's Scene.
#include <array>
#include <string>
#include <utility>
#include <vector>

#include <glm/geometric.hpp>
#include <glm/mat3x3.hpp>
#include <glm/mat4x4.hpp>
#include <glm/vec3.hpp>
#include <glm/vec4.hpp>

namespace foveal::render {

struct Bounds {
  glm::vec3 min{0.0f}, max{0.0f};
  glm::vec3 center() const { return (min + max) * 0.5f; }
  float radius() const { return 0.5f * glm::length(max - min); }  ///< half the diagonal
};

/// Which texture coordinates a material texture reads, and how they are transformed
/// (KHR_texture_transform: uv' = matrix * (uv, 1)).
struct TextureUv {
  glm::mat3 matrix{1.0f};
  int set = 0;  ///< 0: TEXCOORD_0, 1: TEXCOORD_1
};

/// The material extensions a material uses beyond metal-roughness: each one a shader
/// feature and, in the deferred pipelines, one G-buffer attachment (docs/scenes.md,
/// "Materials"). A scene's shaders and G-buffer carry only the features its materials use.
enum MaterialFeature : unsigned {
  feature_clearcoat = 1u << 0,  ///< KHR_materials_clearcoat
  feature_sheen = 1u << 1,      ///< KHR_materials_sheen
  feature_specular = 1u << 2,   ///< KHR_materials_specular and/or KHR_materials_ior
  /// KHR_materials_transmission (with KHR_materials_volume): drawn by the forward pass
  /// over the opaque result it transmits, so it needs no G-buffer target.
  feature_transmission = 1u << 3,
  feature_anisotropy = 1u << 4,  ///< KHR_materials_anisotropy
  feature_iridescence = 1u << 5,  ///< KHR_materials_iridescence
};

/// "clearcoat, sheen" for MaterialFeature bits (in bit order).
inline std::string material_feature_names(unsigned features) {
  static const char* const kNames[] = {"clearcoat", "sheen", "specular", "transmission", "anisotropy", "iridescence"};
  std::string out;
  for (unsigned i = 0; i < sizeof kNames / sizeof kNames[0]; ++i)
    if (features & (1u << i)) out += (out.empty() ? "" : ", ") + std::string(kNames[i]);
  return out;
}

/// glTF 2.0 metal-roughness material. Texture indices point into Scene::textures (-1: none).
/// A KHR_materials_pbrSpecularGlossiness material keeps its diffuse factor and texture in
/// base_color, its specular-glossiness texture in metal_rough_tex, and is converted to
/// metal-roughness per fragment (docs/scenes.md).
struct Material {
  enum Slot {
    base_color_slot, metal_rough_slot, normal_slot, occlusion_slot, emissive_slot,
    clearcoat_slot, clearcoat_roughness_slot, clearcoat_normal_slot,  // KHR_materials_clearcoat
    sheen_color_slot, sheen_roughness_slot,                           // KHR_materials_sheen
    specular_slot, specular_color_slot,                               // KHR_materials_specular
    transmission_slot, thickness_slot,                                // KHR_materials_transmission, _volume
    anisotropy_slot,                                                  // KHR_materials_anisotropy
    iridescence_slot, iridescence_thickness_slot,                     // KHR_materials_iridescence
    slot_count
  };
  static constexpr int kCoreSlots = 5;  ///< the metal-roughness slots, base colour to emissive
  glm::vec4 base_color{1.0f};
  float metallic = 1.0f, roughness = 1.0f;
  glm::vec3 emissive{0.0f};
  float normal_scale = 1.0f, occlusion_strength = 1.0f;
  float alpha_cutoff = -1.0f;  ///< >= 0 for alphaMode MASK
  /// alphaMode BLEND: left out of the opaque passes (and the shadow map) and composited
  /// over the lit opaque result in a sorted forward pass (docs/scenes.md, "Transparency").
  bool blend = false;
  bool unlit = false;          ///< KHR_materials_unlit
  bool double_sided = false;
  int base_color_tex = -1, metal_rough_tex = -1, normal_tex = -1, occlusion_tex = -1, emissive_tex = -1;
  std::array<TextureUv, slot_count> uv{};  ///< per texture, indexed by Slot
  bool spec_gloss = false;                 ///< KHR_materials_pbrSpecularGlossiness
  glm::vec3 specular{1.0f};                ///< its specularFactor
  float glossiness = 1.0f;                 ///< its glossinessFactor

  /// MaterialFeature bits of what follows; 0 for a plain metal-roughness material.
  unsigned features = 0;
  /// Extension textures (Scene::textures, -1: none), indexed by Slot - kCoreSlots.
  std::array<int, slot_count - kCoreSlots> ext_tex{-1, -1, -1, -1, -1, -1, -1, -1, -1, -1, -1, -1};
  float clearcoat = 0.0f, clearcoat_roughness = 0.0f, clearcoat_normal_scale = 1.0f;  ///< KHR_materials_clearcoat
  glm::vec3 sheen_color{0.0f};                                                          ///< KHR_materials_sheen
  float sheen_roughness = 0.0f;
  float specular_factor = 1.0f;                ///< KHR_materials_specular
  glm::vec3 specular_color{1.0f};
  float ior = 1.5f;                            ///< KHR_materials_ior
  float transmission = 0.0f;                   ///< KHR_materials_transmission
  float thickness = 0.0f;                      ///< KHR_materials_volume: mesh units, 0 thin-walled
  float attenuation_distance = 0.0f;           ///< world units; 0: no attenuation (the spec's +inf)
  glm::vec3 attenuation_color{1.0f};
  float anisotropy = 0.0f, anisotropy_rotation = 0.0f;  ///< KHR_materials_anisotropy: strength, radians
  float iridescence = 0.0f, iridescence_ior = 1.3f;       ///< KHR_materials_iridescence
  float iridescence_thickness_min = 100.0f, iridescence_thickness_max = 400.0f;  ///< nanometres

  /// Drawn by the forward pass after the opaque result, not by the opaque passes:
  /// alphaMode BLEND, or transmission (docs/scenes.md, "Transparency", "Materials").
  bool forward() const { return blend || (features & feature_transmission) != 0; }

  /// The texture of any slot (-1: none).
  int texture(Slot s) const {
    const int core[kCoreSlots] = {base_color_tex, metal_rough_tex, normal_tex, occlusion_tex, emissive_tex};
    return s < kCoreSlots ? core[s] : ext_tex[static_cast<std::size_t>(s - kCoreSlots)];
  }
};

/// A KHR_materials_variants variant: per primitive (the loader sink's index), the
/// material it takes when the variant is chosen.
struct MaterialVariant {
  std::string name;
  std::vector<std::pair<int, int>> primitive_material;  ///< (primitive, material index)
};

struct DrawItem {
  int primitive = 0;
  glm::mat4 world{1.0f};
};

/// A KHR_lights_punctual light placed by its node (docs/scenes.md, "Lights"): world
/// position and the direction the light points (the node's −Z), both without the node's
/// scale; range, intensity and cone angles as the file gives them.
struct PunctualLight {
  enum class Type { directional, point, spot } type = Type::point;
  glm::vec3 color{1.0f};   ///< linear RGB
  float intensity = 1.0f;  ///< candela (point, spot) or lux (directional)
  float range = 0.0f;      ///< 0: no cutoff
  float inner_cone = 0.0f, outer_cone = 0.7853982f;  ///< radians, spot only
  glm::vec3 position{0.0f};
  glm::vec3 direction{0.0f, 0.0f, -1.0f};  ///< unit, where the light shines
  int index = 0;                           ///< its index in the extension's `lights`
};

/// Where the viewer's head is: the midpoint between the eyes, looking along -z.
struct ViewPose {
  glm::mat4 head_to_world{1.0f};  ///< rotation and translation only
  float units_per_meter = 1.0f;   ///< scales the IPD into scene units
  std::string source;             ///< "view file", "glTF camera NAME" or "framing"
};

}  // namespace foveal::render
