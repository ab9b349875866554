#include "foveal/bench/bench_flicker.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <map>
#include <optional>
#include <sstream>

#include <glm/geometric.hpp>
#include <glm/vec2.hpp>

#include "foveal/bench/bench_outputs.hpp"
#include "foveal/core/data_paths.hpp"
#include "foveal/core/display_model.hpp"
#include "foveal/core/gaze_log.hpp"
#include "foveal/image/foveate.hpp"
#include "foveal/image/metrics.hpp"
#include "foveal/render/scene.hpp"
#include "foveal/render/stereo_camera.hpp"
#include "foveal/runtime/gaze_pipeline.hpp"

namespace foveal::bench {

using render::Method;
using render::Pipeline;

const char* const kFlickerColumns =
    "scene,pipeline,camera,method,sigma,sigma_nd,gaze,frames,fovea_step_px,reference_change,periphery_error,periphery_change,flicker,"
    "prefiltered_flicker,reference,temporal";

const char* flicker_gaze_name(FlickerGaze g) {
  switch (g) {
    case FlickerGaze::raw: return "raw";
    case FlickerGaze::filtered: return "filtered";
    case FlickerGaze::fixed: return "fixed";
  }
  return "?";
}

namespace {

/// Only the periphery counts: pixels more than this far from both frames' foveae.
constexpr double kPeripheryDeg = 15.0;
/// The window starts this many samples in (1 s at 120 Hz), after the filter has settled.
constexpr std::size_t kStartSample = 120;
/// The shared reference is the full method through the G-buffer pipeline (the project's
/// reference); with FlickerOptions::own_reference each pipeline's own full frames are.
constexpr Pipeline kSharedReference = Pipeline::gbuffer;

constexpr auto num = bench::csv_number;

template <class T, class Parse>
Result<std::vector<T>> parse_list(const std::string& list, const std::string& option, Parse parse) {
  std::vector<T> out;
  std::istringstream in(list);
  for (std::string item; std::getline(in, item, ',');) {
    auto v = parse(item);
    if (!v) return v.error();
    if (std::find(out.begin(), out.end(), *v) != out.end()) return bad_input(option + ": '" + item + "' is listed twice");
    out.push_back(*v);
  }
  if (out.empty()) return bad_input(option + ": no values in '" + list + "'");
  return out;
}

/// The frames' R, G, B at every second pixel of every second row: what the figures read.
using Samples = std::vector<std::uint8_t>;
Samples sample(const image::Image& img) {
  Samples s;
  s.reserve(static_cast<std::size_t>((img.width + 1) / 2) * static_cast<std::size_t>((img.height + 1) / 2) * 3);
  for (int y = 0; y < img.height; y += 2)
    for (int x = 0; x < img.width; x += 2) s.insert(s.end(), img.at(x, y), img.at(x, y) + 3);
  return s;
}

/// Both eyes' foveae (normalised viewport coordinates) for each frame of the window.
using Foveae = std::array<glm::dvec2, 2>;

/// The window of the log the run renders: the samples' foveae (raw and filtered), their
/// times and head poses.
struct GazeWindow {
  std::vector<Foveae> raw, filtered;
  std::vector<double> t_s;               ///< since the window's first sample
  std::vector<std::optional<Pose>> head;  ///< the log's pose, relative to the window's first valid one
  double fps = 0;                         ///< frames per second: the samples' mean rate over the window
};

Result<GazeWindow> read_window(const std::string& log, int frames) {
  const std::string path = log.empty() ? data_path("data/gaze/vive_pro_eye_TESTNA01.csv") : log;
  auto samples = read_gaze_log(path);
  if (!samples) return samples.error();
  const DisplayModel model = DisplayModel::vive_pro_eye();
  GazePipeline pipe(model, FilterConfig{});
  const glm::dvec2 eye_size(model.eye_width, model.eye_height);
  const std::size_t start = std::min<std::size_t>(kStartSample, samples->size() > 2 ? samples->size() - 2 : 0);
  const std::size_t n = std::min<std::size_t>(static_cast<std::size_t>(frames), samples->size() - start);
  if (n < 2) return bad_input(path + ": too short for --flicker (" + std::to_string(samples->size()) + " samples)");
  GazeWindow w;
  Foveae last_raw{glm::dvec2(0.5), glm::dvec2(0.5)};
  std::optional<Pose> anchor;
  for (std::size_t k = 0; k < start + n; ++k) {
    const GazeSample& g = (*samples)[k];
    const FoveaFrame f = pipe.update(g);  // every sample, so the filter has settled at the window
    Foveae r = last_raw, q{};
    for (Eye e : kEyes) {
      const std::size_t i = static_cast<std::size_t>(e);
      if (g.eyes[i].has(kValidDirection)) {
        const glm::vec2 px = model.direction_to_pixel(e, g.eyes[i].direction);
        if (std::isfinite(px.x) && std::isfinite(px.y)) r[i] = glm::clamp(glm::dvec2(px) / eye_size, 0.0, 1.0);
      }
      q[i] = glm::dvec2(f.eyes[i].px) / eye_size;
    }
    last_raw = r;
    if (k < start) continue;
    w.raw.push_back(r);
    w.filtered.push_back(q);
    w.t_s.push_back(static_cast<double>(g.t_ns - (*samples)[start].t_ns) * 1e-9);
    if (g.head.valid && !anchor) anchor = g.head.pose;
    w.head.push_back(g.head.valid ? std::optional<Pose>(relative_to(*anchor, g.head.pose)) : std::nullopt);
  }
  w.fps = static_cast<double>(w.t_s.size() - 1) / w.t_s.back();
  if (!(std::isfinite(w.fps) && w.fps > 0 && w.fps <= 1000))
    return bad_input(path + ": the samples of the --flicker window span " + std::to_string(w.t_s.back()) +
                     " s: no frame rate in (0, 1000] Hz for JOD");
  return w;
}

/// The head pose of each frame along one camera path.
Result<std::vector<Pose>> path_poses(const CameraPath& path, const GazeWindow& w, double pivot_m, double start_m, const std::string& log) {
  const Pose start{glm::vec3(0.0f, 0.0f, static_cast<float>(-start_m)), glm::quat(1.0f, 0.0f, 0.0f, 0.0f)};
  std::vector<Pose> out;
  if (path.kind == CameraPath::Kind::recorded) {
    if (std::none_of(w.head.begin(), w.head.end(), [](const auto& h) { return h.has_value(); }))
      return bad_input("--camera-path recorded: " + (log.empty() ? std::string("the bundled recording") : log) +
                       " has no head pose in the frames --flicker renders (a native log v2 with head columns has one)");
    Pose held{};  // until the first valid pose: the scene's view; then the last one seen
    for (const auto& h : w.head) {
      if (h) held = *h;
      out.push_back(compose(start, held));
    }
    return out;
  }
  for (double t : w.t_s) out.push_back(compose(start, camera_pose(path, pivot_m, t)));
  return out;
}

/// The figures of one point, summed over the frame pairs.
struct Sums {
  double reference_change = 0, error = 0, change = 0, flicker = 0, prefiltered_flicker = 0, fovea_step = 0;
  std::size_t values = 0;
};

/// One frame of a point: the foveated frame F, the reference R and, for RMFR, the
/// prefiltered reference P (empty otherwise).
struct FrameSamples {
  const Samples *f, *r, *p;
};

/// Adds frame k against frame k-1 to `s`, over the periphery.
void accumulate(const FrameSamples& prev, const FrameSamples& cur, const Foveae& fv_prev, const Foveae& fv, int eye_w, int eye_h,
                double f_px, Sums& s) {
  const Samples &f_prev = *prev.f, &f = *cur.f, &r_prev = *prev.r, &r = *cur.r;
  const bool prefiltered = !cur.p->empty();
  for (std::size_t i = 0; i < 2; ++i) s.fovea_step += glm::length((fv[i] - fv_prev[i]) * glm::dvec2(eye_w, eye_h)) / 2;
  std::size_t j = 0;
  for (int y = 0; y < eye_h; y += 2)
    for (int x = 0; x < 2 * eye_w; x += 2, j += 3) {
      const std::size_t e = x < eye_w ? 0 : 1;
      const double px = (x % eye_w) + 0.5 - eye_w / 2.0, py = y + 0.5 - eye_h / 2.0;
      auto ecc = [&](glm::dvec2 g) { return image::eccentricity_deg(px, py, g.x * eye_w - eye_w / 2.0, g.y * eye_h - eye_h / 2.0, f_px); };
      if (ecc(fv[e]) < kPeripheryDeg || ecc(fv_prev[e]) < kPeripheryDeg) continue;
      for (std::size_t c = 0; c < 3; ++c) {
        const int df = int(f[j + c]) - int(f_prev[j + c]), dr = int(r[j + c]) - int(r_prev[j + c]);
        s.change += std::abs(df);
        s.reference_change += std::abs(dr);
        s.flicker += std::abs(df - dr);
        s.error += std::abs(int(f[j + c]) - int(r[j + c]));
        if (prefiltered) s.prefiltered_flicker += std::abs(df - (int((*cur.p)[j + c]) - int((*prev.p)[j + c])));
      }
      s.values += 3;
    }
}

/// What an ideally prefiltered RMFR makes of a reference frame: each eye area-averaged
/// into its reduced buffer and mapped back (image::foveate, the same mapping as the
/// compositor's), sampled like the frames.
Result<Samples> prefiltered(const image::Image& reference, const render::FrameParams& f) {
  const int eye_w = reference.width / 2;
  std::array<image::Image, 2> eyes;
  for (std::size_t i = 0; i < 2; ++i) {
    const image::Image eye = image::crop(reference, {static_cast<int>(i) * eye_w, 0, eye_w, reference.height});
    const render::EyeFoveation& e = f.eyes[i];
    auto r = image::foveate(eye, {e.sigma, e.fx, e.fy, e.fovea_x, e.fovea_y});
    if (!r) return r.error();
    eyes[i] = std::move(r->output);
  }
  return sample(image::hconcat(eyes[0], eyes[1]));
}

}  // namespace

Result<std::vector<CameraPath>> parse_camera_paths(const std::string& list) {
  return parse_list<CameraPath>(list, "--camera-path", [](const std::string& s) { return parse_camera_path(s); });
}

Result<std::vector<FlickerGaze>> parse_flicker_gazes(const std::string& list) {
  return parse_list<FlickerGaze>(list, "--flicker-gaze", [](const std::string& s) -> Result<FlickerGaze> {
    for (FlickerGaze g : {FlickerGaze::raw, FlickerGaze::filtered, FlickerGaze::fixed})
      if (s == flicker_gaze_name(g)) return g;
    return bad_input("--flicker-gaze: '" + s + "': expected raw, filtered or fixed");
  });
}

Result<std::vector<Pipeline>> parse_flicker_pipelines(const std::string& list, Pipeline fallback) {
  if (list.empty()) return std::vector<Pipeline>{fallback};
  return parse_list<Pipeline>(list, "--flicker-pipelines", [](const std::string& s) -> Result<Pipeline> {
    auto p = render::parse_pipeline(s);
    if (!p) return bad_input("--flicker-pipelines: " + p.error().message);
    return *p;
  });
}

Result<std::vector<bool>> parse_temporal_list(const std::string& list) {
  auto v = parse_list<bool>(list, "--temporal", [](const std::string& s) -> Result<bool> {
    if (s == "off" || s == "on") return s == "on";
    return bad_input("--temporal: '" + s + "': expected off or on");
  });
  if (v) std::sort(v->begin(), v->end());  // off first: the on rows compare against it
  return v;
}

std::vector<bool> temporal_values(const std::vector<bool>& temporal, Method m, Pipeline p) {
  if (!render::temporal_applies(m, p)) return {false};
  return temporal;
}

std::size_t flicker_points(const FlickerOptions& o, const std::vector<Method>& methods_without_full) {
  std::size_t per_camera = 0;
  for (Pipeline p : o.pipelines) {
    per_camera += 1;  // full
    for (Method m : methods_without_full) per_camera += temporal_values(o.temporal, m, p).size();
  }
  return o.cameras.size() * per_camera * o.gazes.size();
}

Status run_flicker(const FlickerOptions& o, render::Compositor& comp, const std::vector<Method>& methods_without_full,
                   const std::string& spec, bench::SweepRows& rows, const std::function<void()>& tick, StereoJodScorer* jod) {
  std::optional<render::Scene> scene;  // loaded by the first point this shard runs
  std::optional<GazeWindow> window;
  auto load = [&]() -> Status {
    if (scene) return {};
    auto s = render::load_scene(spec);
    if (!s) return s.error();
    scene = std::move(*s);
    auto w = read_window(o.log, o.frames);
    if (!w) return w.error();
    window = std::move(*w);
    return {};
  };
  const std::string scene_name = std::filesystem::path(spec).stem().string();
  const int eye_w = comp.width() / 2, eye_h = comp.height();
  std::vector<Method> methods = {Method::full};
  methods.insert(methods.end(), methods_without_full.begin(), methods_without_full.end());

  auto frame = [&](Method m, Pipeline p, const Foveae& fv, const Pose& head, bool temporal = false) {
    render::FrameParams f = render::efr_frame(m, Eye::right, o.sigma, o.sigma_nd > 0 ? o.sigma_nd : o.sigma, o.fx, o.fy);
    for (std::size_t i = 0; i < 2; ++i) f.eyes[i].fovea_x = fv[i].x, f.eyes[i].fovea_y = fv[i].y;
    f.pipeline = p;
    f.head = head;
    f.temporal = temporal;
    f.blend_at = o.blend_at;
    return f;
  };
  auto render_image = [&](const render::FrameParams& f) -> Result<image::Image> {
    auto r = comp.render(*scene, f);
    if (!r) return r.error();
    return comp.read_image();
  };

  auto foveae_of = [&](FlickerGaze gaze) {
    if (gaze == FlickerGaze::raw) return window->raw;
    if (gaze == FlickerGaze::filtered) return window->filtered;
    const glm::dvec2 at(o.fovea.first, o.fovea.second);
    return std::vector<Foveae>(window->raw.size(), Foveae{at, at});
  };
  const bool has_rmfr = std::find(methods.begin(), methods.end(), Method::rmfr) != methods.end();

  struct References {
    std::vector<Samples> frames;              // per frame; one for a still camera (the same every frame)
    std::vector<image::Image> images;         // the same frames whole, for JOD (empty without)
    std::vector<std::vector<Samples>> ideal;  // per gaze, per frame: RMFR's prefiltered reference
  };
  for (const CameraPath& given : o.cameras) {
    std::vector<Pose> heads;
    std::map<Pipeline, References> references;  // by the pipeline that rendered them
    CameraPath path = given;
    // The path's poses, once per path, when a point needs them.
    auto prepare = [&]() -> Status {
      if (!heads.empty()) return {};
      if (Status s = load(); !s) return s;
      const render::ViewPose& v = scene->view;
      ViewGeometry g = view_geometry(v.head_to_world, v.units_per_meter, scene->bounds.center(), scene->bounds.radius());
      const double start_m = o.fill ? fill_offset_m(g) : 0.0;
      g.ahead_m -= start_m;
      const double pivot_m = o.pivot_m > 0 ? o.pivot_m : default_pivot_m(g);
      path = with_default_speed(given, pivot_m);
      auto h = path_poses(path, *window, pivot_m, start_m, o.log);
      if (!h) return h.error();
      heads = std::move(*h);
      return {};
    };
    // The references along the path through `rp`, once per path and pipeline.
    auto references_of = [&](Pipeline rp) -> Result<const References*> {
      if (auto it = references.find(rp); it != references.end()) return &it->second;
      References out;
      out.ideal.resize(o.gazes.size());
      const bool still = std::all_of(heads.begin(), heads.end(), [&](const Pose& p) { return p == heads.front(); });
      std::vector<std::vector<Foveae>> foveae;
      for (FlickerGaze gaze : o.gazes) foveae.push_back(foveae_of(gaze));
      image::Image img;
      for (std::size_t k = 0; k < heads.size(); ++k) {
        if (k == 0 || !still) {
          auto r = render_image(frame(Method::full, rp, window->raw[k], heads[k]));
          if (!r) return r.error();
          img = std::move(*r);
          out.frames.push_back(sample(img));
          if (jod) out.images.push_back(img);
        }
        for (std::size_t gi = 0; has_rmfr && gi < o.gazes.size(); ++gi) {
          auto p = prefiltered(img, frame(Method::rmfr, rp, foveae[gi][k], heads[k]));
          if (!p) return p.error();
          out.ideal[gi].push_back(std::move(*p));
        }
      }
      return &references.emplace(rp, std::move(out)).first->second;
    };

    for (Pipeline pipeline : o.pipelines)
      for (Method m : methods)
          for (bool temporal : temporal_values(o.temporal, m, pipeline))
          for (std::size_t gi = 0; gi < o.gazes.size(); ++gi) {
            const FlickerGaze gaze = o.gazes[gi];
            if (!rows.take()) continue;
            if (Status s = prepare(); !s) return s;
            const Pipeline rp = o.own_reference ? pipeline : kSharedReference;
            auto refs = references_of(rp);
            if (!refs) return refs.error();
            const References& refset = **refs;
            auto ref = [&](std::size_t k) -> const Samples& { return refset.frames[std::min(k, refset.frames.size() - 1)]; };
            auto ref_image = [&](std::size_t k) -> const image::Image& { return refset.images[std::min(k, refset.images.size() - 1)]; };
            const std::size_t n = heads.size();
            const std::vector<Foveae> foveae = foveae_of(gaze);
            static const Samples none;
            auto ideal_at = [&](std::size_t k) -> const Samples& { return m == Method::rmfr ? refset.ideal[gi][k] : none; };
            const double ppd = comp.plan(Eye::left).screen_w > 0 ? comp.plan(Eye::left).pixels_per_degree() : 13.15 * eye_w / 1440.0;
            const double f_px = image::focal_length_px(ppd);
            // The reference's own frames stand for full through its pipeline (it renders them).
            const bool is_reference = m == Method::full && pipeline == rp;
            Sums sums;
            Samples prev;
            // JOD as a video at the log's rate, each eye at its recorded (raw) gaze: where the
            // viewer looked, whichever fovea the frame was rendered with.
            std::optional<StereoJodScorer::Video> video;
            if (jod) {
              auto v = jod->video(window->fps);
              if (!v) return v.error();
              video.emplace(std::move(*v));
            }
            comp.reset_history();  // a point's history starts with its first frame
            for (std::size_t k = 0; k < n; ++k) {
              Samples cur;
              const EyeFovea gaze_l = std::array<double, 2>{window->raw[k][0].x, window->raw[k][0].y};
              const EyeFovea gaze_r = std::array<double, 2>{window->raw[k][1].x, window->raw[k][1].y};
              if (is_reference) {
                cur = ref(k);
                if (video)
                  if (Status st = video->push(ref_image(k), ref_image(k), gaze_l, gaze_r); !st) return st;
              } else {
                auto r = render_image(frame(m, pipeline, foveae[k], heads[k], temporal));
                if (!r) return r.error();
                cur = sample(*r);
                if (video)
                  if (Status st = video->push(ref_image(k), *r, gaze_l, gaze_r); !st) return st;
              }
              if (k > 0)
                accumulate({&prev, &ref(k - 1), &ideal_at(k - 1)}, {&cur, &ref(k), &ideal_at(k)}, foveae[k - 1], foveae[k], eye_w, eye_h, f_px, sums);
              prev = std::move(cur);
            }
            std::optional<StereoJod> jv;
            if (video) {
              auto sc = video->score();
              if (!sc) return sc.error();
              jv = *sc;
            }
            tick();
            const double values = sums.values ? static_cast<double>(sums.values) : 1.0;
            const double sigma = m == Method::full ? 1.0 : o.sigma, sigma_nd = m == Method::full ? 1.0 : o.sigma_nd > 0 ? o.sigma_nd : o.sigma;
            const double step = sums.fovea_step / static_cast<double>(n - 1);
            rows.add_line("flicker.csv", scene_name + "," + render::pipeline_name(pipeline) + "," + path.text() + "," + render::method_name(m) +
                                             "," + num(sigma) + "," + num(sigma_nd) + "," + flicker_gaze_name(gaze) + "," + std::to_string(n) + "," + num(step) +
                                             "," + num(sums.reference_change / values) + "," + num(sums.error / values) + "," +
                                             num(sums.change / values) + "," + num(sums.flicker / values) + "," +
                                             (m == Method::rmfr ? num(sums.prefiltered_flicker / values) : std::string()) + "," +
                                             render::pipeline_name(rp) + (temporal ? ",on" : ",off") +
                                             (jv ? "," + num(jv->left) + "," + num(jv->right) + "," + num(jv->combined) : ""));
            nlohmann::json item = {{"scene", scene_name}, {"pipeline", render::pipeline_name(pipeline)}, {"camera", path.text()},
                                      {"method", render::method_name(m)}, {"sigma", sigma}, {"sigma_nd", sigma_nd}, {"gaze", flicker_gaze_name(gaze)},
                                      {"frames", n}, {"fovea_step_px", step}, {"reference_change", sums.reference_change / values},
                                      {"periphery_error", sums.error / values}, {"periphery_change", sums.change / values},
                                      {"flicker", sums.flicker / values},
                                      {"prefiltered_flicker", m == Method::rmfr ? nlohmann::json(sums.prefiltered_flicker / values) : nlohmann::json()},
                                      {"reference", render::pipeline_name(rp)}, {"temporal", temporal ? "on" : "off"}};
            if (jv) item.update({{"jod_left", jv->left}, {"jod_right", jv->right}, {"jod", jv->combined}});
            rows.add_item("flicker", std::move(item));
          }
  }
  return {};
}

}  // namespace foveal::bench
