// The model of FovVideoVDP (docs/metrics.md, "JOD"), written from the paper's description;
// fitted values from parameters.hpp, the CSF from csf.cpp, the pyramid from pyramid.cpp.
#include "foveal/perception/jod.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <exception>
#include <string>
#include <thread>

#include "foveal/perception/csf.hpp"
#include "foveal/perception/pyramid.hpp"

namespace foveal::perception {

namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr double kDeg = 180.0 / kPi;
constexpr int kMaxBands = 14;

double srgb_to_linear(double v) { return v > 0.04045 ? std::pow((v + 0.055) / 1.055, 2.4) : v / 12.92; }

// One band's view directions: the visual angle of each column and row (degrees, about the
// principal point) and, for foveated scoring, log2 of the band's frequency on the retina.
struct BandGeometry {
  int width = 0, height = 0;
  float log2_rho = 0;                 ///< the band's frequency at the principal point
  std::vector<float> angle_x, angle_y;
  Plane log2_rho_off_axis;            ///< frequency scaled by the local pixels per degree
};

// fn(begin, end, part) over [0, n) in `threads` contiguous parts, part 0 on this thread.
// An exception in any part (bad_alloc on a large frame) is thrown here once all have
// joined: in a worker it would call std::terminate.
template <class F>
void parallel_for(int threads, int n, F fn) {
  const int t = std::max(1, std::min(threads, n));
  std::vector<std::exception_ptr> failed(static_cast<std::size_t>(t));
  const auto part = [&](int i) {
    try {
      fn(n * i / t, n * (i + 1) / t, i);
    } catch (...) {
      failed[static_cast<std::size_t>(i)] = std::current_exception();
    }
  };
  std::vector<std::thread> pool;
  pool.reserve(static_cast<std::size_t>(t - 1));  // before any thread: no throw with one running
  int started = 1;
  for (; started < t; ++started) {
    try {
      pool.emplace_back(part, started);
    } catch (...) {
      break;  // no thread to be had (memory short: system_error or bad_alloc): this one does the rest
    }
  }
  part(0);
  for (int i = started; i < t; ++i) part(i);
  for (auto& th : pool) th.join();
  for (const auto& e : failed)
    if (e) std::rethrow_exception(e);
}

}  // namespace

struct JodMetric::Impl {
  EyeGeometry geometry;
  Photometry photometry;
  Parameters p;
  double ppd = 0;
  int bands = 0;                       ///< bands scored (the base band is not)
  std::vector<BandGeometry> band;
  std::shared_ptr<const CsfTable> csf_sustained, csf_transient;
  std::array<std::array<float, 256>, 3> lum_lut{};  ///< R, G, B code -> its share of Y (cd/m²)
  float log2_sensitivity_gain = 0, log2_mask_gain = 0;
  int threads = 1;

  Impl(EyeGeometry g, Photometry ph, Parameters par, int n_threads)
      : geometry(g), photometry(ph), p(par), ppd(g.ppd()),
        csf_sustained(shared_csf_table(0.0, par.csf_sigma, par.k_cm)),
        csf_transient(shared_csf_table(par.transient_omega_hz, par.csf_sigma, par.k_cm)) {
    // Bands: the first at Nyquist, then 0.3228·Nyquist halving, down to 0.5 cpd and at
    // most log2(min size) - 1 of them.
    // Nothing to score on an image under 2×2 (or on a degenerate geometry).
    const int min_side = std::min(g.width, g.height);
    const int max_levels =
        min_side >= 2 && std::isfinite(ppd) && ppd > 0 ? static_cast<int>(std::floor(std::log2(min_side))) - 1 : 0;
    std::vector<double> freq;
    freq.push_back(ppd / 2);
    for (int k = 0; k < kMaxBands; ++k) freq.push_back(0.3228 * std::pow(2.0, -k) * ppd / 2);
    int first_low = max_levels;
    for (int k = 0; k < static_cast<int>(freq.size()); ++k)
      if (freq[static_cast<std::size_t>(k)] <= 0.5) {
        first_low = k;
        break;
      }
    bands = std::clamp(first_low + 1, 0, std::max(max_levels, 0));
    // Pixels per degree off axis relative to the centre (a pixel's angular size shrinks as
    // tan grows): at visual angle a, (tan(a + δ) - tan a) / tan δ with δ half a pixel (the
    // angle a is the length of the per-axis angles, as the reference takes it).
    const double half_px_deg = 0.5 / ppd;
    const double tan_half = std::tan(half_px_deg / kDeg);
    int w = g.width, h = g.height;
    for (int b = 0; b < bands; ++b) {
      BandGeometry bg;
      bg.width = w;
      bg.height = h;
      bg.log2_rho = static_cast<float>(std::log2(freq[static_cast<std::size_t>(b)]));
      for (int x = 0; x < w; ++x)
        bg.angle_x.push_back(static_cast<float>(std::atan(((x + 0.5) * g.width / w - g.cx) / g.focal_px) * kDeg));
      for (int y = 0; y < h; ++y)
        bg.angle_y.push_back(static_cast<float>(std::atan(((y + 0.5) * g.height / h - g.cy) / g.focal_px) * kDeg));
      bg.log2_rho_off_axis = Plane(w, h);
      for (int y = 0; y < h; ++y) {
        float* o = bg.log2_rho_off_axis.row(y);
        for (int x = 0; x < w; ++x) {
          const double ax = bg.angle_x[static_cast<std::size_t>(x)], ay = bg.angle_y[static_cast<std::size_t>(y)];
          // (tan(a + δ) - tan a) / tan δ = (1 + tan² a) / (1 - tan a · tan δ): one tan.
          const double ta = std::tan(std::min(std::sqrt(ax * ax + ay * ay), 89.9) / kDeg);
          const double mag = (1.0 + ta * ta) / (1.0 - ta * tan_half);
          o[x] = static_cast<float>(std::log2(freq[static_cast<std::size_t>(b)] * mag));
        }
      }
      band.push_back(std::move(bg));
      w = (w + 1) / 2;
      h = (h + 1) / 2;
    }
    const double luma[3] = {0.2126729, 0.7151522, 0.0721750};  // sRGB primaries' Y
    for (int c = 0; c < 3; ++c)
      for (int v = 0; v < 256; ++v)
        lum_lut[static_cast<std::size_t>(c)][static_cast<std::size_t>(v)] = static_cast<float>(
            luma[c] * ((ph.peak_cd_m2 - ph.black_cd_m2) * srgb_to_linear(v / 255.0) + ph.black_cd_m2));
    log2_sensitivity_gain = static_cast<float>(p.sensitivity_correction_db / 20.0 * std::log2(10.0));
    log2_mask_gain = static_cast<float>(p.mask_c * std::log2(10.0));
    threads = std::max(1, n_threads);
  }

  Plane luminance(const image::Image& img) const {
    Plane out(img.width, img.height);
    const std::uint8_t* s = img.rgba.data();
    for (float& o : out.v) {
      o = lum_lut[0][s[0]] + lum_lut[1][s[1]] + lum_lut[2][s[2]];
      s += 4;
    }
    return out;
  }

  // The pooled difference of one frame per temporal channel and band, q[c][b]: channels
  // are (test, reference) pairs, sustained first; the first reference sets adaptation.
  void score_frame(const std::vector<const Plane*>& ch, const std::optional<Fixation>& fix,
                   std::vector<std::vector<double>>& q) const {
    const int n = static_cast<int>(ch.size());
    const std::size_t n_temporal = ch.size() / 2;
    std::vector<std::vector<Plane>> gauss(static_cast<std::size_t>(n));
    parallel_for(threads, n, [&](int c0, int c1, int) {
      for (int c = c0; c < c1; ++c) {
        auto& g = gauss[static_cast<std::size_t>(c)];
        g.push_back(*ch[static_cast<std::size_t>(c)]);
        for (int b = 0; b < bands; ++b) g.push_back(pyramid_reduce(g.back()));
      }
    });
    float gaze_x = 0, gaze_y = 0;
    if (fix) {
      gaze_x = static_cast<float>(std::atan((fix->x - geometry.cx) / geometry.focal_px) * kDeg);
      gaze_y = static_cast<float>(std::atan((fix->y - geometry.cy) / geometry.focal_px) * kDeg);
    }
    const float sqrt_ecc_max = static_cast<float>(std::sqrt(120.0));
    const float log2_d_max = static_cast<float>(std::log2(1e4));
    const float mask_p = static_cast<float>(p.mask_p), beta = static_cast<float>(p.beta);
    const float mask_q[2] = {static_cast<float>(p.mask_q_sustained), static_cast<float>(p.mask_q_transient)};
    q.assign(n_temporal, std::vector<double>(static_cast<std::size_t>(bands), 0.0));
    std::vector<Plane> expanded(static_cast<std::size_t>(n));
    for (int b = 0; b < bands; ++b) {
      const BandGeometry& bg = band[static_cast<std::size_t>(b)];
      parallel_for(threads, n, [&](int c0, int c1, int) {
        for (int c = c0; c < c1; ++c)
          expanded[static_cast<std::size_t>(c)] =
              pyramid_expand(gauss[static_cast<std::size_t>(c)][static_cast<std::size_t>(b) + 1], bg.width, bg.height);
      });
      // A Laplacian band's amplitude is half a grating's except in the finest band.
      const float mult = b == 0 ? 1.0f : 2.0f;
      std::vector<std::array<double, 2>> part(static_cast<std::size_t>(threads), {0.0, 0.0});
      parallel_for(threads, bg.height, [&](int y0, int y1, int slot) {
        std::array<double, 2> acc{0.0, 0.0};
        for (int y = y0; y < y1; ++y) {
          const float ay = bg.angle_y[static_cast<std::size_t>(y)] - gaze_y;
          const float* l_ref = expanded[1].row(y);
          const float* rho_row = bg.log2_rho_off_axis.row(y);
          const std::size_t row0 = static_cast<std::size_t>(y) * static_cast<std::size_t>(bg.width);
          std::array<double, 2> row_acc{0.0, 0.0};
          for (int x = 0; x < bg.width; ++x) {
            const float l_bkg = std::max(l_ref[x], 0.1f);
            const float log2_l = std::log2(l_bkg);
            float log2_rho = bg.log2_rho, sqrt_ecc = 0;
            if (fix) {
              const float ax = bg.angle_x[static_cast<std::size_t>(x)] - gaze_x;
              sqrt_ecc = std::min(std::sqrt(std::sqrt(ax * ax + ay * ay)), sqrt_ecc_max);
              log2_rho = rho_row[x];
            }
            const std::size_t i = row0 + static_cast<std::size_t>(x);
            for (std::size_t t = 0; t < n_temporal; ++t) {
              const CsfTable& csf = t == 0 ? *csf_sustained : *csf_transient;
              const float log2_s = csf.log2_sensitivity(log2_rho, log2_l, sqrt_ecc) + log2_sensitivity_gain;
              const float ct = std::min((gauss[2 * t][static_cast<std::size_t>(b)].v[i] - expanded[2 * t].v[i]) / l_bkg, 1000.0f) * mult;
              const float cr = std::min((gauss[2 * t + 1][static_cast<std::size_t>(b)].v[i] - expanded[2 * t + 1].v[i]) / l_bkg, 1000.0f) * mult;
              // In log2: D = |S (ct - cr)|^p / (1 + (g S min(|ct|, |cr|))^q), at most 1e4.
              const float log2_m = std::log2(std::min(std::abs(ct), std::abs(cr))) + log2_s + log2_mask_gain;
              float log2_d = mask_p * (std::log2(std::abs(ct - cr)) + log2_s) - std::log2(1.0f + std::exp2(mask_q[t] * log2_m));
              log2_d = std::min(log2_d, log2_d_max);
              row_acc[t] += static_cast<double>(std::exp2(beta * log2_d));
            }
          }
          for (std::size_t t = 0; t < n_temporal; ++t) acc[t] += row_acc[t];
        }
        part[static_cast<std::size_t>(slot)] = acc;
      });
      const double count = static_cast<double>(bg.width) * bg.height;
      for (std::size_t t = 0; t < n_temporal; ++t) {
        double sum = 0;
        for (const auto& a : part) sum += a[t];
        q[t][static_cast<std::size_t>(b)] = std::pow(sum / count, 1.0 / p.beta);
      }
    }
  }

  // One frame's difference: bands summed per temporal channel, the channels p-normed.
  double pool_frame(const std::vector<std::vector<double>>& q) const {
    if (q.size() == 1) {
      double s = 0;
      for (double v : q[0]) s += v;
      return s;
    }
    double total = 0;
    for (std::size_t t = 0; t < q.size(); ++t) {
      double s = 0;
      for (double v : q[t]) s += v;
      s *= t == 0 ? 1.0 : p.w_transient;
      total += std::pow(s, p.beta_tch);
    }
    return std::pow(total, 1.0 / p.beta_tch);
  }

  static Status check_fixation(const std::optional<Fixation>& f) {
    if (f && (!std::isfinite(f->x) || !std::isfinite(f->y)))
      return bad_input("fixation: must be finite, got " + std::to_string(f->x) + "," + std::to_string(f->y));
    return {};
  }

  Status check_size(const image::Image& img, const char* what) const {
    if (img.width != geometry.width || img.height != geometry.height)
      return bad_input(std::string(what) + ": size " + std::to_string(img.width) + "x" + std::to_string(img.height) +
                       " differs from the metric's " + std::to_string(geometry.width) + "x" + std::to_string(geometry.height));
    return {};
  }
};

double EyeGeometry::ppd() const { return 1.0 / (2.0 * std::atan(0.5 / focal_px) * kDeg); }

EyeGeometry eye_geometry(const DisplayModel& model, Eye e, int w, int h) {
  const glm::vec2 f = model.focal_px(e);
  const glm::vec2 c = model.principal_point(e);
  const double sx = static_cast<double>(w) / model.eye_width, sy = static_cast<double>(h) / model.eye_height;
  EyeGeometry g;
  g.width = w;
  g.height = h;
  // Square pixels: one focal length, the horizontal one.
  g.focal_px = static_cast<double>(f.x) * sx;
  g.cx = static_cast<double>(c.x) * sx;
  g.cy = static_cast<double>(c.y) * sy;
  return g;
}

Status Photometry::validate() const {
  if (!std::isfinite(peak_cd_m2) || !std::isfinite(black_cd_m2) || black_cd_m2 <= 0 || peak_cd_m2 <= black_cd_m2)
    return bad_input("display luminance: need 0 < black < peak (cd/m²), got black " + std::to_string(black_cd_m2) +
                     ", peak " + std::to_string(peak_cd_m2));
  // The CSF's table spans this luminance; past it the planes overflow (peak 1e300 gave a
  // JOD of NaN).
  if (black_cd_m2 < kMinLuminanceCdM2 || peak_cd_m2 > kMaxLuminanceCdM2)
    return bad_input("display luminance: black and peak must lie in [0.001, 10000] cd/m², got black " +
                     std::to_string(black_cd_m2) + ", peak " + std::to_string(peak_cd_m2));
  return {};
}

double jod_from_q(double q, const Parameters& p) {
  const double e = std::pow(10.0, p.log_jod_exp);
  return 10.0 + p.jod_a * std::pow(q, e);
}

JodMetric::JodMetric(EyeGeometry geometry, Photometry photometry, Parameters parameters, int threads)
    : impl_(std::make_shared<const Impl>(geometry, photometry, parameters, threads)) {}
JodMetric::~JodMetric() = default;
JodMetric::JodMetric(JodMetric&&) noexcept = default;
JodMetric& JodMetric::operator=(JodMetric&&) noexcept = default;
const EyeGeometry& JodMetric::geometry() const { return impl_->geometry; }

Result<JodScore> JodMetric::still(const image::Image& reference, const image::Image& test,
                                  const std::optional<Fixation>& fixation) const {
  if (auto s = impl_->check_size(reference, "reference"); !s) return s.error();
  if (auto s = impl_->check_size(test, "test"); !s) return s.error();
  if (auto s = Impl::check_fixation(fixation); !s) return s.error();
  if (auto s = impl_->photometry.validate(); !s) return s.error();
  const Plane r = impl_->luminance(reference), t = impl_->luminance(test);
  std::vector<std::vector<double>> q;
  impl_->score_frame({&t, &r}, fixation, q);
  JodScore out;
  out.q = impl_->pool_frame(q);
  out.jod = jod_from_q(out.q, impl_->p);
  out.frames = 1;
  out.bands = impl_->bands;
  out.ppd = impl_->ppd;
  return out;
}

// A video's state: the last frames' luminance (as many as the temporal filters span), the
// two filters, and the per-frame differences so far.
struct JodMetric::Video::State {
  std::shared_ptr<const Impl> impl;
  std::vector<float> sustained, transient;  ///< weight of the frame `k` frames back
  std::vector<Plane> ref_ring, test_ring;
  long frames = 0;
  std::vector<double> q_frames;
};

JodMetric::Video::Video(std::unique_ptr<State> s) : s_(std::move(s)) {}
JodMetric::Video::~Video() = default;
JodMetric::Video::Video(Video&&) noexcept = default;

Result<JodMetric::Video> JodMetric::video(double fps) const {
  // The ring holds ceil(fps / 4) frames of both videos: 1000 Hz is the most it takes.
  if (auto st = impl_->photometry.validate(); !st) return st.error();
  if (!std::isfinite(fps) || fps <= 0 || fps > 1000)
    return bad_input("--fps: must be in (0, 1000], got " + std::to_string(fps));
  auto s = std::make_unique<Video::State>();
  s->impl = impl_;
  // 250 ms of frames: a log-normal sustained response (peak 60 ms) and its derivative,
  // sampled on [0, n/fps] at n points.
  // Below 4 fps one frame spans the 250 ms: the sustained channel is that frame and the
  // transient one is empty (the reference fails there: it needs two taps).
  const int n = std::max(1, static_cast<int>(std::ceil(250.0 / (1000.0 / fps))));
  const double step = n > 1 ? (static_cast<double>(n) / fps) / (n - 1) : 1.0;
  const Parameters& p = impl_->p;
  std::vector<double> f(static_cast<std::size_t>(n));
  double sum = 0;
  for (int k = 0; k < n; ++k) {
    const double l = std::log(k * step + 1e-4) - std::log(p.sustained_beta_s);
    f[static_cast<std::size_t>(k)] = std::exp(-l * l / (2 * p.sustained_sigma * p.sustained_sigma));
    sum += f[static_cast<std::size_t>(k)];
  }
  // The transient response's gain (0.0621705) puts its CSF at 5 Hz on the sustained one's scale.
  const double k_transient = 0.062170507756932;
  for (int k = 0; k < n; ++k) {
    s->sustained.push_back(static_cast<float>(f[static_cast<std::size_t>(k)] / sum));
    const double d = k + 1 < n ? (f[static_cast<std::size_t>(k) + 1] - f[static_cast<std::size_t>(k)]) / sum / step : 0.0;
    s->transient.push_back(static_cast<float>(k_transient * d));
  }
  s->ref_ring.resize(static_cast<std::size_t>(n));
  s->test_ring.resize(static_cast<std::size_t>(n));
  return Video(std::move(s));
}

Status JodMetric::Video::push(const image::Image& reference, const image::Image& test,
                              const std::optional<Fixation>& fixation) {
  State& s = *s_;
  const Impl& impl = *s.impl;
  if (auto st = impl.check_size(reference, "reference frame"); !st) return st;
  if (auto st = impl.check_size(test, "test frame"); !st) return st;
  if (auto st = Impl::check_fixation(fixation); !st) return st;
  const std::size_t n = s.sustained.size();
  const std::size_t slot = static_cast<std::size_t>(s.frames) % n;
  s.ref_ring[slot] = impl.luminance(reference);
  s.test_ring[slot] = impl.luminance(test);
  const std::size_t px = s.ref_ring[slot].v.size();
  std::array<Plane, 4> ch;
  for (Plane& c : ch) c = Plane(reference.width, reference.height);
  for (std::size_t k = 0; k < n; ++k) {
    // Frames before the first are the first.
    const long idx = std::max(0L, s.frames - static_cast<long>(k));
    const std::size_t ring = static_cast<std::size_t>(idx) % n;
    const float ws = s.sustained[k], wt = s.transient[k];
    const float* tr = s.test_ring[ring].v.data();
    const float* rr = s.ref_ring[ring].v.data();
    for (std::size_t i = 0; i < px; ++i) {
      ch[0].v[i] += ws * tr[i];
      ch[1].v[i] += ws * rr[i];
      ch[2].v[i] += wt * tr[i];
      ch[3].v[i] += wt * rr[i];
    }
  }
  std::vector<std::vector<double>> q;
  impl.score_frame({&ch[0], &ch[1], &ch[2], &ch[3]}, fixation, q);
  s.q_frames.push_back(impl.pool_frame(q));
  ++s.frames;
  return {};
}

Result<JodScore> JodMetric::Video::score() const {
  const State& s = *s_;
  if (s.q_frames.empty()) return bad_input("video: no frames");
  double sum = 0;
  for (double q : s.q_frames) sum += q;
  JodScore out;
  out.q = sum / static_cast<double>(s.q_frames.size());
  out.jod = jod_from_q(out.q, s.impl->p);
  out.frames = static_cast<int>(s.q_frames.size());
  out.bands = s.impl->bands;
  out.ppd = s.impl->ppd;
  return out;
}

}  // namespace foveal::perception
