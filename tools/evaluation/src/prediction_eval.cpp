#include "foveal/evaluation/prediction_eval.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

#include <glm/geometric.hpp>

#include "foveal/runtime/gaze_pipeline.hpp"

namespace foveal::evaluation {

const char* shown_name(Shown s) {
  switch (s) {
    case Shown::none: return "none";
    case Shown::filter: return "filter";
    case Shown::filter_predict: return "filter_predict_ms";
    case Shown::predict: return "predict";
  }
  return "?";
}

const char* phase_name(Phase p) {
  switch (p) {
    case Phase::all: return "all";
    case Phase::fixation: return "fixation";
    case Phase::pursuit: return "pursuit";
    case Phase::saccade: return "saccade";
    case Phase::onset: return "saccade_onset";
  }
  return "?";
}

const char* truth_name(Truth t) { return t == Truth::recorded ? "recorded" : "smoothed"; }

namespace {

constexpr TimeNs kMaxGapNs = 25 * kNsPerMs;  // neighbours further apart than 3 frames: no truth between them
constexpr int kSmoothHalf = 2;               // the smoothed truth: samples k-2 .. k+2

double angle_deg(glm::dvec3 a, glm::dvec3 b) {
  return std::atan2(glm::length(glm::cross(a, b)), glm::dot(a, b)) * 180.0 / std::numbers::pi;
}

enum class Label { fixation, pursuit, saccade };

// One eye's recording, as the evaluation needs it.
struct EyeSeries {
  std::vector<bool> valid;
  std::vector<glm::dvec3> raw;       // unit direction where valid
  std::vector<glm::dvec3> smooth;    // centred mean where all 5 are valid and close, else NaN
  std::vector<FoveaState> state;     // the pipeline's state at each sample
  std::vector<std::pair<TimeNs, TimeNs>> saccades;  // [onset, landing], from the pipeline
};

ErrorStats stats_of(std::vector<double> v) {
  ErrorStats s;
  s.n = v.size();
  if (v.empty()) return s;
  std::sort(v.begin(), v.end());
  auto rank = [&v](double q) {  // nearest rank
    const auto k = static_cast<std::size_t>(std::ceil(q * static_cast<double>(v.size())));
    return v[std::clamp<std::size_t>(k, 1, v.size()) - 1];
  };
  s.p50 = rank(0.50);
  s.p95 = rank(0.95);
  s.p99 = rank(0.99);
  double sum = 0;
  for (double x : v) sum += x;
  s.mean = sum / static_cast<double>(v.size());
  return s;
}

}  // namespace

PredictionEvaluator::PredictionEvaluator(DisplayModel model, FilterConfig cfg, std::vector<double> latencies_ms,
                                         FoveaPrediction p)
    : model_(std::move(model)), cfg_(cfg), latencies_ms_(std::move(latencies_ms)), prediction_(p) {
  errors_.resize(latencies_ms_.size());
}

void PredictionEvaluator::add(const std::vector<GazeSample>& samples) {
  const std::size_t n = samples.size();
  if (n < 2) return;
  std::vector<TimeNs> t(n);
  for (std::size_t i = 0; i < n; ++i) t[i] = samples[i].t_ns;

  // The pipeline as configured, every output kept (what predict_fovea starts from).
  GazePipeline pipe(model_, cfg_);
  std::vector<FoveaFrame> frames(n);
  std::array<EyeSeries, 2> eyes;
  for (auto& es : eyes) {
    es.valid.resize(n);
    es.raw.resize(n);
    es.state.resize(n);
  }
  std::array<std::size_t, 2> open_saccade{SIZE_MAX, SIZE_MAX};
  for (std::size_t i = 0; i < n; ++i) {
    frames[i] = pipe.update(samples[i]);
    for (Eye e : kEyes) {
      const auto k = static_cast<std::size_t>(e);
      EyeSeries& es = eyes[k];
      const EyeEvents& ev = pipe.events(e);
      es.valid[i] = ev.valid;
      es.raw[i] = ev.valid ? glm::normalize(glm::dvec3(samples[i].eye(e).direction)) : glm::dvec3(NAN);
      es.state[i] = frames[i].eyes[k].state;
      if (open_saccade[k] != SIZE_MAX && es.state[i] != FoveaState::saccade) {
        es.saccades[open_saccade[k]].second = t[i];  // landed (or lost) here
        open_saccade[k] = SIZE_MAX;
      }
      if (ev.saccade_onset) {
        es.saccades.emplace_back(ev.onset_t_ns, t[n - 1]);
        open_saccade[k] = es.saccades.size() - 1;
      }
    }
  }
  for (auto& es : eyes) {
    es.smooth.assign(n, glm::dvec3(NAN));
    for (std::size_t i = kSmoothHalf; i + kSmoothHalf < n; ++i) {
      if (t[i + kSmoothHalf] - t[i - kSmoothHalf] > 2 * kSmoothHalf * 12 * kNsPerMs) continue;  // no gap inside
      glm::dvec3 sum(0.0);
      bool all = true;
      for (std::size_t j = i - kSmoothHalf; j <= i + kSmoothHalf; ++j) {
        all = all && es.valid[j];
        if (es.valid[j]) sum += es.raw[j];
      }
      if (all) es.smooth[i] = glm::normalize(sum);
    }
  }

  for (std::size_t li = 0; li < latencies_ms_.size(); ++li) {
    const double L = latencies_ms_[li];
    const auto L_ns = static_cast<TimeNs>(std::llround(L * 1e6));
    FilterConfig fixed = cfg_;
    fixed.predict_ms = std::min(L, 100.0);  // FilterConfig's own limit
    GazePipeline pipe_fixed(model_, fixed);
    std::size_t j = 0;  // t[j] <= tau < t[j + 1]
    for (std::size_t i = 0; i < n; ++i) {
      const FoveaFrame fixed_frame = pipe_fixed.update(samples[i]);
      const TimeNs tau = t[i] + L_ns;
      while (j + 1 < n && t[j + 1] <= tau) ++j;
      if (j + 1 >= n) break;  // the truth runs past the recording
      const double w = static_cast<double>(tau - t[j]) / static_cast<double>(t[j + 1] - t[j]);
      const FoveaFrame predicted = predict_fovea(frames[i], tau, model_.eye_width, model_.eye_height, prediction_);
      for (Eye e : kEyes) {
        const auto k = static_cast<std::size_t>(e);
        const EyeSeries& es = eyes[k];
        if (!es.valid[i] || !es.valid[j] || !es.valid[j + 1] || t[j + 1] - t[j] > kMaxGapNs) continue;
        auto label_at = [&es](TimeNs when, std::size_t idx) {
          for (const auto& [a, b] : es.saccades)
            if (when >= a && when < b) return Label::saccade;
          return es.state[idx] == FoveaState::pursuit ? Label::pursuit : Label::fixation;
        };
        const Label now = label_at(t[i], i), then = label_at(tau, j);
        const std::array<glm::dvec3, kShown.size()> shown = {
            es.raw[i], glm::dvec3(model_.pixel_to_direction(e, frames[i].eyes[k].px)),
            glm::dvec3(model_.pixel_to_direction(e, fixed_frame.eyes[k].px)),
            glm::dvec3(model_.pixel_to_direction(e, predicted.eyes[k].px))};
        for (Truth tr : kTruths) {
          const auto& src = tr == Truth::recorded ? es.raw : es.smooth;
          const glm::dvec3 truth = glm::normalize((1.0 - w) * src[j] + w * src[j + 1]);
          if (!std::isfinite(truth.x)) continue;
          auto& by_phase = errors_[li][static_cast<std::size_t>(tr)];
          for (std::size_t s = 0; s < kShown.size(); ++s) {
            const double err = angle_deg(shown[s], truth);
            by_phase[static_cast<std::size_t>(Phase::all)][s].push_back(err);
            const Phase ph = then == Label::saccade ? Phase::saccade : then == Label::pursuit ? Phase::pursuit : Phase::fixation;
            by_phase[static_cast<std::size_t>(ph)][s].push_back(err);
            if (then == Label::saccade && now != Label::saccade)
              by_phase[static_cast<std::size_t>(Phase::onset)][s].push_back(err);
          }
        }
      }
    }
  }
}

std::vector<LatencyResult> PredictionEvaluator::result() const {
  std::vector<LatencyResult> out(latencies_ms_.size());
  for (std::size_t li = 0; li < out.size(); ++li) {
    out[li].latency_ms = latencies_ms_[li];
    for (std::size_t tr = 0; tr < kTruths.size(); ++tr)
      for (std::size_t ph = 0; ph < kPhases.size(); ++ph)
        for (std::size_t s = 0; s < kShown.size(); ++s) out[li].stats[tr][ph][s] = stats_of(errors_[li][tr][ph][s]);
  }
  return out;
}

std::vector<LatencyResult> evaluate_prediction(const std::vector<GazeSample>& samples, const DisplayModel& model,
                                               const FilterConfig& cfg, const std::vector<double>& latencies_ms,
                                               const FoveaPrediction& prediction) {
  PredictionEvaluator ev(model, cfg, latencies_ms, prediction);
  ev.add(samples);
  return ev.result();
}

}  // namespace foveal::evaluation
