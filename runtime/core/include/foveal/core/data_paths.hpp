#pragma once
// Where foveal finds what it ships: display models, the bundled gaze log, shaders.
#include <string>

namespace foveal {

/// Root holding data/ and shaders/: $FOVEAL_DATA_DIR if set, else <exe>/../share/foveal
/// (an installed binary), else the configured install prefix's share/foveal, else the
/// source tree this build came from. Thread-safe.
std::string data_root();
/// data_root() + "/" + relative.
std::string data_path(const std::string& relative);

}  // namespace foveal
