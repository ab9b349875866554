// `foveal study stats`: votes per pair of conditions with the exact binomial test, and
// mean scores per condition and the sigma_UF/sigma_NF estimates, from a trials CSV
// (docs/study.md). `study run` is in cmd_study_run.cpp.
#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include <cstdio>
#include <map>
#include <optional>

#include "commands.hpp"
#include "foveal/runtime/cli.hpp"
#include "foveal/study/study_conditions.hpp"
#include "foveal/study/study_stats.hpp"

namespace foveal::cmd {

namespace {

using Predictions = std::optional<std::map<std::string, PredictedJod>>;

// A condition's predicted JOD (--conditions), null when the file has no such condition.
nlohmann::json predicted(const Predictions& jod, const std::string& label) {
  const auto it = jod->find(label);
  return it == jod->end() ? nlohmann::json(nullptr) : nlohmann::json(it->second.jod);
}

std::string predicted_text(const Predictions& jod, const std::string& label) {
  if (!jod) return "";
  const auto it = jod->find(label);
  char b[32] = "        -";
  if (it != jod->end()) std::snprintf(b, sizeof b, " %8.2f", it->second.jod);
  return b;
}

nlohmann::json stats_json(const std::string& path, const StudyStats& st, const Predictions& jod) {
  nlohmann::json pairs = nlohmann::json::array(), scores = nlohmann::json::array();
  for (const PairVotes& p : st.pairs)
    pairs.push_back({{"first", p.first},
                     {"second", p.second},
                     {"trials", p.trials},
                     {"votes_first", p.votes_first},
                     {"votes_second", p.votes_second},
                     {"ratio_first", p.share_first},
                     {"p_value", p.p_value}});
  for (const ConditionScore& c : st.scores)
    scores.push_back({{"condition", c.condition}, {"trials", c.trials}, {"mean", c.mean}, {"sd", c.sd}});
  if (jod) {
    for (auto& p : pairs)
      p.update({{"predicted_jod_first", predicted(jod, p["first"].get<std::string>())}, {"predicted_jod_second", predicted(jod, p["second"].get<std::string>())}});
    for (auto& c : scores) c["predicted_jod"] = predicted(jod, c["condition"].get<std::string>());
  }
  auto estimate = [](const std::optional<SigmaEstimate>& e) -> nlohmann::json {
    if (!e) return nullptr;
    return {{"sigma", e->sigma}, {"bound", estimate_bound_name(e->bound)}};
  };
  nlohmann::json sigmas = nlohmann::json::array();
  for (const SigmaEstimates& e : st.sigmas) {
    nlohmann::json levels = nlohmann::json::array();
    for (const LevelScore& l : e.levels)
      levels.push_back({{"sigma_d", l.sigma_d}, {"sigma_nd", l.sigma_nd}, {"trials", l.trials}, {"mean", l.mean}});
    nlohmann::json j = {{"method", e.method}, {"threshold", e.threshold}, {"levels", levels},
                        {"sigma_uf", estimate(e.sigma_uf)}, {"sigma_nf", estimate(e.sigma_nf)}};
    if (e.sigma_nf) j["sigma_nf"]["at_sigma_d"] = e.sigma_nf_at_sigma_d;
    sigmas.push_back(std::move(j));
  }
  return {{"file", path}, {"pairs", pairs}, {"scores", scores}, {"validation_trials", st.validation_trials},
          {"sigma_estimates", sigmas}};
}

void print_text(const std::string& path, const StudyStats& st, const Predictions& jod) {
  std::printf("%s: %zu pairs of conditions, %zu scored conditions, %llu validation trials left out\n", path.c_str(),
              st.pairs.size(), st.scores.size(), static_cast<unsigned long long>(st.validation_trials));
  if (!st.pairs.empty()) {
    std::printf("  %-40s %7s %15s %8s %12s%s\n", "pair (first vs second)", "trials", "votes", "ratio", "p (2-sided)",
                jod ? "   JOD first : second (predicted)" : "");
    for (const PairVotes& p : st.pairs) {
      const std::string name = p.first + " vs " + p.second;
      const std::string votes = std::to_string(p.votes_first) + " : " + std::to_string(p.votes_second);
      std::printf("  %-40s %7llu %15s %7.1f%% %12.4g%s%s\n", name.c_str(), static_cast<unsigned long long>(p.trials),
                  votes.c_str(), 100.0 * p.share_first, p.p_value, predicted_text(jod, p.first).c_str(),
                  jod ? (" :" + predicted_text(jod, p.second)).c_str() : "");
    }
  }
  if (!st.scores.empty()) {
    std::printf("  %-40s %7s %8s %8s%s\n", "condition", "trials", "mean", "sd", jod ? " JOD (predicted)" : "");
    for (const ConditionScore& c : st.scores)
      std::printf("  %-40s %7llu %8.3f %8.3f%s\n", c.condition.c_str(), static_cast<unsigned long long>(c.trials),
                  c.mean, c.sd, predicted_text(jod, c.condition).c_str());
  }
  auto bound = [](const SigmaEstimate& x) {
    switch (x.bound) {
      case EstimateBound::interpolated: return "";
      case EstimateBound::at_least: return " or more (no tested level fell below the threshold)";
      case EstimateBound::below_range: return " or less (the smallest tested level fell below the threshold)";
    }
    return "";
  };
  for (const SigmaEstimates& e : st.sigmas) {
    if (e.sigma_uf)
      std::printf("  %s: sigma_UF %.3f%s; mean score >= %.2f on the uniform levels\n", e.method.c_str(),
                  e.sigma_uf->sigma, bound(*e.sigma_uf), e.threshold);
    if (e.sigma_nf)
      std::printf("  %s: sigma_NF %.3f%s, the dominant eye at sigma %.3g\n", e.method.c_str(), e.sigma_nf->sigma,
                  bound(*e.sigma_nf), e.sigma_nf_at_sigma_d);
  }
}

}  // namespace

void add_study(CLI::App& app, int& exit_code) {
  CLI::App* study = app.add_subcommand("study", "User studies of foveation: run one (2AFC or random test), statistics of their trials");
  study->require_subcommand(1);
  struct Args {
    std::string file, conditions;
    double threshold = 4.0;
    bool json = false;
  };
  auto args = std::make_shared<Args>();
  CLI::App* stats = study->add_subcommand(
      "stats", "Votes per pair of conditions with the exact binomial test; mean score per condition; sigma_UF/sigma_NF");
  stats->add_option("file", args->file, "Trials CSV (method_a,method_b,chosen and/or condition,score)")->required();
  stats->add_option("--threshold", args->threshold,
                    "sigma_UF/sigma_NF: the mean score that still counts as no visible difference")
      ->check(CLI::Range(1.0, 5.0))
      ->capture_default_str();
  stats->add_option("--conditions", args->conditions,
                    "conditions.csv of study run: each condition's predicted JOD, printed beside its votes and scores");
  stats->add_flag("--json", args->json, "Print the report as JSON");
  stats->callback([args, &exit_code] {
    // CLI::Range lets NaN through (every comparison with it is false).
    if (!(args->threshold >= 1.0 && args->threshold <= 5.0)) {
      exit_code = cli::report(bad_input("--threshold: " + std::to_string(args->threshold) + " is not a mean score in [1, 5]"));
      return;
    }
    auto trials = read_study_trials(args->file);
    if (!trials) {
      exit_code = cli::report(trials.error());
      return;
    }
    Predictions jod;
    if (!args->conditions.empty()) {
      auto j = read_predicted_jod(args->conditions);
      if (!j) {
        exit_code = cli::report(j.error());
        return;
      }
      jod = std::move(*j);
    }
    const StudyStats st = compute_study_stats(*trials, args->threshold);
    if (args->json) cli::print_json(stats_json(args->file, st, jod));
    else print_text(args->file, st, jod);
  });
  add_study_run(*study, exit_code);
}

}  // namespace foveal::cmd
