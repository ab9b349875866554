#pragma once
// Small GL queries and the pass state shared by the library's GL files.
#include <string>

#include "foveal/core/error.hpp"
#include "foveal/render/gl.hpp"

namespace foveal::rmfr::detail {

/// How a texture's texels reach a shader: float (also normalised, sRGB, depth), int, uint.
enum class Kind { floating, signed_int, unsigned_int };

struct TextureInfo {
  int width = 0, height = 0;
  GLenum internal_format = 0;
  bool depth = false;
  Kind kind = Kind::floating;
};

/// Level 0 of a 2D texture. Errors: bad_input for a name that is no 2D texture or a
/// stencil-only format; `what` names the argument.
Result<TextureInfo> texture_info(GLuint texture, const std::string& what);

/// GL_MAX_DRAW_BUFFERS.
int max_draw_buffers();

/// The fixed-function state every pass of the library sets (rmfr.hpp, Foveator).
void set_pass_state();

}  // namespace foveal::rmfr::detail
