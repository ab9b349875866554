#pragma once
// The directional albedo of KHR_materials_sheen's lobe, for the albedo scaling the
// specification asks of the layer below: E(μ, r) = ∫ D_Charlie(h; α = r²) · V_Neubelt · (n·l) dω_l
// over the hemisphere, μ = n·v (shaders/common/lighting.glsl evaluates the same lobe).
#include <vector>

namespace foveal::render::detail {

/// E at size×size grid points, row-major, row = roughness r = (j + 0.5) / size, column =
/// μ = (i + 0.5) / size (texel centres, for a linearly filtered texture). Values in [0, 1].
std::vector<float> sheen_albedo_table(int size);

/// E at one (μ, r) by the same quadrature (for tests).
double sheen_albedo(double mu, double roughness);

}  // namespace foveal::render::detail
