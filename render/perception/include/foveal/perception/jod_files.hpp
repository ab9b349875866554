#pragma once
// JOD of image files and frame sequences as `foveal metrics --jod` reads them: a still, a
// folder of frames (sorted by name) or a .txt list of frame paths; side-by-side stereo
// frames scored per eye (docs/metrics.md, "JOD").
#include <array>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "foveal/core/display_model.hpp"
#include "foveal/core/error.hpp"
#include "foveal/perception/jod.hpp"

namespace foveal::perception {

/// A fovea in normalised coordinates of an eye's image ([0,1]², origin top-left).
struct NormFovea {
  double x = 0.5, y = 0.5;
};

struct JodRequest {
  std::string reference, test;  ///< image, folder of frames, or .txt list of frame paths
  DisplayModel display = DisplayModel::vive_pro_eye();
  Photometry photometry;
  Parameters parameters;
  bool stereo = false;          ///< side by side, left eye on the left
  double fps = 0;               ///< needed for more than one frame
  /// Per eye (left, right); none: not foveated.
  std::optional<NormFovea> fovea_left, fovea_right;
  /// One line per frame, "X,Y" (both eyes) or "XL,YL,XR,YR"; overrides the foveae.
  std::string fovea_list;
  int threads = 2;  ///< per eye, in turn
};

struct JodReport {
  std::vector<JodScore> eyes;  ///< one, or left and right
  JodScore combined;           ///< stereo: the JOD of both eyes' mean difference
  int width = 0, height = 0;   ///< of one eye's image
};

/// The frames `path` names: itself if an image file, a folder's image files sorted by
/// name, or the non-empty lines of a .txt file (relative to its folder). The list is read
/// through the project's file entry point: a regular file of at most kMaxListBytes.
Result<std::vector<std::string>> frame_paths(const std::string& path, const char* what);

/// The largest frame list or fovea list read (each line one frame: a million frames fit).
inline constexpr std::size_t kMaxListBytes = std::size_t{64} << 20;

/// What run_jod will score and about how much memory that takes, from the frame lists and
/// the first frames' headers alone (nothing decoded): callers refuse work past a bound
/// before it starts.
struct JodPlan {
  std::vector<std::string> refs, tests;
  int width = 0, height = 0;  ///< of one eye's image
  int eyes = 1;
  std::uint64_t bytes = 0;    ///< jod_working_set_bytes of this request
};
Result<JodPlan> plan_jod(const JodRequest& request);

/// The peak memory run_jod needs, about (within ~10 %, docs/metrics.md "Memory"): the
/// metric's per-eye planes, a video's ring of ceil(fps/4) frames (at most its frame
/// count) of both videos per eye,
/// one frame's pyramids, and the decoded frames (file_bytes: the largest frame file).
/// frames > 1 is a video at `fps`.
std::uint64_t jod_working_set_bytes(int eye_width, int eye_height, int eyes, std::size_t frames, double fps,
                                    std::uint64_t file_bytes);

Result<JodReport> run_jod(const JodRequest& request);

}  // namespace foveal::perception
