#include "foveal/bench/bench_jod.hpp"

#include <chrono>
#include <cstdio>
#include <string>

namespace foveal::bench {

namespace {

double ms_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
}

image::Image eye_half(const image::Image& frame, int e, int w, int h) { return image::crop(frame, {e * w, 0, w, h}); }

}  // namespace

Result<StereoJodScorer> StereoJodScorer::create(const DisplayModel& model, int width, int height, int threads,
                                                const perception::Photometry& light) {
  if (width % 2 != 0 || width / 2 < 8 || height < 8)
    return bad_input("JOD: a side-by-side frame of even width and at least 8x8 per eye is needed, got " + std::to_string(width) + "x" +
                     std::to_string(height));
  if (Status s = light.validate(); !s) return Error{s.error().kind, "JOD: " + s.error().message};
  const int w = width / 2;
  std::vector<perception::JodMetric> eyes;
  for (Eye e : {Eye::left, Eye::right})
    eyes.emplace_back(perception::eye_geometry(model, e, w, height), light, perception::Parameters{}, threads);
  return StereoJodScorer(std::move(eyes), light, w, height);
}

double StereoJodScorer::ppd(Eye e) const { return eyes_[e == Eye::left ? 0 : 1].geometry().ppd(); }

Status StereoJodScorer::check(const image::Image& reference, const image::Image& test) const {
  for (const image::Image* i : {&reference, &test})
    if (i->width != 2 * eye_w_ || i->height != eye_h_)
      return bad_input("JOD: a frame of " + std::to_string(i->width) + "x" + std::to_string(i->height) + ", the metric was made for " +
                       std::to_string(2 * eye_w_) + "x" + std::to_string(eye_h_));
  return {};
}

std::optional<perception::Fixation> StereoJodScorer::fixation(const EyeFovea& f) const {
  if (!f) return std::nullopt;
  return perception::Fixation{(*f)[0] * eye_w_, (*f)[1] * eye_h_};
}

StereoJod StereoJodScorer::combine(const perception::JodScore& l, const perception::JodScore& r) const {
  return {l.jod, r.jod, perception::jod_from_q(0.5 * (l.q + r.q), parameters_)};
}

Result<StereoJod> StereoJodScorer::still(const image::Image& reference, const image::Image& test, const EyeFovea& left,
                                         const EyeFovea& right) {
  if (Status s = check(reference, test); !s) return s.error();
  const auto t0 = std::chrono::steady_clock::now();
  std::array<perception::JodScore, 2> score;
  for (int e = 0; e < 2; ++e) {
    auto s = eyes_[static_cast<std::size_t>(e)].still(eye_half(reference, e, eye_w_, eye_h_), eye_half(test, e, eye_w_, eye_h_),
                                                      fixation(e == 0 ? left : right));
    if (!s) return s.error();
    score[static_cast<std::size_t>(e)] = *s;
  }
  total_ms_ += ms_since(t0);
  ++scored_;
  return combine(score[0], score[1]);
}

Result<StereoJodScorer::Video> StereoJodScorer::video(double fps) {
  std::vector<perception::JodMetric::Video> v;
  for (const auto& m : eyes_) {
    auto e = m.video(fps);
    if (!e) return e.error();
    v.push_back(std::move(*e));
  }
  return Video(*this, std::move(v));
}

Status StereoJodScorer::Video::push(const image::Image& reference, const image::Image& test, const EyeFovea& left, const EyeFovea& right) {
  StereoJodScorer& o = *owner_;
  if (Status s = o.check(reference, test); !s) return s;
  const auto t0 = std::chrono::steady_clock::now();
  for (int e = 0; e < 2; ++e)
    if (Status s = eyes_[static_cast<std::size_t>(e)].push(eye_half(reference, e, o.eye_w_, o.eye_h_), eye_half(test, e, o.eye_w_, o.eye_h_),
                                                           o.fixation(e == 0 ? left : right));
        !s)
      return s;
  o.total_ms_ += ms_since(t0);
  ++o.scored_;
  return {};
}

Result<StereoJod> StereoJodScorer::Video::score() const {
  std::array<perception::JodScore, 2> score;
  for (int e = 0; e < 2; ++e) {
    auto s = eyes_[static_cast<std::size_t>(e)].score();
    if (!s) return s.error();
    score[static_cast<std::size_t>(e)] = *s;
  }
  return owner_->combine(score[0], score[1]);
}

nlohmann::json jod_settings(const StereoJodScorer& j) {
  return {{"release", "1.2"}, {"peak_cd_m2", j.photometry().peak_cd_m2}, {"black_cd_m2", j.photometry().black_cd_m2},
          {"ppd", {j.ppd(Eye::left), j.ppd(Eye::right)}}, {"frames", j.scored()},
          {"per_frame_ms", j.scored() ? j.total_ms() / j.scored() : 0.0}};
}

void print_jod_cost(const StereoJodScorer& j, const char* label, std::chrono::steady_clock::time_point start) {
  if (!j.scored()) return;
  const double run_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  std::fprintf(stderr, "%s: JOD added %.0f ms per frame (%d frames, %.1f s of the run's %.1f s; --no-jod leaves it out)\n", label,
               j.total_ms() / j.scored(), j.scored(), j.total_ms() / 1000, run_s);
}

}  // namespace foveal::bench
