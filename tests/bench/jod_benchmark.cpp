// foveal_jod_bench: how long the native FovVideoVDP takes on a 2880×1600 stereo pair (each
// eye 1440×1600 on the Vive Pro Eye model, foveated), against PSNR + SSIM + FPSNR of the same
// pair in the same run. usage: foveal_jod_bench [REF.png TEST.png] [--threads N] [--runs N]
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>
#include <vector>

#include "foveal/image/metrics.hpp"
#include "foveal/perception/jod.hpp"

using namespace foveal;

namespace {

double now_s() {
  return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
}

// A textured frame: sums of gratings, so every band carries contrast.
image::Image synthetic(int w, int h, int shift) {
  image::Image img(w, h);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      const double v = 128 + 50 * std::sin((x + shift) * 0.31) * std::cos(y * 0.17) + 40 * std::sin((x * 0.05 + y * 0.07));
      std::uint8_t* p = img.at(x, y);
      for (int c = 0; c < 3; ++c) p[c] = static_cast<std::uint8_t>(std::clamp(v + c * 9, 0.0, 255.0));
      p[3] = 255;
    }
  return img;
}

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  return v[v.size() / 2];
}

}  // namespace

int main(int argc, char** argv) {
  int threads = 2, runs = 5;
  std::vector<std::string> files;
  for (int i = 1; i < argc; ++i) {
    if (!std::strcmp(argv[i], "--threads") && i + 1 < argc) threads = std::atoi(argv[++i]);
    else if (!std::strcmp(argv[i], "--runs") && i + 1 < argc) runs = std::atoi(argv[++i]);
    else files.push_back(argv[i]);
  }
  image::Image ref, test;
  if (files.size() == 2) {
    auto r = image::load(files[0]);
    auto t = image::load(files[1]);
    if (!r || !t) {
      std::fprintf(stderr, "foveal_jod_bench: %s\n", (!r ? r.error() : t.error()).message.c_str());
      return 2;
    }
    ref = *r;
    test = *t;
  } else {
    ref = synthetic(2880, 1600, 0);
    test = synthetic(2880, 1600, 1);
  }
  const int w = ref.width / 2, h = ref.height;
  const DisplayModel vive = DisplayModel::vive_pro_eye();
  std::vector<perception::JodMetric> eyes;
  const double t_setup = now_s();
  for (Eye e : {Eye::left, Eye::right}) {
    perception::Parameters p;
    eyes.emplace_back(perception::eye_geometry(vive, e, w, h), perception::Photometry{}, p, threads);
  }
  const double setup = now_s() - t_setup;
  const image::Image ref_l = image::crop(ref, {0, 0, w, h}), ref_r = image::crop(ref, {w, 0, w, h});
  const image::Image test_l = image::crop(test, {0, 0, w, h}), test_r = image::crop(test, {w, 0, w, h});
  std::vector<double> t_jod, t_base;
  double jod_l = 0, jod_r = 0;
  for (int k = 0; k < runs; ++k) {
    double t0 = now_s();
    auto l = eyes[0].still(ref_l, test_l, perception::Fixation{0.4 * w, 0.5 * h});
    auto r = eyes[1].still(ref_r, test_r, perception::Fixation{0.6 * w, 0.5 * h});
    t_jod.push_back(now_s() - t0);
    if (!l || !r) return 1;
    jod_l = l->jod;
    jod_r = r->jod;
    t0 = now_s();
    image::MetricsOptions o;
    auto m = image::compute_stereo_metrics(ref, test, o);
    t_base.push_back(now_s() - t0);
    if (!m) return 1;
  }
  std::printf("JOD of a %dx%d stereo pair (%dx%d per eye, Vive Pro Eye, foveated), %d thread%s, median of %d:\n",
              ref.width, ref.height, w, h, threads, threads == 1 ? "" : "s", runs);
  std::printf("  JOD both eyes        %.3f s   (left %.4f, right %.4f JOD; setup %.3f s, once per display)\n",
              median(t_jod), jod_l, jod_r, setup);
  std::printf("  PSNR+SSIM+FPSNR      %.3f s   (compute_stereo_metrics, one thread)\n", median(t_base));
  std::printf("  ratio JOD / PSNR+SSIM+FPSNR  %.2f\n", median(t_jod) / median(t_base));
  return 0;
}
