#include "render/render_args.hpp"

#include <cmath>
#include <cstdlib>

#include <CLI/CLI.hpp>

#include "foveal/core/data_paths.hpp"
#include "foveal/image/foveation_plan.hpp"
#include "foveal/runtime/args.hpp"
#include "render/render_head.hpp"

namespace foveal::cmd {

std::string default_scene() { return data_path("data/scenes/Dungeon/dungeon_simplified.gltf"); }

void add_render_options(CLI::App& sub, RenderArgs& a) {
  sub.add_option("--scene", a.scene, "glTF file or pattern:NAME[@DEG] (checker, stripes-h, stripes-v, noise); default: the bundled Dungeon");
  sub.add_option("--variant", a.variant,
                 "KHR_materials_variants variant to draw (by name); default: the file's default materials");
  sub.add_option("--method", a.method, "One of " + render::method_names_joined(", ") + " (full: the reference)")
      ->check(CLI::IsMember(render::method_names()))
      ->capture_default_str();
  sub.add_option("--pipeline", a.pipeline, "gbuffer or visibility: how surface samples are made (docs/rmfr.md, \"Pipelines\")")
      ->check(CLI::IsMember(render::pipeline_names()))
      ->capture_default_str();
  sub.add_option("--temporal", a.temporal,
                 "on or off: foveated temporal accumulation, RMFR in the visibility pipeline (docs/rmfr.md, \"Temporal "
                 "accumulation\"); every frame rendered accumulates")
      ->check(CLI::IsMember({"on", "off"}))
      ->capture_default_str();
  sub.add_option("--blend-at", a.blend_at,
                 "output or samples: where alphaMode BLEND surfaces are shaded: at output resolution after the inverse pass, "
                 "or at the samples the method keeps, before it (visibility pipeline, foveated methods; "
                 "docs/rmfr.md, \"Transparency at the kept samples\")")
      ->check(CLI::IsMember(render::blend_at_names()))
      ->capture_default_str();
  sub.add_option("--sigma-d", a.sigma_d, "RMFR level of the dominant eye (>= 1)")->capture_default_str();
  sub.add_option("--sigma-nd", a.sigma_nd, "RMFR level of the other eye (>= sigma-d)")->capture_default_str();
  sub.add_option("--dominant", a.dominant, "Dominant eye")->check(CLI::IsMember({"left", "right"}))->capture_default_str();
  sub.add_option("--fx", a.fx, "RMFR f along x, a fraction of the eye's width (> 0)")->capture_default_str();
  sub.add_option("--fy", a.fy, "RMFR f along y, a fraction of the eye's height (> 0)")->capture_default_str();
  sub.add_option("--fovea-left", a.fovea_left,
                 "Left-eye fovea X,Y in [0,1], origin top-left of the eye's viewport (default: 0.5,0.5, or with --log the log's)");
  sub.add_option("--fovea-right", a.fovea_right, "Right-eye fovea X,Y in [0,1] (default as --fovea-left)");
  sub.add_option("--head", a.head,
                 "Head pose X,Y,Z,QW,QX,QY,QZ relative to the scene's view: metres and a unit quaternion, the runtime's "
                 "axes (x right, y up, -z forward; docs/conventions.md); default: the scene's view");
  sub.add_option("--log", a.log,
                 "Native gaze log with head pose: with --at, render with its head pose (relative to its first pose) and "
                 "filtered fovea at that time, as bench --gaze does");
  sub.add_option("--at", a.at, "With --log: seconds after the log's first sample");
  sub.add_option("--f", a.f, "auto: pick f_x, f_y from the content (overrides --fx/--fy; docs/methods.md)")
      ->check(CLI::IsMember({"auto"}));
  sub.add_option("--kfr-alpha", a.kfr_alpha, "KFR kernel exponent (> 0)")->capture_default_str();
  sub.add_option("--layer-scale", a.layer_scale,
                 "hyperbolic/linear: scale of the 10/20 degree thresholds (default: match the cost of sigma)");
  sub.add_option("--inset-deg", a.inset_deg,
                 "inset/inset-fixed: the inner view's half-extent in degrees (default 0: 35% of the view per axis)");
  sub.add_option("--inset-band-deg", a.inset_band_deg, "inset/inset-fixed: the inner view's blend band in degrees")
      ->capture_default_str();
  sub.add_option("--size", a.size, "Side-by-side output size WxH (even width)")->capture_default_str();
  sub.add_option("--display", a.display, "Display model: a name under data/display (htc_vive_pro_eye, hires_3800_35ppd) or a JSON file (default: htc_vive_pro_eye)");
  sub.add_flag("--no-distortion", a.no_distortion, "Ignore the display model's lens distortion (frames comparable with metrics)");
  sub.add_option("--light-lists", a.light_lists,
                 "The glTF file's own lights: tiles (each 16x16-pixel tile loops over the lights that reach it) or all "
                 "(every light at every sample); docs/scenes.md, \"Lights\"")
      ->check(CLI::IsMember({"tiles", "all"}))
      ->capture_default_str();
}

namespace {

// The head pose (--head, or --log at --at) and the foveae: an option's, else the log's,
// else the centre.
Status resolve_head(const RenderArgs& a, RenderSetup& s) {
  std::array<glm::dvec2, 2> fovea{glm::dvec2(0.5), glm::dvec2(0.5)};
  if (!a.head.empty() && !a.log.empty()) return bad_input("--head and --log: give one head pose, not both");
  if (!a.at.empty() && a.log.empty()) return bad_input("--at needs --log (the log whose time it is)");
  if (!a.head.empty()) {
    auto p = parse_head_pose(a.head, "--head");
    if (!p) return p.error();
    s.frame.head = *p;
    s.head.kind = "head";
  } else if (!a.log.empty()) {
    if (a.at.empty()) return bad_input("--log needs --at SECONDS (the time in the log to render)");
    char* end = nullptr;
    const double at = std::strtod(a.at.c_str(), &end);
    if (*end != '\0' || !std::isfinite(at)) return bad_input("--at: '" + a.at + "' is not a number of seconds");
    auto f = log_frame_at(a.log, at, s.compositor.model);
    if (!f) return f.error();
    s.frame.head = f->relative;
    fovea = f->fovea;
    s.head = {"log", a.log, at, f->sample_s, {"log", "log"}};
  }
  const std::pair<const std::string*, const char*> given[2] = {{&a.fovea_left, "--fovea-left"}, {&a.fovea_right, "--fovea-right"}};
  for (std::size_t i = 0; i < 2; ++i) {
    if (!given[i].first->empty()) {
      auto p = cli::parse_point(*given[i].first, given[i].second);
      if (!p) return p.error();
      if (p->first < 0 || p->first > 1 || p->second < 0 || p->second > 1)
        return bad_input(std::string(given[i].second) + ": X and Y must lie in [0,1], got '" + *given[i].first + "'");
      fovea[i] = {p->first, p->second};
      s.head.fovea[i] = "option";
    }
    s.frame.eyes[i].fovea_x = fovea[i].x;
    s.frame.eyes[i].fovea_y = fovea[i].y;
  }
  return {};
}

}  // namespace

Result<RenderSetup> resolve(const RenderArgs& a) {
  RenderSetup s;
  s.scene = a.scene.empty() ? default_scene() : a.scene;
  s.scene_options.variant = a.variant;
  auto method = render::parse_method(a.method);
  if (!method) return method.error();
  if (!(a.sigma_d >= 1.0)) return bad_input("--sigma-d must be >= 1");
  if (!(a.sigma_nd >= a.sigma_d)) return bad_input("--sigma-nd must be >= --sigma-d (EFR: the non-dominant eye is foveated at least as much)");
  if (!(a.fx > 0) || !(a.fy > 0)) return bad_input("--fx and --fy must be > 0");
  if (!(a.kfr_alpha > 0)) return bad_input("--kfr-alpha must be > 0");
  if (!(a.layer_scale >= 0)) return bad_input("--layer-scale must be >= 0");
  if (!(a.inset_deg >= 0 && a.inset_deg < 89)) return bad_input("--inset-deg must be in [0, 89) degrees");
  if (!(a.inset_band_deg >= 0 && a.inset_band_deg <= 45)) return bad_input("--inset-band-deg must be in [0, 45] degrees");
  const Eye dominant = a.dominant == "left" ? Eye::left : Eye::right;
  auto pipeline = render::parse_pipeline(a.pipeline);
  if (!pipeline) return Error{pipeline.error().kind, "--pipeline: " + pipeline.error().message};
  s.frame = render::efr_frame(*method, dominant, a.sigma_d, a.sigma_nd, a.fx, a.fy);
  s.frame.pipeline = *pipeline;
  s.frame.temporal = a.temporal == "on";
  auto blend_at = render::parse_blend_at(a.blend_at);
  if (!blend_at) return Error{blend_at.error().kind, "--blend-at: " + blend_at.error().message};
  s.frame.blend_at = *blend_at;
  if (Status c = render::check_blend_at(*blend_at, *pipeline); !c) return c.error();
  for (auto& e : s.frame.eyes)
    e.kfr_alpha = a.kfr_alpha, e.layer_scale = a.layer_scale, e.inset_deg = a.inset_deg, e.inset_band_deg = a.inset_band_deg;
  s.auto_f = a.f == "auto";
  auto size = cli::parse_size(a.size, "--size");
  if (!size) return size.error();
  if (size->first % 2 != 0) return bad_input("--size: the width must be even (two eyes side by side)");
  s.compositor.width = size->first;
  s.compositor.height = size->second;
  s.compositor.distortion = !a.no_distortion;
  s.compositor.light_tiles = a.light_lists == "tiles";
  if (!a.display.empty()) {
    auto m = DisplayModel::load(display_model_path(a.display));
    if (!m) return m.error();
    s.compositor.model = *m;
  }
  if (Status st = resolve_head(a, s); !st) return st.error();
  return s;
}

}  // namespace foveal::cmd
