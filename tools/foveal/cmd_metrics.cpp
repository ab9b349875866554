// foveal metrics: PSNR, SSIM and FPSNR of a test image against a reference, on a single
// image or a side-by-side stereo frame (docs/metrics.md).
#include <cmath>
#include <cstdio>
#include <memory>

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include "commands.hpp"
#include "foveal/image/metrics.hpp"
#include "foveal/tools/args.hpp"
#include "foveal/tools/cli.hpp"

namespace foveal::cmd {

namespace {

struct Args {
  std::string ref, test, fovea, fovea_right, ssim_channels = "luma";
  double ppd = image::kDefaultPixelsPerDegree;
  bool stereo = false, json = false;
};

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
  if (!img) return bad_input(std::string(what) + " " + img.error().message);
  return img;
}

int run(const Args& a) {
  image::MetricsOptions opt;
  auto fovea = parse_fovea(a.fovea, "--fovea");
  if (!fovea) return cli::report(fovea.error());
  opt.fovea = opt.fovea_right = *fovea;  // the same spot in each eye unless told
  if (!a.fovea_right.empty()) {
    if (!a.stereo) return cli::report(bad_input("--fovea-right: only with --stereo"));
    auto r = parse_fovea(a.fovea_right, "--fovea-right");
    if (!r) return cli::report(r.error());
    opt.fovea_right = *r;
  }
  if (!std::isfinite(a.ppd) || a.ppd <= 0) return cli::report(bad_input("--ppd: must be > 0, got " + std::to_string(a.ppd)));
  opt.ppd = a.ppd;
  opt.ssim_channels = a.ssim_channels == "rgb" ? image::SsimChannels::rgb : image::SsimChannels::luma;
  auto ref = load_named(a.ref, "--ref");
  if (!ref) return cli::report(ref.error());
  auto test = load_named(a.test, "--test");
  if (!test) return cli::report(test.error());
  if (ref->width != test->width || ref->height != test->height)
    return cli::report(bad_input(a.test + ": size " + std::to_string(test->width) + "x" + std::to_string(test->height) +
                                 " differs from the reference " + a.ref + " (" + std::to_string(ref->width) + "x" +
                                 std::to_string(ref->height) + ")"));

  nlohmann::json j = {{"ref", a.ref}, {"test", a.test}, {"size", {ref->width, ref->height}}, {"stereo", a.stereo},
                      {"ppd", opt.ppd}, {"ssim_channels", a.ssim_channels}};
  if (a.stereo) {
    auto m = image::compute_stereo_metrics(*ref, *test, opt);
    if (!m) return cli::report(m.error());
    if (a.json) {
      j["fovea_left"] = {opt.fovea.x, opt.fovea.y};
      j["fovea_right"] = {opt.fovea_right.x, opt.fovea_right.y};
      j.update(to_json(m->combined));
      j["left"] = to_json(m->left);
      j["right"] = to_json(m->right);
      cli::print_json(j);
    } else {
      std::printf("%s vs %s (%dx%d stereo, %.2f ppd, fovea L %.3f,%.3f R %.3f,%.3f)\n", a.test.c_str(), a.ref.c_str(),
                  ref->width, ref->height, opt.ppd, opt.fovea.x, opt.fovea.y, opt.fovea_right.x, opt.fovea_right.y);
      print_line("left", m->left);
      print_line("right", m->right);
      print_line("combined", m->combined);
    }
  } else {
    auto m = image::compute_metrics(*ref, *test, opt);
    if (!m) return cli::report(m.error());
    if (a.json) {
      j["fovea"] = {opt.fovea.x, opt.fovea.y};
      j.update(to_json(*m));
      cli::print_json(j);
    } else {
      std::printf("%s vs %s (%dx%d, %.2f ppd, fovea %.3f,%.3f)\n", a.test.c_str(), a.ref.c_str(), ref->width,
                  ref->height, opt.ppd, opt.fovea.x, opt.fovea.y);
      print_line("image", *m);
    }
  }
  return cli::kExitOk;
}

}  // namespace

void add_metrics(CLI::App& app, int& exit_code) {
  auto args = std::make_shared<Args>();
  CLI::App* sub = app.add_subcommand("metrics", "PSNR, SSIM and foveated PSNR of a test image against a reference");
  sub->add_option("--ref,-r", args->ref, "Reference image (PNG, JPEG, BMP, TGA)")->required();
  sub->add_option("--test,-t", args->test, "Test image, same size")->required();
  sub->add_option("--fovea,--fovea-left", args->fovea,
                  "Fovea X,Y in [0,1] of the image (of the left half with --stereo), origin top-left")
      ->required();
  sub->add_option("--fovea-right", args->fovea_right, "With --stereo: the right half's fovea (default: --fovea)");
  sub->add_flag("--stereo", args->stereo, "Side-by-side stereo frame: each half is an eye with its own fovea");
  sub->add_option("--ppd", args->ppd, "Pixels per degree at the (eye) image centre")->capture_default_str();
  sub->add_option("--ssim-channels", args->ssim_channels, "SSIM on BT.601 luma, or the mean over R, G, B")
      ->check(CLI::IsMember({"luma", "rgb"}))
      ->capture_default_str();
  sub->add_flag("--json", args->json, "Print the metrics as JSON (infinite PSNR as \"inf\")");
  sub->callback([args, &exit_code] { exit_code = run(*args); });
}

}  // namespace foveal::cmd
