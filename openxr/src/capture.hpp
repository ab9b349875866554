#pragma once
// A composed frame saved for inspection and tests: FOVEAL_OPENXR_CAPTURE_DIR=DIR saves
// composed frame FOVEAL_OPENXR_CAPTURE_FRAME (default 0) as DIR/composed.png, both eyes
// side by side, written to a temporary name and renamed. Once per session; it reads the
// images back, so it is for debugging, not for a running app.
#include <cstdint>
#include <string>

#include "composer.hpp"

namespace foveal::openxr {

struct OutputSwapchain;
void capture_stereo(Composer& composer, const std::uint64_t images[2], const OutputSwapchain out[2],
                    const std::string& dir);

}  // namespace foveal::openxr
