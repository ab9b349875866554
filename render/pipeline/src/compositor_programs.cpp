// The compositor's programs: the shader variant for the scene's material features and
// lights (use_features), the programs of the kernels not built up front on first use
// (ensure_variant).
#include <string>
#include <vector>

#include "compositor_impl.hpp"
#include "sheen_albedo.hpp"

namespace foveal::render {

Status Compositor::Impl::build(gl::Program& out, const std::vector<gl::ShaderStage>& stages, const std::string& defines,
                               const std::vector<gl::VirtualFile>& files) const {
  auto p = shaders.program(stages, defines, files);
  if (!p) return p.error();
  out = std::move(*p);
  return {};
}

// The shader variant and G-buffer layout for material features `features`, and the
// lighting and blend programs for the scene's lights: the file's (FILE_LIGHTS) or the
// rig's. Code a scene does not use is not compiled in: on llvmpipe even a light loop
// that never runs cost the rig-lit Dungeon 6% of its lighting pass.
Status Compositor::Impl::use_features(unsigned features, bool file_lights) {
  const bool same_features = features == requested_features && gbuffer_prog;
  if (same_features && file_lights == requested_file_lights && lighting_progs[0]) return {};
  const detail::SurfaceLayout next = same_features ? layout : detail::SurfaceLayout::for_features(features);
  if (!same_features && features) {
    GLint units = 0, buffers = 0;
    glGetIntegerv(GL_MAX_TEXTURE_IMAGE_UNITS, &units);
    glGetIntegerv(GL_MAX_DRAW_BUFFERS, &buffers);
    const GLint need_units = static_cast<GLint>(detail::material_texture_unit(Material::slot_count - 1)) + 1;
    const GLint need_buffers = static_cast<GLint>(detail::SurfaceLayout::kFirstLocation + next.targets.size());
    if (units < need_units || buffers < need_buffers)
      return Error{ErrorKind::unsupported, "the material variant " + next.variant_name() + " needs " + std::to_string(need_units) +
                                               " fragment texture units and " + std::to_string(need_buffers) +
                                               " draw buffers; this GL has " + std::to_string(units) + " and " + std::to_string(buffers)};
  }
  // A features change that fails part way leaves no G-buffer program, so the next frame
  // builds every program again rather than keep lighting built for a layout not in use.
  if (!same_features) gbuffer_prog.reset();
  const std::string d = next.defines();
  const std::string lit = d + (file_lights ? "#define FILE_LIGHTS 1\n" : "");
  if (Status s = build(blend_prog, {{GL_VERTEX_SHADER, "gbuffer.vert"}, {GL_FRAGMENT_SHADER, "blend.frag"}}, lit); !s) return s;
  const gl::ShaderStage vert{GL_VERTEX_SHADER, "fullscreen.vert"};
  for (std::size_t v = 0; v < lighting_progs.size(); ++v) {
    lighting_progs[v].reset();  // the kernels not built up front: rebuilt on use
    if (mapping_kernel(v).built_up_front)
      if (Status s = build(lighting_progs[v], {vert, {GL_FRAGMENT_SHADER, "lighting.frag"}}, lit, mapping_files(v)); !s) return s;
  }
  lit_defines = lit;
  requested_file_lights = file_lights;
  if (same_features) return {};  // the rest depends on the features only
  if (Status s = build(gbuffer_prog, {{GL_VERTEX_SHADER, "gbuffer.vert"}, {GL_FRAGMENT_SHADER, "gbuffer.frag"}}, d); !s) return s;
  for (std::size_t v = 0; v < map_progs.size(); ++v) {  // RMFR maps through foveal-rmfr, which maps every attachment
    map_progs[v].reset();
    if (mapping_kernel(v).built_up_front && !mapping_kernel(v).rmfr_passes)
      if (Status s = build(map_progs[v], {vert, {GL_FRAGMENT_SHADER, "map.frag"}}, d, mapping_files(v)); !s) return s;
  }
  if (Status s = visibility->use_layout(shaders, next); !s) return s;
  if ((features & feature_sheen) && !sheen_albedo) {
    constexpr int kSize = 32;
    const std::vector<float> table = detail::sheen_albedo_table(kSize);
    sheen_albedo = gl::make_texture_2d(GL_R32F, kSize, kSize);
    glTextureSubImage2D(sheen_albedo.id(), 0, 0, 0, kSize, kSize, GL_RED, GL_FLOAT, table.data());
    glTextureParameteri(sheen_albedo.id(), GL_TEXTURE_MIN_FILTER, GL_LINEAR);
    glTextureParameteri(sheen_albedo.id(), GL_TEXTURE_MAG_FILTER, GL_LINEAR);
    glTextureParameteri(sheen_albedo.id(), GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
    glTextureParameteri(sheen_albedo.id(), GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
  }
  layout = next;
  requested_features = features;
  gbuffer.reset();
  for (auto& t : transformed) t.reset();
  return {};
}

// The programs of a kernel not built up front (MethodKernel::built_up_front), built on
// first use and again after a features change: compiling every kernel up front would
// cost each compositor the programs of methods it never runs.
Status Compositor::Impl::ensure_variant(std::size_t v) {
  const MethodKernel& kernel = mapping_kernel(v);
  if (kernel.built_up_front) return {};
  const std::vector<gl::VirtualFile> files = mapping_files(v);
  const gl::ShaderStage vert{GL_VERTEX_SHADER, "fullscreen.vert"};
  if (!lighting_progs[v])
    if (Status s = build(lighting_progs[v], {vert, {GL_FRAGMENT_SHADER, "lighting.frag"}}, lit_defines, files); !s)
      return s;
  if (!map_progs[v] && !kernel.rmfr_passes)  // foveal-rmfr maps and resolves RMFR's
    if (Status s = build(map_progs[v], {vert, {GL_FRAGMENT_SHADER, "map.frag"}}, layout.defines(), files); !s)
      return s;
  for (std::size_t lens = 0; lens < 2; ++lens)
    if (!resolve_progs[v][lens] && !kernel.rmfr_passes)
      if (Status s = build(resolve_progs[v][lens], {vert, {GL_FRAGMENT_SHADER, "resolve.frag"}},
                           lens ? "#define DISTORTION 1\n" : "", files);
          !s)
        return s;
  return visibility->ensure_mapping(shaders, v);
}

}  // namespace foveal::render
