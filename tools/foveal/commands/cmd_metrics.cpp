// foveal metrics: PSNR, SSIM and FPSNR of a test image against a reference, on a single
// image or a side-by-side stereo frame; with --jod, FovVideoVDP's JOD of images and frame
// sequences (docs/metrics.md). The options; the work is evaluation::run_metrics
// (tools/evaluation), which of the two a frame is and the one ppd of the call
// foveal/evaluation/metrics_frame.hpp.
#include <memory>

#include <CLI/CLI.hpp>

#include "commands.hpp"
#include "foveal/evaluation/metrics_run.hpp"
#include "foveal/runtime/cli.hpp"
#include "render/render_args.hpp"

namespace foveal::cmd {

void add_metrics(CLI::App& app, int& exit_code) {
  auto args = std::make_shared<evaluation::MetricsRequest>();
  args->render_size = RenderArgs{}.size;
  CLI::App* sub = app.add_subcommand("metrics", "PSNR, SSIM and foveated PSNR of a test image against a reference, or with --jod FovVideoVDP's JOD of images or videos");
  sub->add_option("--ref,-r", args->ref, "Reference image (PNG, JPEG, BMP, TGA)")->required();
  sub->add_option("--test,-t", args->test, "Test image, same size")->required();
  sub->add_option("--fovea,--fovea-left", args->fovea,
                  "Fovea X,Y in [0,1] of the image (of the left half of a stereo frame), origin top-left; "
                  "required except with --jod, where 'none' or leaving it out scores without foveation");
  sub->add_option("--fovea-right", args->fovea_right, "Stereo frames: the right half's fovea (default: --fovea)");
  CLI::Option* stereo = sub->add_flag("--stereo", args->stereo,
                                      "Side-by-side stereo frame: each half is an eye with its own fovea (default: detected, "
                                      "stereo exactly when the size is the display's two eyes side by side or foveal render's default)");
  sub->add_flag("--mono", args->mono, "One image, even at a stereo frame's size")->excludes(stereo);
  CLI::Option* ppd = sub->add_option("--ppd", args->ppd,
                                     "Pixels per degree at the (eye) image centre, [0.1, 1000], for every metric "
                                     "(default: the display's eye at the image's size: 13.15 on a 1440-px Vive eye)");
  sub->add_option("--ssim-channels", args->ssim_channels, "SSIM on BT.601 luma, or the mean over R, G, B")
      ->check(CLI::IsMember({"luma", "rgb"}))
      ->capture_default_str();
  sub->add_flag("--json", args->json, "Print the metrics as JSON (infinite PSNR as \"inf\")");
  sub->add_flag("--jod", args->jod,
                "FovVideoVDP's JOD instead (docs/metrics.md): --ref/--test may be folders or .txt lists of frames");
  sub->add_option("--display", args->display,
                  "Display-model file or name under data/display (default: htc_vive_pro_eye): stereo detection, and the ppd "
                  "of every metric");
  CLI::Option* fps = sub->add_option("--fps", args->fps, "--jod: frame rate of frame sequences, (0, 1000]");
  sub->add_option("--fovea-list", args->fovea_list, "--jod: a file with one fovea per frame (X,Y or XL,YL,XR,YR or none)");
  sub->add_option("--jod-release", args->jod_release,
                  "--jod: the calibration, FovVideoVDP release 1.2's or 1.0's (the paper's)")
      ->check(CLI::IsMember({"1.2", "1.0"}))
      ->capture_default_str();
  sub->add_option("--peak", args->peak, "--jod: the display's peak luminance, cd/m² (black < peak <= 10000)")->capture_default_str();
  sub->add_option("--black", args->black, "--jod: the display's black level, cd/m² (0.001 <= black < peak)")->capture_default_str();
  sub->callback([args, fps, ppd, &exit_code] {
    args->fps_given = fps->count() > 0;
    args->ppd_given = ppd->count() > 0;
    if (Status s = evaluation::run_metrics(*args); !s) exit_code = cli::report(s.error());
  });
}

}  // namespace foveal::cmd
