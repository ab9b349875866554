#pragma once
// One opener per output kind; open_output() picks among them.
#include "foveal/render/output.hpp"

namespace foveal::render {

Result<std::unique_ptr<Output>> open_headless_output();
Result<std::unique_ptr<Output>> open_window_output(const OutputOptions& options);
Result<std::unique_ptr<Output>> open_drm_output(const OutputOptions& options);

}  // namespace foveal::render
