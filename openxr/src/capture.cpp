#include "capture.hpp"

#include <unistd.h>

#include <cstdio>
#include <cstring>
#include <vector>

#define STB_IMAGE_WRITE_STATIC
#define STB_IMAGE_WRITE_IMPLEMENTATION
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wconversion"
#pragma GCC diagnostic ignored "-Wmissing-field-initializers"
#pragma GCC diagnostic ignored "-Wunused-function"
#pragma GCC diagnostic ignored "-Wpedantic"
#pragma GCC diagnostic ignored "-Wshadow"
#pragma GCC diagnostic ignored "-Wsign-compare"
#pragma GCC diagnostic ignored "-Wunused-parameter"
#include <stb/stb_image_write.h>
#pragma GCC diagnostic pop

#include "layer_log.hpp"
#include "quad_session.hpp"

namespace foveal::openxr {

void capture_stereo(Composer& composer, const std::uint64_t images[2], const OutputSwapchain out[2],
                    const std::string& dir) {
  std::vector<std::uint8_t> eye[2];
  for (int e = 0; e < 2; ++e) {
    const ComposeTarget target{images[e], out[e].format, out[e].serial, static_cast<int>(out[e].width),
                               static_cast<int>(out[e].height)};
    if (!composer.read(target, eye[e])) {
      log_line("capture: the composed image could not be read back");
      return;
    }
  }
  const int w0 = static_cast<int>(out[0].width), w1 = static_cast<int>(out[1].width);
  const int h = static_cast<int>(std::max(out[0].height, out[1].height));
  const int w = w0 + w1;
  std::vector<std::uint8_t> sbs(static_cast<std::size_t>(w) * static_cast<std::size_t>(h) * 4, 0);
  for (int e = 0; e < 2; ++e) {
    const int we = e == 0 ? w0 : w1, x0 = e == 0 ? 0 : w0;
    for (int y = 0; y < static_cast<int>(out[e].height); ++y)
      std::memcpy(sbs.data() + (static_cast<std::size_t>(y) * static_cast<std::size_t>(w) + static_cast<std::size_t>(x0)) * 4,
                  eye[e].data() + static_cast<std::size_t>(y) * static_cast<std::size_t>(we) * 4,
                  static_cast<std::size_t>(we) * 4);
  }
  const std::string final_path = dir + "/composed.png";
  const std::string tmp = final_path + ".tmp." + std::to_string(::getpid());
  if (!stbi_write_png(tmp.c_str(), w, h, 4, sbs.data(), w * 4) || std::rename(tmp.c_str(), final_path.c_str()) != 0) {
    std::remove(tmp.c_str());
    log_line("capture: could not write composed.png in FOVEAL_OPENXR_CAPTURE_DIR");
    return;
  }
  log_line("capture: the composed frame is in FOVEAL_OPENXR_CAPTURE_DIR/composed.png");
}

}  // namespace foveal::openxr
