#include "jod_cases.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>

#include "foveal/image/foveate.hpp"

namespace foveal::test {

namespace {

using image::Image;
using perception::NormFovea;

constexpr int kFrames = 20;
constexpr double kFps = 90;
constexpr int kW = 384, kH = 224;

std::uint8_t clamp8(double v) { return static_cast<std::uint8_t>(std::lround(std::clamp(v, 0.0, 255.0))); }

Result<Image> render(const std::string& dir, const std::string& name) {
  auto img = image::load(dir + "/" + name + ".png");
  if (!img) return img.error();
  return img;
}

// Each R, G, B value through f(value, x, y, channel).
template <class F>
Image per_value(const Image& in, F f) {
  Image out = in;
  for (int y = 0; y < in.height; ++y)
    for (int x = 0; x < in.width; ++x)
      for (int c = 0; c < 3; ++c) out.at(x, y)[c] = clamp8(f(static_cast<double>(in.at(x, y)[c]), x, y, c));
  return out;
}

// Uniform noise in ±amp from a 32-bit LCG seeded with `seed`, the same value on R, G, B;
// only where inside(x, y).
template <class In>
Image noise(const Image& in, double amp, std::uint32_t seed, In inside) {
  Image out = in;
  std::uint32_t s = seed;
  for (int y = 0; y < in.height; ++y)
    for (int x = 0; x < in.width; ++x) {
      s = s * 1664525u + 1013904223u;
      const double n = (static_cast<double>(s >> 8) / 16777216.0 * 2.0 - 1.0) * amp;
      if (!inside(x, y)) continue;
      for (int c = 0; c < 3; ++c) out.at(x, y)[c] = clamp8(in.at(x, y)[c] + n);
    }
  return out;
}
Image noise(const Image& in, double amp, std::uint32_t seed) {
  return noise(in, amp, seed, [](int, int) { return true; });
}

// Separable Gaussian of `sigma` pixels on the 8-bit values, radius ceil(3 sigma), edges
// mirrored.
Image blur(const Image& in, double sigma) {
  const int r = static_cast<int>(std::ceil(3 * sigma));
  std::vector<double> k(static_cast<std::size_t>(2 * r + 1));
  double sum = 0;
  for (int i = -r; i <= r; ++i) sum += k[static_cast<std::size_t>(i + r)] = std::exp(-i * i / (2 * sigma * sigma));
  for (double& v : k) v /= sum;
  const auto mirror = [](int i, int n) { return i < 0 ? -i - 1 : (i >= n ? 2 * n - 1 - i : i); };
  const int w = in.width, h = in.height;
  std::vector<double> tmp(static_cast<std::size_t>(w) * static_cast<std::size_t>(h) * 3);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x)
      for (int c = 0; c < 3; ++c) {
        double s = 0;
        for (int i = -r; i <= r; ++i) s += k[static_cast<std::size_t>(i + r)] * in.at(mirror(x + i, w), y)[c];
        tmp[(static_cast<std::size_t>(y) * static_cast<std::size_t>(w) + static_cast<std::size_t>(x)) * 3 + static_cast<std::size_t>(c)] = s;
      }
  Image out = in;
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x)
      for (int c = 0; c < 3; ++c) {
        double s = 0;
        for (int i = -r; i <= r; ++i)
          s += k[static_cast<std::size_t>(i + r)] *
               tmp[(static_cast<std::size_t>(mirror(y + i, h)) * static_cast<std::size_t>(w) + static_cast<std::size_t>(x)) * 3 +
                   static_cast<std::size_t>(c)];
        out.at(x, y)[c] = clamp8(s);
      }
  return out;
}

Result<Image> rmfr(const Image& in, double sigma, NormFovea g) {
  image::FoveateParams p;
  p.sigma = sigma;
  p.fovea_x = g.x;
  p.fovea_y = g.y;
  auto r = image::foveate(in, p);
  if (!r) return r.error();
  return r->output;
}

// A still: the reference and a test image scored at one fovea or none.
JodCaseRecipe still(std::string name, std::optional<NormFovea> fovea,
                    std::function<Result<Image>(const std::string&, const Image&)> make_test) {
  return {name, [=](const std::string& dir) -> Result<JodCase> {
            auto ref = render(dir, "full");
            if (!ref) return ref.error();
            auto test = make_test(dir, *ref);
            if (!test) return test.error();
            JodCase c;
            c.name = name;
            c.fovea = {fovea};
            c.ref = {*ref};
            c.test = {*test};
            return c;
          }};
}

JodCaseRecipe render_still(const std::string& render_name, const std::string& tag, std::optional<NormFovea> fovea) {
  return still(render_name + tag, fovea, [render_name](const std::string& dir, const Image&) { return render(dir, render_name); });
}

// A 20-frame video at 90 Hz: frame k of the reference is a 384×224 window of the wide render
// `pan` pixels per frame to the right; the test makes frame k from it.
JodCaseRecipe video(std::string name, int pan, std::function<std::optional<NormFovea>(int)> fovea,
                    std::function<Result<Image>(const Image& ref_frame, int k, const std::vector<Image>& refs)> make_test) {
  return {name, [=](const std::string& dir) -> Result<JodCase> {
            auto wide = render(dir, "full_wide");
            if (!wide) return wide.error();
            JodCase c;
            c.name = name;
            c.fps = kFps;
            for (int k = 0; k < kFrames; ++k) c.ref.push_back(image::crop(*wide, {pan * k, 0, kW, kH}));
            for (int k = 0; k < kFrames; ++k) {
              auto t = make_test(c.ref[static_cast<std::size_t>(k)], k, c.ref);
              if (!t) return t.error();
              c.test.push_back(std::move(*t));
              c.fovea.push_back(fovea(k));
            }
            return c;
          }};
}

}  // namespace

std::vector<JodCaseRecipe> jod_case_recipes() {
  const NormFovea c{0.5, 0.5};
  const std::optional<NormFovea> none;
  std::vector<JodCaseRecipe> r;
  // foveal's methods rendered through the GL pipeline (render_inputs.sh), at their gaze and not.
  for (const char* m : {"rmfr_s1.5_c", "rmfr_s3_c", "kfr_s2_c", "hyperbolic_s2_c", "uniform_s2"}) {
    r.push_back(render_still(m, "@c", c));
    r.push_back(render_still(m, "@none", none));
  }
  r.push_back(render_still("rmfr_s2_g25_40", "@g25_40", NormFovea{0.25, 0.4}));
  r.push_back(render_still("rmfr_s2_g25_40", "@g75_60", NormFovea{0.75, 0.6}));
  r.push_back(render_still("rmfr_s2_g25_40", "@none", none));
  // RMFR in image space (foveal foveate) at levels and gazes.
  const NormFovea g1{0.2, 0.3}, g2{0.8, 0.7};
  for (double s : {1.5, 2.5, 4.0})
    for (NormFovea g : {c, g1}) {
      const std::string name = "foveate_s" + std::to_string(s).substr(0, 3) + (g.x == 0.5 ? "@c" : "@g20_30");
      r.push_back(still(name, g, [s, g](const std::string&, const Image& ref) { return rmfr(ref, s, g); }));
    }
  r.push_back(still("foveate_s2.5_g20_30@g80_70", g2, [g1](const std::string&, const Image& ref) { return rmfr(ref, 2.5, g1); }));
  // Blur, noise, contrast.
  for (double s : {0.7, 1.5, 3.0})
    r.push_back(still("blur_" + std::to_string(s).substr(0, 3) + "@c", c, [s](const std::string&, const Image& ref) -> Result<Image> { return blur(ref, s); }));
  r.push_back(still("blur_1.5@none", none, [](const std::string&, const Image& ref) -> Result<Image> { return blur(ref, 1.5); }));
  for (double a : {3.0, 8.0, 20.0})
    r.push_back(still("noise_" + std::to_string(static_cast<int>(a)) + "@c", c,
                      [a](const std::string&, const Image& ref) -> Result<Image> { return noise(ref, a, 7); }));
  r.push_back(still("noise_8@none", none, [](const std::string&, const Image& ref) -> Result<Image> { return noise(ref, 8, 7); }));
  r.push_back(still("noise_16_left_strip@g85_50", NormFovea{0.85, 0.5}, [](const std::string&, const Image& ref) -> Result<Image> {
    return noise(ref, 16, 11, [](int x, int) { return x < 96; });
  }));
  r.push_back(still("contrast_0.8@c", c, [](const std::string&, const Image& ref) -> Result<Image> {
    return per_value(ref, [](double v, int, int, int) { return 128 + 0.8 * (v - 128); });
  }));

  // Videos.
  const auto at = [](std::optional<NormFovea> g) { return [g](int) { return g; }; };
  r.push_back(video("v_pan_foveate_s2@c", 3, at(c), [c](const Image& f, int, const std::vector<Image>&) { return rmfr(f, 2, c); }));
  r.push_back(video("v_pan_foveate_s3@c", 3, at(c), [c](const Image& f, int, const std::vector<Image>&) { return rmfr(f, 3, c); }));
  const auto moving = [](int k) { return std::optional<NormFovea>(NormFovea{0.3 + 0.02 * k, 0.5}); };
  r.push_back(video("v_pan_foveate_s2@moving", 3, moving, [moving](const Image& f, int k, const std::vector<Image>&) {
    return rmfr(f, 2, *moving(k));
  }));
  for (double a : {0.03, 0.08})
    r.push_back(video("v_pan_flicker_" + std::to_string(a).substr(0, 4) + "@c", 3, at(c), [a](const Image& f, int k, const std::vector<Image>&) -> Result<Image> {
      const double g = 1 + (k % 2 ? a : -a);
      return per_value(f, [g](double v, int, int, int) { return v * g; });
    }));
  r.push_back(video("v_pan_flicker_0.08@none", 3, at(none), [](const Image& f, int k, const std::vector<Image>&) -> Result<Image> {
    const double g = k % 2 ? 1.08 : 0.92;
    return per_value(f, [g](double v, int, int, int) { return v * g; });
  }));
  r.push_back(video("v_still_flicker30hz_0.05@c", 0, at(c), [](const Image& f, int k, const std::vector<Image>&) -> Result<Image> {
    const double g = k % 3 == 2 ? 0.95 : 1.0;
    return per_value(f, [g](double v, int, int, int) { return v * g; });
  }));
  r.push_back(video("v_pan_dynamic_noise_6@c", 3, at(c), [](const Image& f, int k, const std::vector<Image>&) -> Result<Image> {
    return noise(f, 6, 100u + static_cast<std::uint32_t>(k));
  }));
  r.push_back(video("v_pan_dynamic_noise_6@none", 3, at(none), [](const Image& f, int k, const std::vector<Image>&) -> Result<Image> {
    return noise(f, 6, 100u + static_cast<std::uint32_t>(k));
  }));
  r.push_back(video("v_pan_static_noise_6@c", 3, at(c), [](const Image& f, int, const std::vector<Image>&) -> Result<Image> {
    return noise(f, 6, 5);
  }));
  r.push_back(video("v_pan_blur_1.5@c", 3, at(c), [](const Image& f, int, const std::vector<Image>&) -> Result<Image> { return blur(f, 1.5); }));
  r.push_back(video("v_pan_judder@c", 3, at(c), [](const Image&, int k, const std::vector<Image>& refs) -> Result<Image> {
    return refs[static_cast<std::size_t>(k - k % 2)];  // every other frame repeated: 45 Hz content
  }));
  r.push_back(video("v_fast_pan_judder@none", 3, at(none), [](const Image&, int k, const std::vector<Image>& refs) -> Result<Image> {
    return refs[static_cast<std::size_t>(k - k % 3)];
  }));
  return r;
}

}  // namespace foveal::test
