#include "foveal/study/study_session.hpp"

#include <charconv>
#include <cmath>
#include <cstdio>

#include "foveal/core/shown_text.hpp"

namespace foveal {

Result<StudyResponse> parse_study_response(const std::string& word) {
  StudyResponse r;
  const std::size_t at = word.find('@');
  const std::string key = word.substr(0, at);
  if (key.size() != 1 || key[0] < '1' || key[0] > '5')
    return bad_input("'" + shown_text(word) + "' is not a response (1 to 5, optionally @SECONDS)");
  r.key = key[0] - '0';
  if (at != std::string::npos) {
    double s = 0;
    const char* b = word.data() + at + 1;
    const char* e = word.data() + word.size();
    const auto [end, ec] = std::from_chars(b, e, s);
    if (ec != std::errc{} || end != e || !std::isfinite(s) || s < 0)
      return bad_input("'" + shown_text(word) + "': the response time after '@' must be seconds >= 0");
    // No answer takes longer than an hour; 1e308 was written to the trials as it came.
    if (s > kMaxResponseSeconds)
      return bad_input("'" + shown_text(word) + "': a response time of " + shown_text(word.substr(at + 1)) +
                       " s is more than " + std::to_string(static_cast<int>(kMaxResponseSeconds)) + " s");
    r.response_s = s;
  }
  return r;
}

StudySession::StudySession(StudyOptions o, std::vector<PlannedTrial> plan) : o_(std::move(o)), plan_(std::move(plan)) {}

Status StudySession::respond(const StudyResponse& r) {
  if (done()) return bad_input("the study is already complete");
  const PlannedTrial& t = plan_[next_];
  TrialResult res{t, r};
  if (o_.design == StudyDesign::two_afc) {
    if (r.key != 1 && r.key != 2) return bad_input("a 2AFC trial asks for 1 (first) or 2 (second)");
    const bool chose_first = r.key == 1;
    res.chose_a = chose_first != t.b_first;
    // Validation: side a is full resolution, the right answer.
    res.validation_failed = t.validation && !res.chose_a;
  } else {
    if (r.key < 1 || r.key > 5) return bad_input("a score trial asks for 1 (very different) to 5 (no difference)");
    res.score = r.key;
    res.validation_failed = t.validation && r.key < o_.validation_min_score;
  }
  if (t.validation) ++validation_trials_;
  if (res.validation_failed) {
    ++validation_failures_;
    if (validation_failures_ > o_.max_validation_errors) discarded_ = true;
    else if (next_ + 1 < plan_.size()) {
      pause_requested_ = true;
      ++pauses_;
    }
  }
  results_.push_back(std::move(res));
  ++next_;
  return {};
}

std::string study_trials_csv(const StudySession& s) {
  std::string out =
      "participant,scene,trial,design,method_a,sigma_a,f_a,method_b,sigma_b,f_b,order,chosen,"
      "condition,sigma_d,sigma_nd,score,response_s,validation,validation_failed\n";
  const bool two_afc = s.options().design == StudyDesign::two_afc;
  for (const TrialResult& r : s.results()) {
    const PlannedTrial& t = r.trial;
    std::string row = s.options().participant + "," + t.scene + "," + std::to_string(t.index) + "," +
                      study_design_name(s.options().design) + ",";
    if (two_afc) {
      // A 2AFC condition is uniform: one sigma for both eyes.
      for (const StudyCondition* c : {&t.a, &t.b})
        row += c->method + "," + (c->method == "full" ? "1" : level_text(c->sigma_d)) + "," +
               (c->method == "full" ? "" : level_text(c->f)) + ",";
      row += std::string(t.b_first ? "ba" : "ab") + "," + (r.chose_a ? "a" : "b") + ",,,,,";
    } else {
      const StudyCondition& c = t.b;
      row += ",,,,,,";
      row += std::string(t.b_first ? "test-first" : "reference-first") + ",," + c.label() + "," +
             level_text(c.sigma_d) + "," + level_text(c.sigma_nd) + "," + std::to_string(r.score) + ",";
    }
    char rt[32] = "";
    if (r.response.response_s) std::snprintf(rt, sizeof rt, "%.3f", *r.response.response_s);
    row += std::string(rt) + "," + (t.validation ? "1" : "0") + "," + (r.validation_failed ? "1" : "0") + "\n";
    out += row;
  }
  return out;
}

}  // namespace foveal
