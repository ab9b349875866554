#include "foveal/evaluation/metrics_run.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <utility>

#include <nlohmann/json.hpp>

#include "foveal/evaluation/memory_bound.hpp"
#include "foveal/evaluation/metrics_frame.hpp"
#include "foveal/perception/jod_files.hpp"
#include "foveal/runtime/args.hpp"
#include "foveal/runtime/cli.hpp"

namespace foveal::evaluation {

namespace {

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

FrameChoice frame_choice(const MetricsRequest& a) {
  FrameChoice c;
  c.display = a.display;
  c.stereo = a.stereo;
  c.mono = a.mono;
  if (a.ppd_given) c.ppd = a.ppd;
  c.render_size = a.render_size;
  return c;
}

Error fovea_right_refused(const MetricsFrame& f) {
  return bad_input("--fovea-right: only for a stereo frame, and this " + std::to_string(f.width) + "x" + std::to_string(f.height) +
                   " frame is " + f.summary());
}

nlohmann::json jod_json(const perception::JodScore& s) { return {{"jod", s.jod}, {"q", s.q}}; }

// JOD per eye and combined; the fovea "none" scores without foveation.
Status run_jod(const MetricsRequest& a) {
  perception::JodRequest rq;
  rq.reference = a.ref;
  rq.test = a.test;
  rq.fps = a.fps;
  rq.fovea_list = a.fovea_list;
  if (Status s = check_range(a.peak, perception::kMinLuminanceCdM2, perception::kMaxLuminanceCdM2, true, "--peak", "cd/m²"); !s)
    return s.error();
  if (Status s = check_range(a.black, perception::kMinLuminanceCdM2, perception::kMaxLuminanceCdM2, false, "--black", "cd/m²"); !s)
    return s.error();
  if (a.fps_given)
    if (Status s = check_range(a.fps, 0, kMaxFps, true, "--fps", "frames per second"); !s) return s.error();
  rq.photometry = {a.peak, a.black};
  if (Status s = rq.photometry.validate(); !s) return bad_input("--peak/--black: " + s.error().message);
  if (a.jod_release == "1.0") rq.parameters = perception::Parameters::release_1_0();
  // Stereo or not, and the ppd, from the first frame's size (headers only).
  auto sized = perception::plan_jod(rq);
  if (!sized) return sized.error();
  auto frame = metrics_frame(frame_choice(a), sized->width, sized->height);
  if (!frame) return frame.error();
  rq.stereo = frame->stereo;
  rq.display = frame->model;
  const auto fovea = [](const std::string& s, const char* what) -> Result<std::optional<perception::NormFovea>> {
    if (s.empty() || s == "none") return std::optional<perception::NormFovea>{};
    auto p = parse_fovea(s, what);
    if (!p) return p.error();
    return std::optional<perception::NormFovea>{perception::NormFovea{p->x, p->y}};
  };
  auto l = fovea(a.fovea, "--fovea");
  if (!l) return l.error();
  rq.fovea_left = rq.fovea_right = *l;
  if (!a.fovea_right.empty()) {
    if (!frame->stereo) return fovea_right_refused(*frame);
    auto r = fovea(a.fovea_right, "--fovea-right");
    if (!r) return r.error();
    rq.fovea_right = *r;
  }
  // Sized from the frame lists and headers before a pixel is decoded.
  auto plan = perception::plan_jod(rq);
  if (!plan) return plan.error();
  if (Status s = check_memory(plan->bytes, work_text(*plan, a.fps)); !s) return bad_input("metrics --jod: " + s.error().message);
  auto rep = perception::run_jod(rq);
  if (!rep) return rep.error();
  const auto& c = rep->combined;
  for (const perception::JodScore* sc : {&rep->combined, &rep->eyes.front(), &rep->eyes.back()})
    if (!std::isfinite(sc->jod) || !std::isfinite(sc->q))
      return Error{ErrorKind::internal, "metrics --jod: the metric gave JOD " + std::to_string(sc->jod) + " (Q " +
                                                        std::to_string(sc->q) + "), not a number: an internal error, not a result"};
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
  return {};
}

}  // namespace

Status run_metrics(const MetricsRequest& a) {
  if (a.ppd_given)
    if (Status s = check_range(a.ppd, kMinPpd, kMaxPpd, false, "--ppd", "pixels per degree"); !s) return s.error();
  if (a.jod) return run_jod(a);
  if (a.fovea.empty()) return bad_input("--fovea: required (except with --jod)");
  image::MetricsOptions opt;
  auto fovea = parse_fovea(a.fovea, "--fovea");
  if (!fovea) return fovea.error();
  opt.fovea = opt.fovea_right = *fovea;  // the same spot in each eye unless told
  auto hr = image::probe(a.ref);
  if (!hr) return bad_input("--ref " + hr.error().message);
  {  // Both images decoded (4 B a pixel each) and one decode's transients (docs/metrics.md, "Memory").
    auto ht = image::probe(a.test);
    if (!ht) return bad_input("--test " + ht.error().message);
    const std::uint64_t px = static_cast<std::uint64_t>(std::max(hr->width, ht->width)) * static_cast<std::uint64_t>(std::max(hr->height, ht->height));
    const std::uint64_t need = 12 * px + 2 * std::max(hr->file_bytes, ht->file_bytes);
    if (Status s = check_memory(need, "two " + std::to_string(hr->width) + "x" + std::to_string(hr->height) + " images"); !s)
      return bad_input("metrics: " + s.error().message);
  }
  auto frame = metrics_frame(frame_choice(a), hr->width, hr->height);
  if (!frame) return frame.error();
  if (!a.fovea_right.empty()) {
    if (!frame->stereo) return fovea_right_refused(*frame);
    auto r = parse_fovea(a.fovea_right, "--fovea-right");
    if (!r) return r.error();
    opt.fovea_right = *r;
  }
  opt.ppd = frame->ppd;
  opt.ssim_channels = a.ssim_channels == "rgb" ? image::SsimChannels::rgb : image::SsimChannels::luma;
  auto ref = load_named(a.ref, "--ref");
  if (!ref) return ref.error();
  auto test = load_named(a.test, "--test");
  if (!test) return test.error();
  if (ref->width != test->width || ref->height != test->height)
    return bad_input(a.test + ": size " + std::to_string(test->width) + "x" + std::to_string(test->height) +
                                 " differs from the reference " + a.ref + " (" + std::to_string(ref->width) + "x" +
                                 std::to_string(ref->height) + ")");

  nlohmann::json j = {{"ref", a.ref}, {"test", a.test}, {"size", {ref->width, ref->height}}, {"stereo", frame->stereo},
                      {"stereo_from", frame->stereo_from}, {"display", frame->display_name}, {"ppd", opt.ppd},
                      {"ppd_from", frame->ppd_from}, {"ssim_channels", a.ssim_channels}};
  if (frame->stereo) {
    auto m = image::compute_stereo_metrics(*ref, *test, opt);
    if (!m) return m.error();
    for (const auto& [eye, label] : {std::pair{&m->left, "left"}, std::pair{&m->right, "right"}, std::pair{&m->combined, "combined"}})
      if (Status s = check_finite(*eye, label); !s) return s.error();
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
    if (!m) return m.error();
    if (Status s = check_finite(*m, "image"); !s) return s.error();
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
  return {};
}

}  // namespace foveal::evaluation
