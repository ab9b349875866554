#include "foveal/study/study_trials.hpp"

#include "foveal/core/shown_text.hpp"
#include "foveal/import/table_reader.hpp"

namespace foveal {

namespace {

/// The columns a trials file may carry, found once from its header.
struct TrialColumns {
  long method_a = -1, method_b = -1, chosen = -1;
  long condition = -1, score = -1;
  long validation = -1;
  long sigma_d = -1, sigma_nd = -1;
  /// Further condition parameters: (name, column of side a, column of side b).
  struct Parameter {
    std::string name;
    std::size_t a, b;
  };
  std::vector<Parameter> parameters;
};

TrialColumns find_columns(const TableReader& t, const std::vector<std::string>& header) {
  TrialColumns c;
  c.method_a = t.find_column("method_a");
  c.method_b = t.find_column("method_b");
  c.chosen = t.find_column("chosen");
  c.condition = t.find_column("condition");
  c.score = t.find_column("score");
  c.validation = t.find_column("validation");
  c.sigma_d = t.find_column("sigma_d");
  c.sigma_nd = t.find_column("sigma_nd");
  for (std::size_t i = 0; i < header.size(); ++i) {
    const std::string& h = header[i];
    if (h.size() < 3 || h.compare(h.size() - 2, 2, "_a") != 0 || h == "method_a") continue;
    const std::string name = h.substr(0, h.size() - 2);
    const long b = t.find_column(name + "_b");
    if (b >= 0) c.parameters.push_back({name, i, static_cast<std::size_t>(b)});
  }
  return c;
}

/// A field that becomes part of a label: no control characters (a NUL cut the printed
/// label short), at most kMaxLabelBytes.
Status check_label_field(const TableReader& t, std::size_t col) {
  constexpr std::size_t kMaxLabelBytes = 256;
  const std::string_view v = t.field(col);
  if (v.size() > kMaxLabelBytes)
    return t.field_error(col, std::to_string(v.size()) + " bytes; a label has at most " + std::to_string(kMaxLabelBytes));
  for (std::size_t i = 0; i < v.size(); ++i) {
    const auto ch = static_cast<unsigned char>(v[i]);
    if (ch < 0x20 || ch == 0x7f)
      return t.field_error(col, "byte " + std::to_string(i + 1) + " of '" + shown_text(v) + "' is a control character");
  }
  return {};
}

/// "rmfr", or "rmfr sigma=2.6 f=0.3" when the file has sigma_a/sigma_b, f_a/f_b columns.
Result<std::string> condition_of(const TableReader& t, const TrialColumns& c, bool side_a) {
  const auto method = static_cast<std::size_t>(side_a ? c.method_a : c.method_b);
  if (Status s = check_label_field(t, method); !s) return s.error();
  std::string label(t.field(method));
  for (const auto& p : c.parameters) {
    if (Status s = check_label_field(t, side_a ? p.a : p.b); !s) return s.error();
    label += " " + p.name + "=" + std::string(t.field(side_a ? p.a : p.b));
  }
  return label;
}

Result<bool> validation_flag(const TableReader& t, long column) {
  if (column < 0) return false;
  const std::string_view v = t.field(static_cast<std::size_t>(column));
  if (v.empty() || v == "0" || v == "false") return false;
  if (v == "1" || v == "true") return true;
  return t.field_error(static_cast<std::size_t>(column), "'" + shown_text(v) + "' is not 0, 1, true or false");
}

}  // namespace

Result<StudyTrials> read_study_trials(const std::string& path) {
  auto table = TableReader::open(path, ',');
  if (!table) return table.error();
  TableReader& t = *table;
  const TrialColumns c = find_columns(t, t.header());
  const bool has_choices = c.method_a >= 0 && c.method_b >= 0 && c.chosen >= 0;
  const bool has_scores = c.condition >= 0 && c.score >= 0;
  if (!has_choices && !has_scores)
    return bad_input(path + ":1: the header needs the columns method_a,method_b,chosen (choice trials) or "
                            "condition,score (score trials)");
  StudyTrials out;
  for (;;) {
    auto got = t.next();
    if (!got) return got.error();
    if (!*got) break;
    auto validation = validation_flag(t, c.validation);
    if (!validation) return validation.error();
    const bool chose = has_choices && !t.field(static_cast<std::size_t>(c.chosen)).empty();
    const bool scored = has_scores && !t.field(static_cast<std::size_t>(c.score)).empty();
    if (!chose && !scored)
      return t.field_error(static_cast<std::size_t>(has_choices ? c.chosen : c.score),
                           has_choices && has_scores ? "empty, and so is score: the row is no trial"
                                                     : "empty");
    if (*validation) {
      ++out.validation_trials;
      continue;
    }
    if (chose) {
      const auto col = static_cast<std::size_t>(c.chosen);
      const std::string_view v = t.field(col);
      if (v != "a" && v != "b") return t.field_error(col, "'" + shown_text(v) + "' is not a or b");
      for (long m : {c.method_a, c.method_b})
        if (t.field(static_cast<std::size_t>(m)).empty()) return t.field_error(static_cast<std::size_t>(m), "empty");
      auto cond_a = condition_of(t, c, true);
      if (!cond_a) return cond_a.error();
      auto cond_b = condition_of(t, c, false);
      if (!cond_b) return cond_b.error();
      ChoiceTrial trial{std::move(*cond_a), std::move(*cond_b), v == "a", t.line()};
      if (trial.condition_a == trial.condition_b)
        return t.field_error(static_cast<std::size_t>(c.method_b),
                             "the same condition '" + shown_text(trial.condition_a) +
                                 "' on both sides; flag such rows in a validation column");
      out.choices.push_back(std::move(trial));
    }
    if (scored) {
      const auto col = static_cast<std::size_t>(c.score);
      auto score = t.number<std::int64_t>(col);
      if (!score) return score.error();
      if (*score < 1 || *score > 5) return t.field_error(col, std::to_string(*score) + " is not a score from 1 to 5");
      const std::string_view cond = t.field(static_cast<std::size_t>(c.condition));
      if (cond.empty()) return t.field_error(static_cast<std::size_t>(c.condition), "empty");
      if (Status st = check_label_field(t, static_cast<std::size_t>(c.condition)); !st) return st.error();
      ScoreTrial trial{std::string(cond), static_cast<int>(*score), t.line(), {}, {}};
      // Both levels or neither: a score of one eye's level alone places nothing.
      std::optional<double>* levels[2] = {&trial.sigma_d, &trial.sigma_nd};
      const long cols[2] = {c.sigma_d, c.sigma_nd};
      for (int i = 0; i < 2; ++i) {
        if (cols[i] < 0 || t.field(static_cast<std::size_t>(cols[i])).empty()) continue;
        auto v = t.number<double>(static_cast<std::size_t>(cols[i]));
        if (!v) return v.error();
        if (!(*v >= 1.0)) return t.field_error(static_cast<std::size_t>(cols[i]), "a level must be >= 1");
        *levels[i] = *v;
      }
      if (trial.sigma_d.has_value() != trial.sigma_nd.has_value())
        return t.field_error(static_cast<std::size_t>(trial.sigma_d ? c.sigma_nd : c.sigma_d),
                             "empty, but the other level is given");
      if (trial.sigma_d && *trial.sigma_nd < *trial.sigma_d)
        return t.field_error(static_cast<std::size_t>(c.sigma_nd), "below sigma_d (EFR: sigma_nd >= sigma_d)");
      out.scores.push_back(std::move(trial));
    }
  }
  if (out.choices.empty() && out.scores.empty() && out.validation_trials == 0)
    return bad_input(path + ": no trials: the file has a header only");
  return out;
}

}  // namespace foveal
