#pragma once
// GL test helpers: one EGL context per test process, rendering a frame, golden images.
#include <string>

#include "foveal/image/image.hpp"
#include "foveal/render/compositor.hpp"
#include "foveal/render/egl_context.hpp"
#include "foveal/render/scene.hpp"

namespace foveal::test {

/// The process's GL context; fails the test (never skips) when there is none.
bool gl_ready();

/// The shader directory of this source tree.
gl::ShaderLoader source_shaders();

/// A compositor of `width`x`height` with the source tree's shaders; aborts the test on error.
render::Compositor make_compositor(int width, int height, bool float_output = false);

/// Loads a scene; aborts the test on error.
render::Scene scene(const std::string& spec);

/// Renders one frame and reads it back.
image::Image render_frame(render::Compositor& c, const render::Scene& s, const render::FrameParams& p);

/// Frame parameters: method, both eyes at `sigma`, f = 0.3, both foveae at (x, y).
render::FrameParams frame(render::Method m, double sigma, double x = 0.5, double y = 0.5);

/// Compares with tests/render/golden/NAME.png: PSNR >= min_psnr_db. On failure writes
/// NAME.actual.png and NAME.diff.png into the build's test-output/ and says where.
/// FOVEAL_UPDATE_GOLDEN=1 rewrites the golden instead.
void expect_matches_golden(const image::Image& img, const std::string& name, double min_psnr_db = 40.0);

/// The eye's pixel rectangle (in the side-by-side image) of a size×size patch centred on
/// the normalised fovea (x, y), clipped to the eye's viewport.
image::Rect fovea_patch(const render::Compositor& c, Eye e, double x, double y, int size = 64);

}  // namespace foveal::test
