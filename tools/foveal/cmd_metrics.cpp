// foveal metrics: PSNR, SSIM and FPSNR of a test image against a reference, on a single
// image or a side-by-side stereo frame; with --jod, FovVideoVDP's JOD of images and frame
// sequences (docs/metrics.md). Which of the two a frame is, and the one ppd of the call:
// metrics_frame.hpp.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <memory>
#include <utility>

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include "commands.hpp"
#include "foveal/image/metrics.hpp"
#include "foveal/perception/jod_files.hpp"
#include "foveal/runtime/args.hpp"
#include "foveal/runtime/cli.hpp"
#include "memory_bound.hpp"
#include "metrics_frame.hpp"

namespace foveal::cmd {

namespace {

struct Args {
  std::string ref, test, fovea, fovea_right, ssim_channels = "luma";
  double ppd = image::kDefaultPixelsPerDegree;
  bool ppd_given = false;
  bool stereo = false, mono = false, json = false;
  // --jod (docs/metrics.md, "JOD")
  bool jod = false;
  std::string display, fovea_list, jod_release = "1.2";
  double fps = 0, peak = 133.3, black = 0.1;
  bool fps_given = false;
};

// The documented ranges (docs/metrics.md): pixels per degree of any display or image a
// person looks at, and the frame rates a video ring is sized for (ceil(fps/4) frames).
constexpr double kMinPpd = 0.1, kMaxPpd = 1000, kMaxFps = 1000;

Status check_range(double v, double lo, double hi, bool lo_open, const char* option, const char* unit) {
  if (std::isfinite(v) && (lo_open ? v > lo : v >= lo) && v <= hi) return {};
  char buf[160];
  std::snprintf(buf, sizeof buf, "%s: must lie in %s%g, %g] %s, got %g", option, lo_open ? "(" : "[", lo, hi, unit, v);
  return bad_input(buf);
}

// "two 1024x1024 images", "two videos of 20 2880x1600 stereo frames at 90 fps".
std::string work_text(const perception::JodPlan& p, double fps) {
  const std::string size = std::to_string(p.width * p.eyes) + "x" + std::to_string(p.height) + (p.eyes > 1 ? " stereo" : "");
  if (p.refs.size() == 1) return "JOD of two " + size + " images";
  char rate[32];
  std::snprintf(rate, sizeof rate, "%g", fps);
  const auto ring = std::min(static_cast<std::size_t>(std::ceil(fps / 4)), p.refs.size());
  return "JOD of two videos of " + std::to_string(p.refs.size()) + " " + size + " frames at " + rate + " fps (each eye keeps " +
         std::to_string(ring) + " frames of both)";
}

// A figure reported as a success must be a number: NaN never is, and infinity only where
// the images are identical (PSNR/FPSNR of a zero error).
Status check_finite(const image::Metrics& m, const char* label) {
  const bool ok = std::isfinite(m.mse) && std::isfinite(m.fmse) && std::isfinite(m.ssim) &&
                  (std::isfinite(m.psnr_db) || (m.mse == 0 && m.psnr_db > 0)) &&
                  (std::isfinite(m.fpsnr_db) || (m.fmse == 0 && m.fpsnr_db > 0));
  if (ok) return {};
  char buf[200];
  std::snprintf(buf, sizeof buf, "metrics: the %s figures are not finite (PSNR %g, SSIM %g, FPSNR %g): an internal error, not a result",
                label, m.psnr_db, m.ssim, m.fpsnr_db);
  return Error{ErrorKind::internal, buf};
}

// JSON has no infinity: identical images print "inf".
nlohmann::json db(double v) { return std::isfinite(v) ? nlohmann::json(v) : nlohmann::json("inf"); }

nlohmann::json to_json(const image::Metrics& m) {
  return {{"psnr_db", db(m.psnr_db)}, {"ssim", m.ssim}, {"fpsnr_db", db(m.fpsnr_db)}, {"mse", m.mse}, {"fmse", m.fmse}};
}

void print_line(const char* label, const image::Metrics& m) {
  std::printf("%-9s PSNR %7.3f dB   SSIM %.5f   FPSNR %7.3f dB\n", label, m.psnr_db, m.ssim, m.fpsnr_db);
}

Result<image::NormPoint> parse_fovea(const std::string& s, const char* what) {
  auto p = cli::parse_point(s, what);
  if (!p) return p.error();
  if (p->first < 0 || p->first > 1 || p->second < 0 || p->second > 1)
    return bad_input(std::string(what) + ": X and Y must lie in [0,1], got '" + s + "'");
  return image::NormPoint{p->first, p->second};
}

Result<image::Image> load_named(const std::string& path, const char* what) {
  auto img = image::load(path);
  if (!img) return Error{img.error().kind, std::string(what) + " " + img.error().message};
  return img;
}

FrameChoice frame_choice(const Args& a) {
  FrameChoice c;
  c.display = a.display;
  c.stereo = a.stereo;
  c.mono = a.mono;
  if (a.ppd_given) c.ppd = a.ppd;
  return c;
}

Error fovea_right_refused(const MetricsFrame& f) {
  return bad_input("--fovea-right: only for a stereo frame, and this " + std::to_string(f.width) + "x" + std::to_string(f.height) +
                   " frame is " + f.summary());
}

nlohmann::json jod_json(const perception::JodScore& s) { return {{"jod", s.jod}, {"q", s.q}}; }

// JOD per eye and combined; the fovea "none" scores without foveation.
int run_jod(const Args& a) {
  perception::JodRequest rq;
  rq.reference = a.ref;
  rq.test = a.test;
  rq.fps = a.fps;
  rq.fovea_list = a.fovea_list;
  if (Status s = check_range(a.peak, perception::kMinLuminanceCdM2, perception::kMaxLuminanceCdM2, true, "--peak", "cd/m²"); !s)
    return cli::report(s.error());
  if (Status s = check_range(a.black, perception::kMinLuminanceCdM2, perception::kMaxLuminanceCdM2, false, "--black", "cd/m²"); !s)
    return cli::report(s.error());
  if (a.fps_given)
    if (Status s = check_range(a.fps, 0, kMaxFps, true, "--fps", "frames per second"); !s) return cli::report(s.error());
  rq.photometry = {a.peak, a.black};
  if (Status s = rq.photometry.validate(); !s) return cli::report(bad_input("--peak/--black: " + s.error().message));
  if (a.jod_release == "1.0") rq.parameters = perception::Parameters::release_1_0();
  // Stereo or not, and the ppd, from the first frame's size (headers only).
  auto sized = perception::plan_jod(rq);
  if (!sized) return cli::report(sized.error());
  auto frame = metrics_frame(frame_choice(a), sized->width, sized->height);
  if (!frame) return cli::report(frame.error());
  rq.stereo = frame->stereo;
  rq.display = frame->model;
  const auto fovea = [](const std::string& s, const char* what) -> Result<std::optional<perception::NormFovea>> {
    if (s.empty() || s == "none") return std::optional<perception::NormFovea>{};
    auto p = parse_fovea(s, what);
    if (!p) return p.error();
    return std::optional<perception::NormFovea>{perception::NormFovea{p->x, p->y}};
  };
  auto l = fovea(a.fovea, "--fovea");
  if (!l) return cli::report(l.error());
  rq.fovea_left = rq.fovea_right = *l;
  if (!a.fovea_right.empty()) {
    if (!frame->stereo) return cli::report(fovea_right_refused(*frame));
    auto r = fovea(a.fovea_right, "--fovea-right");
    if (!r) return cli::report(r.error());
    rq.fovea_right = *r;
  }
  // Sized from the frame lists and headers before a pixel is decoded.
  auto plan = perception::plan_jod(rq);
  if (!plan) return cli::report(plan.error());
  if (Status s = check_memory(plan->bytes, work_text(*plan, a.fps)); !s) return cli::report(bad_input("metrics --jod: " + s.error().message));
  auto rep = perception::run_jod(rq);
  if (!rep) return cli::report(rep.error());
  const auto& c = rep->combined;
  for (const perception::JodScore* sc : {&rep->combined, &rep->eyes.front(), &rep->eyes.back()})
    if (!std::isfinite(sc->jod) || !std::isfinite(sc->q))
      return cli::report(Error{ErrorKind::internal, "metrics --jod: the metric gave JOD " + std::to_string(sc->jod) + " (Q " +
                                                        std::to_string(sc->q) + "), not a number: an internal error, not a result"});
  if (a.json) {
    nlohmann::json j = {{"ref", a.ref}, {"test", a.test}, {"size", {rep->width, rep->height}}, {"stereo", frame->stereo},
                        {"stereo_from", frame->stereo_from}, {"display", frame->display_name}, {"release", a.jod_release},
                        {"ppd", c.ppd}, {"ppd_from", frame->ppd_from}, {"peak_cd_m2", a.peak}, {"black_cd_m2", a.black},
                        {"frames", c.frames}, {"fps", a.fps}, {"bands", c.bands},
                        {"foveated", a.fovea_list.empty() ? nlohmann::json(rq.fovea_left.has_value()) : nlohmann::json("per frame")},
                        {"jod", c.jod}, {"q", c.q}};
    if (frame->stereo) {
      j["left"] = jod_json(rep->eyes[0]);
      j["right"] = jod_json(rep->eyes[1]);
      if (a.fovea_list.empty()) {
        j["left"]["foveated"] = rq.fovea_left.has_value();
        j["right"]["foveated"] = rq.fovea_right.has_value();
      }
    }
    cli::print_json(j);
  } else {
    std::printf("%s vs %s (%dx%d, %s, %d frame%s)\n", a.test.c_str(), a.ref.c_str(), frame->width, frame->height,
                frame->summary().c_str(), c.frames, c.frames == 1 ? "" : "s");
    if (frame->stereo) std::printf("left     JOD %.4f\nright    JOD %.4f\n", rep->eyes[0].jod, rep->eyes[1].jod);
    std::printf("%-8s JOD %.4f\n", frame->stereo ? "combined" : "image", c.jod);
  }
  return cli::kExitOk;
}

int run(const Args& a) {
  if (a.ppd_given)
    if (Status s = check_range(a.ppd, kMinPpd, kMaxPpd, false, "--ppd", "pixels per degree"); !s) return cli::report(s.error());
  if (a.jod) return run_jod(a);
  if (a.fovea.empty()) return cli::report(bad_input("--fovea: required (except with --jod)"));
  image::MetricsOptions opt;
  auto fovea = parse_fovea(a.fovea, "--fovea");
  if (!fovea) return cli::report(fovea.error());
  opt.fovea = opt.fovea_right = *fovea;  // the same spot in each eye unless told
  auto hr = image::probe(a.ref);
  if (!hr) return cli::report(bad_input("--ref " + hr.error().message));
  {  // Both images decoded (4 B a pixel each) and one decode's transients (docs/metrics.md, "Memory").
    auto ht = image::probe(a.test);
    if (!ht) return cli::report(bad_input("--test " + ht.error().message));
    const std::uint64_t px = static_cast<std::uint64_t>(std::max(hr->width, ht->width)) * static_cast<std::uint64_t>(std::max(hr->height, ht->height));
    const std::uint64_t need = 12 * px + 2 * std::max(hr->file_bytes, ht->file_bytes);
    if (Status s = check_memory(need, "two " + std::to_string(hr->width) + "x" + std::to_string(hr->height) + " images"); !s)
      return cli::report(bad_input("metrics: " + s.error().message));
  }
  auto frame = metrics_frame(frame_choice(a), hr->width, hr->height);
  if (!frame) return cli::report(frame.error());
  if (!a.fovea_right.empty()) {
    if (!frame->stereo) return cli::report(fovea_right_refused(*frame));
    auto r = parse_fovea(a.fovea_right, "--fovea-right");
    if (!r) return cli::report(r.error());
    opt.fovea_right = *r;
  }
  opt.ppd = frame->ppd;
  opt.ssim_channels = a.ssim_channels == "rgb" ? image::SsimChannels::rgb : image::SsimChannels::luma;
  auto ref = load_named(a.ref, "--ref");
  if (!ref) return cli::report(ref.error());
  auto test = load_named(a.test, "--test");
  if (!test) return cli::report(test.error());
  if (ref->width != test->width || ref->height != test->height)
    return cli::report(bad_input(a.test + ": size " + std::to_string(test->width) + "x" + std::to_string(test->height) +
                                 " differs from the reference " + a.ref + " (" + std::to_string(ref->width) + "x" +
                                 std::to_string(ref->height) + ")"));

  nlohmann::json j = {{"ref", a.ref}, {"test", a.test}, {"size", {ref->width, ref->height}}, {"stereo", frame->stereo},
                      {"stereo_from", frame->stereo_from}, {"display", frame->display_name}, {"ppd", opt.ppd},
                      {"ppd_from", frame->ppd_from}, {"ssim_channels", a.ssim_channels}};
  if (frame->stereo) {
    auto m = image::compute_stereo_metrics(*ref, *test, opt);
    if (!m) return cli::report(m.error());
    for (const auto& [eye, label] : {std::pair{&m->left, "left"}, std::pair{&m->right, "right"}, std::pair{&m->combined, "combined"}})
      if (Status s = check_finite(*eye, label); !s) return cli::report(s.error());
    if (a.json) {
      j["fovea_left"] = {opt.fovea.x, opt.fovea.y};
      j["fovea_right"] = {opt.fovea_right.x, opt.fovea_right.y};
      j.update(to_json(m->combined));
      j["left"] = to_json(m->left);
      j["right"] = to_json(m->right);
      cli::print_json(j);
    } else {
      std::printf("%s vs %s (%dx%d, %s, fovea L %.3f,%.3f R %.3f,%.3f)\n", a.test.c_str(), a.ref.c_str(), ref->width,
                  ref->height, frame->summary().c_str(), opt.fovea.x, opt.fovea.y, opt.fovea_right.x, opt.fovea_right.y);
      print_line("left", m->left);
      print_line("right", m->right);
      print_line("combined", m->combined);
    }
  } else {
    auto m = image::compute_metrics(*ref, *test, opt);
    if (!m) return cli::report(m.error());
    if (Status s = check_finite(*m, "image"); !s) return cli::report(s.error());
    if (a.json) {
      j["fovea"] = {opt.fovea.x, opt.fovea.y};
      j.update(to_json(*m));
      cli::print_json(j);
    } else {
      std::printf("%s vs %s (%dx%d, %s, fovea %.3f,%.3f)\n", a.test.c_str(), a.ref.c_str(), ref->width, ref->height,
                  frame->summary().c_str(), opt.fovea.x, opt.fovea.y);
      print_line("image", *m);
    }
  }
  return cli::kExitOk;
}

}  // namespace

void add_metrics(CLI::App& app, int& exit_code) {
  auto args = std::make_shared<Args>();
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
    exit_code = run(*args);
  });
}

}  // namespace foveal::cmd
