#include "frame_renderer.hpp"

#include <algorithm>
#include <cinttypes>
#include <cstdio>
#include <utility>

#include "foveal/core/data_paths.hpp"
#include "output_target.hpp"
#include "foveal/image/auto_f.hpp"
#include "foveal/image/image.hpp"

namespace foveal::daemon {

namespace {

constexpr std::size_t kRecentFrames = 128;

// The fovea points a frame renders (the gaze pipeline decides what a lost eye shows; the
// centre stands in only before the first sample).
void set_fovea(std::array<render::EyeFoveation, 2>& eyes, const FoveaFrame& fovea, const DisplayModel& model) {
  for (Eye e : kEyes) {
    const FoveaPoint& fp = fovea.eye(e);
    const bool known = std::isfinite(fp.px.x) && std::isfinite(fp.px.y) && model.eye_width > 0 && model.eye_height > 0;
    auto& eye = eyes[static_cast<std::size_t>(e)];
    eye.fovea_x = known ? double(fp.px.x) / model.eye_width : 0.5;
    eye.fovea_y = known ? double(fp.px.y) / model.eye_height : 0.5;
  }
}

}  // namespace

Result<std::unique_ptr<FrameRenderer>> FrameRenderer::create(const RenderOptions& o, const DisplayModel& model,
                                                             const std::string& out_dir) {
  std::unique_ptr<FrameRenderer> r(new FrameRenderer());
  r->o_ = o;
  r->out_dir_ = out_dir;
  auto method = render::parse_method(o.method);
  if (!method) return method.error();
  r->method_ = *method;
  auto pipeline = render::parse_pipeline(o.pipeline);
  if (!pipeline) return Error{pipeline.error().kind, "--pipeline: " + pipeline.error().message};
  r->pipeline_ = *pipeline;
  auto blend_at = render::parse_blend_at(o.blend_at);
  if (!blend_at) return Error{blend_at.error().kind, "--blend-at: " + blend_at.error().message};
  if (Status s = render::check_blend_at(*blend_at, r->pipeline_); !s) return s.error();
  r->blend_at_ = *blend_at;
  auto output = render::open_output(o.output);
  if (!output) return output.error();
  r->output_ = std::move(*output);
  auto scene = render::load_scene(o.scene.empty() ? data_path("data/scenes/Dungeon/dungeon_simplified.gltf") : o.scene);
  if (!scene) return scene.error();
  r->scene_.emplace(std::move(*scene));
  r->scene_name_ = r->scene_->name;
  render::CompositorOptions co;
  co.width = o.width > 0 ? o.width : model.output_width();
  co.height = o.height > 0 ? o.height : model.output_height();
  co.model = model;
  co.distortion = o.distortion;
  auto comp = render::Compositor::create(co);
  if (!comp) return comp.error();
  r->comp_.emplace(std::move(*comp));
  r->renderer_name_ = r->comp_->renderer();
  r->size_ = {r->comp_->width(), r->comp_->height()};
  r->snap_.output = r->output_->json();
  r->snap_.targets_mb = static_cast<double>(r->comp_->memory().total()) / (1024.0 * 1024.0);
  auto csv = AtomicFile::create(out_dir + "/frames.csv");
  if (!csv) return csv.error();
  r->csv_.emplace(std::move(*csv));
  r->csv_->write(
      std::string("frame,t_ns,generation,fovea_left_x,fovea_left_y,fovea_right_x,fovea_right_y,sigma_left,sigma_right,"
                  "buffer_left_w,buffer_left_h,buffer_right_w,buffer_right_h,f_x,f_y,shadow_ms,gbuffer_ms,mapping_ms,"
                  "lighting_ms,inverse_ms,gpu_ms,cpu_ms,head_x,head_y,head_z,head_qw,head_qx,head_qy,head_qz,head_t_ns,") +
      FrameLatency::csv_header() + ",blend_ms\n");
  // Direct mode paces to its mode's refresh, known now that the output is open.
  const nlohmann::json& out = r->snap_.output;
  const double mode_hz = out.contains("mode") ? out["mode"].value("refresh_hz", 0.0) : 0.0;
  r->refresh_hz_ = mode_hz > 0 ? mode_hz : o.refresh_hz;
  r->pacer_.emplace(o.pacing, r->refresh_hz_);
  return r;
}

FrameRenderer::~FrameRenderer() = default;

FramePlan FrameRenderer::plan_next_frame(TimeNs now) const { return pacer_->plan(now, last_shown_); }

Status FrameRenderer::render(const std::function<FoveaFrame()>& latest, const RenderSettings& s,
                             const DisplayModel& model, const PoseAt& head, const FramePlan& plan) {
  FrameLatency lat;
  lat.start_ns = monotonic_now_ns();
  lat.display_target_ns = plan.display_target_ns;
  const Eye dominant = s.dominant_eye == 0 ? Eye::left : Eye::right;
  render::FrameParams p = render::efr_frame(method_, dominant, s.sigma_d, s.sigma_nd, s.f_x, s.f_y);
  p.pipeline = pipeline_;
  p.ipd_mm = s.ipd_mm;
  p.temporal = o_.temporal.value_or(s.temporal);
  p.blend_at = blend_at_;
  if (head.valid) p.head = head.relative;
  // What the frame shows: the newest fovea, predicted to when the frame is shown.
  const auto shown_fovea = [&](const FoveaFrame& f) {
    return predict_fovea(f, plan.display_target_ns, model.eye_width, model.eye_height, o_.prediction);
  };
  FoveaFrame used = latest();
  lat.latch_ns = monotonic_now_ns();
  set_fovea(p.eyes, shown_fovea(used), model);
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
  // Late latch: the newest fovea once the passes that do not need it are done.
  const render::FoveaLatch latch = [&](std::array<render::EyeFoveation, 2>& eyes) {
    used = latest();
    lat.latch_ns = monotonic_now_ns();
    set_fovea(eyes, shown_fovea(used), model);
  };
  auto t = comp_->render(*scene_, p, o_.late_latch ? latch : render::FoveaLatch{});
  if (!t) return t.error();
  lat.gpu_done_ns = t->gpu_done_ns;
  lat.sample_t_ns = used.t_ns;
  lat.sample_device_t_ns = used.device_t_ns;
  lat.arrival_ns = used.arrival_ns;
  const bool generation_changed = frames_ > 0 && s.generation != last_generation_;
  last_generation_ = s.generation;

  const auto bl = comp_->buffer_size(Eye::left), br = comp_->buffer_size(Eye::right);
  // The fovea the frame was rendered with (`fixed` pins it at the optical centre).
  for (Eye e : kEyes) {
    auto& eye = p.eyes[static_cast<std::size_t>(e)];
    eye.fovea_x = comp_->plan(e).fovea.x, eye.fovea_y = comp_->plan(e).fovea.y;
  }
  // The head pose this frame used, in the tracking frame as the log records it (the
  // identity for a static camera); %.9g keeps a float's digits, so the columns equal the log's.
  const Pose& hp = head.pose;
  char line[768];
  std::snprintf(line, sizeof line,
                "%" PRIu64 ",%" PRId64 ",%u,%.5f,%.5f,%.5f,%.5f,%.3f,%.3f,%d,%d,%d,%d,%.3f,%.3f,%.3f,%.3f,%.3f,%.3f,%.3f,%.3f,%.3f,"
                "%.9g,%.9g,%.9g,%.9g,%.9g,%.9g,%.9g,%" PRId64 ",",
                frames_, static_cast<std::int64_t>(used.t_ns), s.generation, p.eyes[0].fovea_x, p.eyes[0].fovea_y,
                p.eyes[1].fovea_x, p.eyes[1].fovea_y, p.eyes[0].sigma, p.eyes[1].sigma, bl[0], bl[1], br[0], br[1], fx, fy,
                t->shadow, t->gbuffer, t->mapping, t->lighting, t->inverse, t->gpu_total, t->cpu, double(hp.position_m.x),
                double(hp.position_m.y), double(hp.position_m.z), double(hp.orientation.w), double(hp.orientation.x),
                double(hp.orientation.y), double(hp.orientation.z), static_cast<std::int64_t>(head.t_ns));
  if (Status st = output_->present(comp_->output_framebuffer(), comp_->width(), comp_->height()); !st) return st;
  pending_.push_back({line, lat, output_->last_ready_ns(), t->blend});
  // Just in time needs this frame's refresh before it plans the next.
  if (o_.pacing == Pacing::jit)
    if (Status st = output_->finish(); !st) return st;
  if (Status st = write_shown_rows(); !st) return st;
  {
    std::lock_guard lock(csv_mutex_);
    if (csv_closed_) return {};  // abandoned: this frame is not counted
  }
  const bool save = frames_ == 0 || (o_.save_every > 0 && frames_ % static_cast<std::uint64_t>(o_.save_every) == 0);
  ++frames_;
  // Built before taking the lock, so a status request never waits for it.
  nlohmann::json output = output_->json();
  {
    std::lock_guard lock(snapshot_mutex_);
    snap_.frames = frames_;
    snap_.last_params = p;
    snap_.buffers = {bl, br};
    if (snap_.recent.size() < kRecentFrames) snap_.recent.push_back(*t);
    else snap_.recent[(frames_ - 1) % kRecentFrames] = *t;
    snap_.generation = s.generation;
    if (generation_changed) ++snap_.settings_changes;
    if (auto_f_generation_) snap_.auto_f = {auto_fx_, auto_fy_};
    snap_.output = std::move(output);
    const render::TargetMemory memory = comp_->memory();
    snap_.targets_mb = static_cast<double>(memory.total()) / (1024.0 * 1024.0);
    snap_.temporal_mb = static_cast<double>(memory.temporal) / (1024.0 * 1024.0);
    snap_.blend_layers = t->blend_layers;
    snap_.latency = latency_.json(output_->shown_clock());
    snap_.pacing = pacer_->json();
  }
  if (save) return save_frame();
  return {};
}

Status FrameRenderer::write_shown_rows() {
  std::vector<std::int64_t> shown = output_->take_shown();
  std::lock_guard lock(csv_mutex_);
  for (std::int64_t t : shown) {
    if (pending_.empty()) break;  // every shown time is a pending frame's; nothing is left over
    PendingRow row = std::move(pending_.front());
    pending_.pop_front();
    row.latency.shown_ns = t;
    last_shown_ = t;
    latency_.add(row.latency);
    pacer_->shown(row.latency.start_ns, row.ready_ns, t, row.latency.display_target_ns);
    // A row once the frame is on screen, readable in the temporary file while foveald runs.
    if (csv_closed_) continue;
    char blend[32];
    std::snprintf(blend, sizeof blend, ",%.3f", row.blend_ms);
    csv_->write(row.cells + row.latency.csv_cells() + blend + "\n");
    std::fflush(csv_->stream());
  }
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

std::string FrameRenderer::png_name(std::uint64_t frame) {
  char name[64];
  std::snprintf(name, sizeof name, "frame_%06" PRIu64 ".png", frame);
  return name;
}

Status FrameRenderer::check_png_targets(const std::string& out_dir, int save_every, std::uint64_t frames) {
  // The first frame's always; with --frames the last and every K-th are known too (a
  // bound keeps a huge --frames with a small K from checking millions of names).
  std::vector<std::uint64_t> known = {0};
  if (frames > 0) {
    known.push_back(frames - 1);
    if (save_every > 0 && frames / static_cast<std::uint64_t>(save_every) <= 100000)
      for (std::uint64_t f = static_cast<std::uint64_t>(save_every); f < frames; f += static_cast<std::uint64_t>(save_every))
        known.push_back(f);
  }
  for (std::uint64_t f : known)
    if (Status s = check_output_target(out_dir + "/" + png_name(f)); !s) return s;
  return {};
}

Status FrameRenderer::save_frame() {
  if (frames_ == 0 || saved_frame_ == frames_ - 1) return {};
  const std::string name = png_name(frames_ - 1);
  saved_frame_ = frames_ - 1;  // tried once: a frame that cannot be saved is not tried again at finish()
  if (Status s = image::save_png(out_dir_ + "/" + name, comp_->read_image()); !s) return s;
  std::lock_guard lock(snapshot_mutex_);
  snap_.saved.push_back(name);
  return {};
}

Status FrameRenderer::finish(bool save_last) {
  if (Status s = output_->finish(); !s) return s;
  if (Status s = write_shown_rows(); !s) return s;
  {
    std::lock_guard lock(snapshot_mutex_);
    snap_.output = output_->json();
    snap_.latency = latency_.json(output_->shown_clock());
    snap_.pacing = pacer_->json();
  }
  // frames.csv is committed even when the last frame cannot be saved.
  const Status saved = save_last ? save_frame() : Status{};
  std::lock_guard lock(csv_mutex_);
  if (csv_closed_) return saved;
  csv_closed_ = true;
  Status committed = csv_->commit();
  return saved ? committed : saved;
}

Status FrameRenderer::abandon() {
  std::lock_guard lock(csv_mutex_);
  if (csv_closed_) return {};
  csv_closed_ = true;
  return csv_->commit();
}

std::uint64_t FrameRenderer::frames() const {
  std::lock_guard lock(snapshot_mutex_);
  return snap_.frames;
}

std::size_t FrameRenderer::saved_frames() const {
  std::lock_guard lock(snapshot_mutex_);
  return snap_.saved.size();
}

nlohmann::json FrameRenderer::stats_json() const {
  std::lock_guard lock(snapshot_mutex_);
  const render::PassTimes med = render::median_pass_times(snap_.recent);
  nlohmann::json eyes;
  for (Eye e : kEyes) {
    const auto i = static_cast<std::size_t>(e);
    const auto& f = snap_.last_params.eyes[i];
    eyes[eye_name(e)] = {{"sigma", f.sigma}, {"fovea", {f.fovea_x, f.fovea_y}}, {"buffer", snap_.buffers[i]}};
  }
  return {{"frames", snap_.frames},
          {"scene", scene_name_},
          {"method", render::method_name(method_)},
          {"pipeline", render::pipeline_name(pipeline_)},
          {"temporal", snap_.last_params.temporal ? "on" : "off"},
          {"blend_at", render::blend_at_name(blend_at_)},
          {"size", size_},
          {"renderer", renderer_name_},
          {"output", snap_.output},
          {"settings_generation", snap_.generation},
          {"settings_changes_seen", snap_.settings_changes},
          {"auto_f", snap_.auto_f ? nlohmann::json({{"fx", snap_.auto_f->first}, {"fy", snap_.auto_f->second}})
                                  : nlohmann::json(nullptr)},
          {"last_frame", eyes},
          {"passes_ms_median", {{"shadow", med.shadow}, {"gbuffer", med.gbuffer}, {"mapping", med.mapping},
                                {"lighting", med.lighting}, {"inverse", med.inverse}, {"blend", med.blend},
                                {"gpu_total", med.gpu_total}, {"cpu_frame", med.cpu}}},
          {"targets_mb", snap_.targets_mb},
          {"temporal_history_mb", snap_.temporal_mb},
          {"blend_layers_last_frame", snap_.blend_layers},
          {"latch", o_.late_latch ? "late" : "early"},
          {"prediction", o_.prediction.enabled ? "on" : "off"},
          {"gaze_to_photon", snap_.latency},
          {"pacing", snap_.pacing},
          {"saved", snap_.saved}};
}

}  // namespace foveal::daemon
