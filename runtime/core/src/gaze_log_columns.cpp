#include "foveal/core/gaze_log.hpp"

namespace foveal {

const std::vector<std::string>& gaze_log_columns(int version) {
  static const std::vector<std::string> v1 = [] {
    std::vector<std::string> c{"t_ns"};
    for (const char* eye : {"left", "right"}) {
      const std::string e = eye;
      for (const char* f : {"_valid", "_dir_x", "_dir_y", "_dir_z", "_origin_x_mm", "_origin_y_mm",
                            "_origin_z_mm", "_pupil_mm", "_openness"})
        c.push_back(e + f);
    }
    for (const char* f : {"combined_valid", "combined_dir_x", "combined_dir_y", "combined_dir_z",
                          "combined_origin_x_mm", "combined_origin_y_mm", "combined_origin_z_mm"})
      c.push_back(f);
    return c;
  }();
  static const std::vector<std::string> v2 = [] {
    std::vector<std::string> c = v1;
    for (const char* f : {"head_valid", "head_x_m", "head_y_m", "head_z_m", "head_qw", "head_qx", "head_qy", "head_qz"})
      c.push_back(f);
    return c;
  }();
  return version >= kGazeLogV2 ? v2 : v1;
}

}  // namespace foveal
