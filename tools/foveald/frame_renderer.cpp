#include "frame_renderer.hpp"

#include <algorithm>
#include <cinttypes>
#include <cstdio>

#include "foveal/core/data_paths.hpp"
#include "foveal/image/auto_f.hpp"
#include "foveal/image/image.hpp"

namespace foveal::daemon {

namespace {

constexpr std::size_t kRecentFrames = 128;

}  // namespace

Result<std::unique_ptr<FrameRenderer>> FrameRenderer::create(const RenderOptions& o, const DisplayModel& model,
                                                             const std::string& out_dir) {
  std::unique_ptr<FrameRenderer> r(new FrameRenderer());
  r->o_ = o;
  r->out_dir_ = out_dir;
  auto method = render::parse_method(o.method);
  if (!method) return method.error();
  r->method_ = *method;
  if (o.window) {
    render::WindowOptions wo;
    wo.monitor = o.monitor;
    wo.title = "foveald";
    auto w = render::Window::open(wo);
    if (!w) return w.error();
    r->window_.emplace(std::move(*w));
  } else if (o.drm) {
    auto d = render::DrmOutput::open(o.drm_options);
    if (!d) return d.error();
    r->drm_.emplace(std::move(*d));
  } else {
    auto ctx = gl::EglContext::create();
    if (!ctx) return ctx.error();
    r->egl_.emplace(std::move(*ctx));
  }
  auto scene = render::load_scene(o.scene.empty() ? data_path("data/scenes/Dungeon/dungeon_simplified.gltf") : o.scene);
  if (!scene) return scene.error();
  r->scene_.emplace(std::move(*scene));
  render::CompositorOptions co;
  co.width = o.width > 0 ? o.width : model.output_width();
  co.height = o.height > 0 ? o.height : model.output_height();
  co.model = model;
  co.distortion = o.distortion;
  auto comp = render::Compositor::create(co);
  if (!comp) return comp.error();
  r->comp_.emplace(std::move(*comp));
  auto csv = AtomicFile::create(out_dir + "/frames.csv");
  if (!csv) return csv.error();
  r->csv_.emplace(std::move(*csv));
  r->csv_->write(
      "frame,t_ns,generation,fovea_left_x,fovea_left_y,fovea_right_x,fovea_right_y,sigma_left,sigma_right,"
      "buffer_left_w,buffer_left_h,buffer_right_w,buffer_right_h,f_x,f_y,shadow_ms,gbuffer_ms,mapping_ms,lighting_ms,"
      "inverse_ms,gpu_ms,cpu_ms\n");
  return r;
}

FrameRenderer::~FrameRenderer() = default;

Status FrameRenderer::render(const FoveaFrame& fovea, const RenderSettings& s, const DisplayModel& model) {
  const Eye dominant = s.dominant_eye == 0 ? Eye::left : Eye::right;
  render::FrameParams p = render::efr_frame(method_, dominant, s.sigma_d, s.sigma_nd, s.f_x, s.f_y);
  for (Eye e : kEyes) {
    const std::size_t i = static_cast<std::size_t>(e);
    const FoveaPoint& fp = fovea.eye(e);
    if (fp.state != FoveaState::lost && std::isfinite(fp.px.x) && std::isfinite(fp.px.y))
      last_fovea_[i] = glm::dvec2(double(fp.px.x) / model.eye_width, double(fp.px.y) / model.eye_height);
    p.eyes[i].fovea_x = last_fovea_[i].x;
    p.eyes[i].fovea_y = last_fovea_[i].y;
  }
  // f < 0 means automatic: estimated once per settings change (docs/methods.md).
  if ((s.f_x <= 0 || s.f_y <= 0) && auto_f_generation_ != s.generation) {
    if (Status st = estimate_f(p); !st) return st;
    auto_f_generation_ = s.generation;
  }
  for (auto& e : p.eyes) {
    if (s.f_x <= 0) e.fx = auto_fx_;
    if (s.f_y <= 0) e.fy = auto_fy_;
  }
  const double fx = p.eyes[0].fx, fy = p.eyes[0].fy;
  auto t = comp_->render(*scene_, p);
  if (!t) return t.error();
  if (frames_ > 0 && s.generation != last_generation_) ++settings_changes_;
  last_generation_ = s.generation;
  last_params_ = p;
  if (recent_.size() < kRecentFrames) recent_.push_back(*t);
  else recent_[frames_ % kRecentFrames] = *t;

  const auto bl = comp_->buffer_size(Eye::left), br = comp_->buffer_size(Eye::right);
  char line[512];
  std::snprintf(line, sizeof line,
                "%" PRIu64 ",%" PRId64 ",%u,%.5f,%.5f,%.5f,%.5f,%.3f,%.3f,%d,%d,%d,%d,%.3f,%.3f,%.3f,%.3f,%.3f,%.3f,%.3f,%.3f,%.3f\n",
                frames_, static_cast<std::int64_t>(fovea.t_ns), s.generation, p.eyes[0].fovea_x, p.eyes[0].fovea_y,
                p.eyes[1].fovea_x, p.eyes[1].fovea_y, p.eyes[0].sigma, p.eyes[1].sigma, bl[0], bl[1], br[0], br[1], fx, fy,
                t->shadow, t->gbuffer, t->mapping, t->lighting, t->inverse, t->gpu_total, t->cpu);
  if (window_) window_->present(comp_->output_framebuffer(), comp_->width(), comp_->height());
  if (drm_)
    if (Status st = drm_->present(comp_->output_framebuffer(), comp_->width(), comp_->height()); !st) return st;
  // A row once the frame is on its way to the screen, readable in the temporary file
  // while foveald runs.
  csv_->write(line);
  std::fflush(csv_->stream());
  const bool save = frames_ == 0 || (o_.save_every > 0 && frames_ % static_cast<std::uint64_t>(o_.save_every) == 0);
  ++frames_;
  if (save) return save_frame();
  return {};
}

Status FrameRenderer::estimate_f(const render::FrameParams& p) {
  render::FrameParams full = p;
  full.method = render::Method::full;
  for (auto& e : full.eyes) e.fx = e.fy = 0.3;  // unused by full; keeps the plan valid
  if (auto t = comp_->render(*scene_, full); !t) return t.error();
  image::MetricsOptions mo;
  mo.ppd = comp_->plan(Eye::left).pixels_per_degree();
  mo.fovea = {p.eyes[0].fovea_x, p.eyes[0].fovea_y};
  mo.fovea_right = {p.eyes[1].fovea_x, p.eyes[1].fovea_y};
  auto est = image::estimate_rmfr_f(comp_->read_image(), {p.eyes[0].sigma, p.eyes[1].sigma}, mo);
  if (!est) return est.error();
  auto_fx_ = est->fx;
  auto_fy_ = est->fy;
  return {};
}

Status FrameRenderer::save_frame() {
  if (frames_ == 0 || saved_frame_ == frames_ - 1) return {};
  char name[64];
  std::snprintf(name, sizeof name, "frame_%06" PRIu64 ".png", frames_ - 1);
  if (Status s = image::save_png(out_dir_ + "/" + name, comp_->read_image()); !s) return s;
  saved_frame_ = frames_ - 1;
  saved_.push_back(name);
  return {};
}

Status FrameRenderer::finish() {
  if (drm_)
    if (Status s = drm_->finish(); !s) return s;
  if (Status s = save_frame(); !s) return s;
  return csv_->commit();
}

nlohmann::json FrameRenderer::output_json() const {
  if (window_) return {{"kind", "window"}, {"present", window_->stats().json()}};
  if (drm_) {
    const render::KmsMode& m = drm_->mode();
    nlohmann::json connector = render::connector_json(drm_->connector());
    connector.erase("modes");  // `foveal outputs` lists them
    return {{"kind", "drm"},
            {"device", drm_->device()},
            {"connector", connector},
            {"mode", {{"width", m.width}, {"height", m.height}, {"refresh_hz", m.refresh_hz}}},
            {"present", drm_->stats().json()}};
  }
  return {{"kind", "headless"}};
}

bool FrameRenderer::window_closed() const { return window_ && window_->should_close(); }

nlohmann::json FrameRenderer::stats_json() const {
  const render::PassTimes med = render::median_pass_times(recent_);
  nlohmann::json eyes;
  for (Eye e : kEyes) {
    const auto& f = last_params_.eyes[static_cast<std::size_t>(e)];
    const auto b = comp_->buffer_size(e);
    eyes[eye_name(e)] = {{"sigma", f.sigma}, {"fovea", {f.fovea_x, f.fovea_y}}, {"buffer", {b[0], b[1]}}};
  }
  return {{"frames", frames_},
          {"scene", scene_->name},
          {"method", render::method_name(method_)},
          {"size", {comp_->width(), comp_->height()}},
          {"renderer", comp_->renderer()},
          {"output", output_json()},
          {"settings_generation", last_generation_},
          {"settings_changes_seen", settings_changes_},
          {"auto_f", auto_f_generation_ ? nlohmann::json({{"fx", auto_fx_}, {"fy", auto_fy_}}) : nlohmann::json(nullptr)},
          {"last_frame", eyes},
          {"passes_ms_median", {{"shadow", med.shadow}, {"gbuffer", med.gbuffer}, {"mapping", med.mapping},
                                {"lighting", med.lighting}, {"inverse", med.inverse},
                                {"gpu_total", med.gpu_total}, {"cpu_frame", med.cpu}}},
          {"targets_mb", static_cast<double>(comp_->memory().total()) / (1024.0 * 1024.0)},
          {"saved", saved_}};
}

}  // namespace foveal::daemon
