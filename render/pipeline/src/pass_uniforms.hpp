#pragma once
// Uniform setters shared by the compositor's passes (compositor_*.cpp) and the visibility
// pipeline (visibility_pipeline.cpp).
#include <cstddef>

#include <glm/gtc/type_ptr.hpp>
#include <glm/mat3x3.hpp>
#include <glm/mat4x4.hpp>

#include "foveal/core/error.hpp"
#include "foveal/image/foveation_plan.hpp"
#include "foveal/image/method_description.hpp"
#include "foveal/render/gl.hpp"
#include "foveal/render/shader_loader.hpp"
#include "foveal/render/scene_types.hpp"

namespace foveal::render {

struct Scene;

namespace detail {

inline GLint loc(GLuint program, const char* name) { return glGetUniformLocation(program, name); }
inline void set(GLuint p, const char* n, int v) { glProgramUniform1i(p, loc(p, n), v); }
inline void set(GLuint p, const char* n, unsigned v) { glProgramUniform1ui(p, loc(p, n), v); }
inline void set(GLuint p, const char* n, float v) { glProgramUniform1f(p, loc(p, n), v); }
inline void set(GLuint p, const char* n, glm::vec2 v) { glProgramUniform2f(p, loc(p, n), v.x, v.y); }
inline void set(GLuint p, const char* n, glm::ivec2 v) { glProgramUniform2i(p, loc(p, n), v.x, v.y); }
inline void set(GLuint p, const char* n, glm::vec3 v) { glProgramUniform3f(p, loc(p, n), v.x, v.y, v.z); }
inline void set(GLuint p, const char* n, glm::vec4 v) { glProgramUniform4f(p, loc(p, n), v.x, v.y, v.z, v.w); }
inline void set(GLuint p, const char* n, glm::ivec4 v) { glProgramUniform4i(p, loc(p, n), v.x, v.y, v.z, v.w); }
inline void set(GLuint p, const char* n, const glm::mat3& m) { glProgramUniformMatrix3fv(p, loc(p, n), 1, GL_FALSE, glm::value_ptr(m)); }
inline void set(GLuint p, const char* n, const glm::mat4& m) { glProgramUniformMatrix4fv(p, loc(p, n), 1, GL_FALSE, glm::value_ptr(m)); }

/// The material's uniforms of shaders/common/material.glsl, and its textures on their
/// units (material_texture_unit). Uniforms of features the program lacks are skipped (GL
/// ignores location -1).
void set_material(GLuint program, const Scene& scene, const Material& m);

/// The texture unit of a Material::Slot: 0-4 for the core slots, 16 on for the
/// extensions' (shaders/common/material.glsl).
inline GLuint material_texture_unit(int slot) {
  return slot < Material::kCoreSlots ? static_cast<GLuint>(slot) : 16u + static_cast<GLuint>(slot - Material::kCoreSlots);
}

/// The material of a primitive (the default one for -1).
const Material& material_of(const Scene& scene, int material);

/// The depth a material's texels carry from a classification to its EQUAL-tested pass
/// (material_depth in shaders/common/visibility_geometry.glsl): exact in float for up to
/// 2^20 materials.
inline float material_depth(std::size_t material) { return static_cast<float>(material + 1) / 1048576.0f; }

/// Face culling for a draw of material `m` with transform `world`, as glTF says: none
/// when double-sided, else back faces, the winding flipped by a mirroring transform.
void set_culling(const Material& m, const glm::mat4& world);

/// Whether any draw's material is drawn forward (Material::forward: alphaMode BLEND or
/// transmission), by the blend pass only.
bool has_forward_draws(const Scene& scene);

}  // namespace detail

/// The variant of the mapping-dependent programs: one per method kernel, in the order
/// of method_kernels() (foveal/image/method_description.hpp). A method
/// without one is an error, never another method's kernel.
Result<std::size_t> mapping_index(const EyePlan& plan);
std::size_t mapping_variant_count();
/// Variant v's kernel: whether foveal-rmfr runs its mapping and resolve (rmfr_passes),
/// whether its programs are built up front or on first use (built_up_front).
const MethodKernel& mapping_kernel(std::size_t v);
/// What a program of variant v is built with: its kernel's GLSL as the virtual file
/// "method/kernel" (shaders/common/mapping.glsl).
std::vector<gl::VirtualFile> mapping_files(std::size_t v);

/// The mapping uniforms of shaders/common/mapping.glsl for one eye's plan.
void set_mapping(GLuint p, const EyePlan& plan, glm::vec2 texture_size);

}  // namespace foveal::render
