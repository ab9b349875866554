// rmfr_deferred: an application's own deferred renderer, foveated with foveal-rmfr at
// the live fovea and EFR settings of a running foveald (foveal-client), headless.
//   rmfr_deferred --out FRAME.ppm [--full] [--live] [--sigma-d S --sigma-nd S]
//                 [--dominant left|right] [--fovea-left X,Y --fovea-right X,Y]
//                 [--fx F --fy F | --auto-f] [--size WxH] [--frames N]
// --live reads each frame's fovea and, unless given here, σ_d, σ_nd, the dominant eye and
// f from foveald (a negative f there: automatic f, from one full-resolution frame).
// Prints one JSON line: what each eye was rendered with. Exit 2: bad arguments or no
// foveald; 1: GL failed.
#include <foveal/client.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <optional>
#include <string>
#include <thread>

#include <foveal/rmfr.hpp>

#include "egl.hpp"
#include "renderer.hpp"

namespace {

struct Args {
  std::string out;
  bool full = false, live = false, auto_f = false;
  std::optional<double> sigma_d, sigma_nd, fx, fy;
  std::optional<int> dominant;
  std::array<foveal::rmfr::Fovea, 2> fovea{};
  int width = 480, height = 400, frames = 3;
};

int usage(const std::string& why) {
  std::fprintf(stderr, "rmfr_deferred: %s\n", why.c_str());
  return 2;
}

bool parse_pair(const char* s, double& a, double& b, char sep) {
  char* end = nullptr;
  a = std::strtod(s, &end);
  if (end == s || *end != sep) return false;
  const char* rest = end + 1;
  b = std::strtod(rest, &end);
  return end != rest && *end == '\0' && std::isfinite(a) && std::isfinite(b);
}

std::optional<Args> parse(int argc, char** argv, std::string& why) {
  Args a;
  for (int i = 1; i < argc; ++i) {
    const std::string k = argv[i];
    auto value = [&]() -> const char* { return i + 1 < argc ? argv[++i] : nullptr; };
    auto number = [&](std::optional<double>& to) {
      const char* v = value();
      char* end = nullptr;
      const double d = v ? std::strtod(v, &end) : NAN;
      if (!v || *end || !std::isfinite(d)) return why = k + " needs a number", false;
      return to = d, true;
    };
    double x = 0, y = 0;
    if (k == "--out" && value()) a.out = argv[i];
    else if (k == "--full") a.full = true;
    else if (k == "--live") a.live = true;
    else if (k == "--auto-f") a.auto_f = true;
    else if (k == "--sigma-d") { if (!number(a.sigma_d)) return {}; }
    else if (k == "--sigma-nd") { if (!number(a.sigma_nd)) return {}; }
    else if (k == "--fx") { if (!number(a.fx)) return {}; }
    else if (k == "--fy") { if (!number(a.fy)) return {}; }
    else if (k == "--dominant" && value()) {
      const std::string v = argv[i];
      if (v != "left" && v != "right") return why = "--dominant is left or right", std::nullopt;
      a.dominant = v == "left" ? 0 : 1;
    } else if ((k == "--fovea-left" || k == "--fovea-right") && value()) {
      if (!parse_pair(argv[i], x, y, ',')) return why = k + " needs X,Y (normalised, origin top-left)", std::nullopt;
      a.fovea[k == "--fovea-left" ? 0 : 1] = {x, y};
    } else if (k == "--size" && value()) {
      if (!parse_pair(argv[i], x, y, 'x') || x < 16 || y < 16 || x > 4096 || y > 4096)
        return why = "--size needs WxH, each in [16, 4096]", std::nullopt;
      a.width = int(x), a.height = int(y);
    } else if (k == "--frames" && value()) {
      a.frames = std::atoi(argv[i]);
      if (a.frames < 1) return why = "--frames needs a count >= 1", std::nullopt;
    } else {
      return why = "unknown or incomplete argument '" + k + "'", std::nullopt;
    }
  }
  if (a.out.empty()) return why = "--out FILE.ppm is required", std::nullopt;
  return a;
}

// The live source: foveald's block, waited for up to 10 s.
struct Live {
  foveal_client* client = nullptr;
  ~Live() { foveal_client_close(client); }
  std::string open() {
    foveal_error err{};
    for (int i = 0; i < 100 && !client; ++i) {
      client = foveal_client_open(nullptr, &err);
      if (!client) std::this_thread::sleep_for(std::chrono::milliseconds(100));
    }
    return client ? "" : std::string("no live fovea: ") + err.message;
  }
  // The latest fovea, normalised; waits while foveald has none yet.
  std::string read(std::array<foveal::rmfr::Fovea, 2>& out, std::uint64_t& frame) {
    foveal_fovea f{};
    int rc = FOVEAL_ERR_NO_DATA;
    for (int i = 0; i < 100 && (rc = foveal_client_read(client, &f)) == FOVEAL_ERR_NO_DATA; ++i)
      std::this_thread::sleep_for(std::chrono::milliseconds(100));
    if (rc != FOVEAL_OK) return std::string("fovea: ") + foveal_error_message(rc);
    for (int e = 0; e < 2; ++e) out[static_cast<std::size_t>(e)] = {f.x[e] / f.eye_width, f.y[e] / f.eye_height};
    frame = f.frame;
    return {};
  }
};

void write_ppm(const std::string& path, const std::vector<std::uint8_t>& rgba, int w, int h, std::string& error) {
  const std::string tmp = path + ".tmp";
  std::FILE* f = std::fopen(tmp.c_str(), "wb");
  if (!f) return void(error = tmp + ": " + std::strerror(errno));
  std::fprintf(f, "P6\n%d %d\n255\n", w, h);
  for (std::size_t i = 0; i < rgba.size(); i += 4) std::fwrite(&rgba[i], 1, 3, f);
  const bool ok = std::fflush(f) == 0 && std::ferror(f) == 0;
  std::fclose(f);
  if (!ok || std::rename(tmp.c_str(), path.c_str()) != 0) {
    std::remove(tmp.c_str());
    error = path + ": cannot write";
  }
}

}  // namespace

int main(int argc, char** argv) {
  std::string why;
  const auto args = parse(argc, argv, why);
  if (!args) return usage(why);
  Live live;
  foveal::rmfr::EfrSettings efr;
  std::array<foveal::rmfr::Fovea, 2> fovea = args->fovea;
  bool auto_f = false;
  if (args->live) {
    if (std::string e = live.open(); !e.empty()) return usage(e);
    foveal_settings s{};
    if (int rc = foveal_client_settings(live.client, &s); rc != FOVEAL_OK)
      return usage(std::string("settings: ") + foveal_error_message(rc));
    efr.sigma_d = s.sigma_d, efr.sigma_nd = s.sigma_nd, efr.dominant_eye = s.dominant_eye;
    auto_f = s.f_x < 0 || s.f_y < 0;
    if (!auto_f) efr.fx = s.f_x, efr.fy = s.f_y;
  }
  if (args->sigma_d) efr.sigma_d = *args->sigma_d;
  if (args->sigma_nd) efr.sigma_nd = *args->sigma_nd;
  if (args->dominant) efr.dominant_eye = *args->dominant;
  if (args->fx || args->fy) auto_f = false;
  if (args->auto_f) auto_f = true;
  if (args->fx) efr.fx = *args->fx;
  if (args->fy) efr.fy = *args->fy;

  if (std::string e = make_headless_gl_context(); !e.empty()) return usage(e);
  std::string error;
  auto renderer = Renderer::create(args->width, args->height, error);
  if (!renderer) return std::fprintf(stderr, "rmfr_deferred: %s\n", error.c_str()), 1;

  std::optional<std::array<foveal::rmfr::Plan, 2>> plans;
  std::uint64_t gaze_frame = 0;
  for (int frame = 0; frame < args->frames; ++frame) {
    if (args->live)
      if (std::string e = live.read(fovea, gaze_frame); !e.empty()) return usage(e);
    if (!args->full) {
      if (auto_f && frame == 0) {  // f from one full-resolution frame at these foveae
        if (std::string e = renderer->render(std::nullopt); !e.empty()) return std::fprintf(stderr, "rmfr_deferred: %s\n", e.c_str()), 1;
        const std::vector<std::uint8_t> px = renderer->read_rgba();
        const foveal::rmfr::Frustum fr = renderer->frustum();
        const double ppd = args->width / (fr.tan_right - fr.tan_left) * M_PI / 180.0;
        const bool left_dominant = efr.dominant_eye == 0;
        const std::array<double, 2> sigma = {left_dominant ? efr.sigma_d : efr.sigma_nd, left_dominant ? efr.sigma_nd : efr.sigma_d};
        auto f = foveal::rmfr::estimate_f({px.data(), 2 * args->width, args->height, 0, false}, sigma, fovea, ppd);
        if (!f) return usage(f.error().message);
        efr.fx = f->fx, efr.fy = f->fy;
      }
      std::array<foveal::rmfr::EyeParams, 2> eyes;
      for (int e = 0; e < 2; ++e) {
        auto& p = eyes[static_cast<std::size_t>(e)];
        p.width = args->width, p.height = args->height, p.fovea = fovea[static_cast<std::size_t>(e)];
        p.frustum = renderer->frustum();
      }
      auto planned = foveal::rmfr::plan_efr(efr, eyes);
      if (!planned) return usage(planned.error().message);
      plans = *planned;
    }
    if (std::string e = renderer->render(plans); !e.empty()) return std::fprintf(stderr, "rmfr_deferred: %s\n", e.c_str()), 1;
  }
  write_ppm(args->out, renderer->read_rgba(), 2 * args->width, args->height, error);
  if (!error.empty()) return std::fprintf(stderr, "rmfr_deferred: %s\n", error.c_str()), 1;

  std::printf("{\"out\": \"%s\", \"mode\": \"%s\", \"live\": %s, \"gaze_frame\": %llu, \"rmfr\": \"%s\", \"eyes\": [", args->out.c_str(),
              args->full ? "full" : "rmfr", args->live ? "true" : "false", static_cast<unsigned long long>(gaze_frame),
              foveal::rmfr::version());
  for (int e = 0; e < 2; ++e) {
    const auto& f = fovea[static_cast<std::size_t>(e)];
    const int w = plans ? (*plans)[static_cast<std::size_t>(e)].buffer_w : args->width;
    const int h = plans ? (*plans)[static_cast<std::size_t>(e)].buffer_h : args->height;
    const double sigma = plans ? (*plans)[static_cast<std::size_t>(e)].sigma : 1.0;
    std::printf("%s{\"fovea\": [%.6f, %.6f], \"sigma\": %g, \"buffer\": [%d, %d]}", e ? ", " : "", f.x, f.y, sigma, w, h);
  }
  std::printf("], \"dominant\": %d, \"f\": [%g, %g]}\n", efr.dominant_eye, efr.fx, efr.fy);
  return 0;
}
