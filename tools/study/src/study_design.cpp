#include "foveal/study/study_design.hpp"

#include <charconv>
#include <cmath>
#include <optional>
#include <cstdio>
#include <random>


namespace foveal {

namespace {

std::optional<double> parse_double(const std::string& s) {
  double v = 0;
  const auto [end, ec] = std::from_chars(s.data(), s.data() + s.size(), v);
  if (ec != std::errc{} || end != s.data() + s.size() || !std::isfinite(v)) return std::nullopt;
  return v;
}

std::vector<std::string> split(const std::string& s, char sep) {
  std::vector<std::string> out(1);
  for (char c : s) {
    if (c == sep) out.emplace_back();
    else out.back() += c;
  }
  return out;
}

// A uniform integer in [0, n) from the generator's raw output by rejection: the
// standard distributions differ between library implementations, the engine does not.
std::uint64_t draw_below(std::mt19937_64& rng, std::uint64_t n) {
  const std::uint64_t limit = UINT64_MAX - UINT64_MAX % n;
  std::uint64_t x;
  do x = rng();
  while (x >= limit);
  return x % n;
}

template <class T>
void shuffle(std::vector<T>& v, std::mt19937_64& rng) {
  for (std::size_t i = v.size(); i > 1; --i) std::swap(v[i - 1], v[draw_below(rng, i)]);
}

}  // namespace

std::string level_text(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%g", v);
  return buf;
}

std::string StudyCondition::label() const {
  if (method == "full") return "full";
  std::string s = method;
  if (uniform()) s += " sigma=" + level_text(sigma_d);
  else s += " sigma_d=" + level_text(sigma_d) + " sigma_nd=" + level_text(sigma_nd);
  return s + " f=" + level_text(f);
}

Result<StudyCondition> parse_study_condition(const std::string& spec, const std::string& what) {
  const auto fail = [&](const std::string& why) {
    return bad_input(what + ": '" + spec + "': " + why + " (expected METHOD[:SIGMA[/SIGMA_ND]][:F])");
  };
  const std::vector<std::string> parts = split(spec, ':');
  if (parts.size() > 3 || parts[0].empty()) return fail("bad form");
  StudyCondition c;
  c.method = parts[0];
  if (c.method == "full") {
    if (parts.size() > 1) return fail("full resolution takes no level");
    return c;
  }
  if (parts.size() >= 2) {
    const std::vector<std::string> levels = split(parts[1], '/');
    if (levels.size() > 2) return fail("more than two levels");
    auto d = parse_double(levels[0]);
    if (!d || !(*d >= 1.0)) return fail("sigma must be a number >= 1");
    c.sigma_d = c.sigma_nd = *d;
    if (levels.size() == 2) {
      auto nd = parse_double(levels[1]);
      if (!nd || !(*nd >= c.sigma_d)) return fail("sigma_nd must be a number >= sigma");
      c.sigma_nd = *nd;
    }
  } else {
    return fail("a foveated method needs its level");
  }
  if (parts.size() == 3) {
    auto f = parse_double(parts[2]);
    if (!f || !(*f > 0)) return fail("f must be a number > 0");
    c.f = *f;
  }
  return c;
}

const char* study_design_name(StudyDesign d) { return d == StudyDesign::two_afc ? "2afc" : "score"; }

Status StudyOptions::validate() const {
  if (participant.empty() || participant.find_first_of(",\"\n\r") != std::string::npos)
    return bad_input("study: the participant id must be non-empty, without commas, quotes or line ends");
  if (scenes.empty()) return bad_input("study: no scene");
  const std::size_t need = design == StudyDesign::two_afc ? 2 : 1;
  if (conditions.size() < need)
    return bad_input(design == StudyDesign::two_afc ? "study: a 2AFC study needs at least two conditions"
                                                    : "study: a score study needs at least one condition");
  for (std::size_t i = 0; i < conditions.size(); ++i)
    for (std::size_t j = i + 1; j < conditions.size(); ++j)
      if (conditions[i] == conditions[j]) return bad_input("study: condition '" + conditions[i].label() + "' given twice");
  if (repeats < 1) return bad_input("study: repeats must be >= 1");
  if (!(validation_share >= 0 && validation_share <= 0.9)) return bad_input("study: the validation share must lie in [0, 0.9]");
  if (validation_min_score < 1 || validation_min_score > 5) return bad_input("study: the validation minimum score must be 1 to 5");
  if (max_validation_errors < 0) return bad_input("study: the allowed validation errors must be >= 0");
  if (!(present_s > 0) || !(blank_s >= 0)) return bad_input("study: presentations need a time > 0, the black >= 0");
  if (design == StudyDesign::two_afc && validation_condition.method == "full")
    return bad_input("study: the 2AFC validation condition must differ from full resolution");
  return {};
}

std::uint64_t study_seed(const StudyOptions& o) {
  if (o.seed != 0) return o.seed;
  std::uint64_t h = 14695981039346656037ull;
  for (unsigned char c : o.participant) h = (h ^ c) * 1099511628211ull;
  return h;
}

Result<std::vector<PlannedTrial>> plan_study(const StudyOptions& o) {
  if (Status s = o.validate(); !s) return s.error();
  std::mt19937_64 rng(study_seed(o));
  const StudyCondition full;
  std::vector<PlannedTrial> trials;
  for (const std::string& scene : o.scenes)
    for (int r = 0; r < o.repeats; ++r) {
      if (o.design == StudyDesign::two_afc) {
        for (std::size_t i = 0; i < o.conditions.size(); ++i)
          for (std::size_t j = i + 1; j < o.conditions.size(); ++j)
            trials.push_back({0, scene, o.conditions[i], o.conditions[j], false, false});
      } else {
        for (const StudyCondition& c : o.conditions) trials.push_back({0, scene, full, c, false, false});
      }
    }
  const double tests = static_cast<double>(trials.size());
  const auto validations = static_cast<std::size_t>(std::llround(o.validation_share / (1.0 - o.validation_share) * tests));
  for (std::size_t v = 0; v < validations; ++v) {
    const std::string& scene = o.scenes[v % o.scenes.size()];
    const StudyCondition& b = o.design == StudyDesign::two_afc ? o.validation_condition : full;
    trials.push_back({0, scene, full, b, false, true});
  }
  shuffle(trials, rng);
  for (std::size_t i = 0; i < trials.size(); ++i) {
    trials[i].index = static_cast<int>(i + 1);
    trials[i].b_first = draw_below(rng, 2) == 1;
  }
  return trials;
}

}  // namespace foveal
