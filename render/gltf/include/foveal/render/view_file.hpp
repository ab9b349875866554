#pragma once
// "<scene>.view.json": the head pose for a glTF scene (docs/scenes.md). GL-free.
#include <string>

#include "foveal/core/error.hpp"
#include "foveal/render/scene_types.hpp"

namespace foveal::render {

/// {"eye": [x,y,z], "target": [x,y,z], "up": [0,1,0], "units_per_meter": 1}; errors name
/// the file and the key. The pose's source is "view file PATH".
Result<ViewPose> read_view_file(const std::string& path);

}  // namespace foveal::render
