// `foveal study stats`: votes per pair of conditions with the exact binomial test, and
// mean scores per condition, from a trials CSV (docs/study.md).
#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include <cstdio>

#include "commands.hpp"
#include "foveal/study/study_stats.hpp"
#include "foveal/tools/cli.hpp"

namespace foveal::cmd {

namespace {

nlohmann::json stats_json(const std::string& path, const StudyStats& st) {
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
  return {{"file", path}, {"pairs", pairs}, {"scores", scores}, {"validation_trials", st.validation_trials}};
}

void print_text(const std::string& path, const StudyStats& st) {
  std::printf("%s: %zu pairs of conditions, %zu scored conditions, %llu validation trials left out\n", path.c_str(),
              st.pairs.size(), st.scores.size(), static_cast<unsigned long long>(st.validation_trials));
  if (!st.pairs.empty()) {
    std::printf("  %-40s %7s %15s %8s %12s\n", "pair (first vs second)", "trials", "votes", "ratio", "p (2-sided)");
    for (const PairVotes& p : st.pairs) {
      const std::string name = p.first + " vs " + p.second;
      const std::string votes = std::to_string(p.votes_first) + " : " + std::to_string(p.votes_second);
      std::printf("  %-40s %7llu %15s %7.1f%% %12.4g\n", name.c_str(), static_cast<unsigned long long>(p.trials),
                  votes.c_str(), 100.0 * p.share_first, p.p_value);
    }
  }
  if (!st.scores.empty()) {
    std::printf("  %-40s %7s %8s %8s\n", "condition", "trials", "mean", "sd");
    for (const ConditionScore& c : st.scores)
      std::printf("  %-40s %7llu %8.3f %8.3f\n", c.condition.c_str(), static_cast<unsigned long long>(c.trials),
                  c.mean, c.sd);
  }
}

}  // namespace

void add_study(CLI::App& app, int& exit_code) {
  CLI::App* study = app.add_subcommand("study", "User studies of foveation: statistics of their trials");
  study->require_subcommand(1);
  struct Args {
    std::string file;
    bool json = false;
  };
  auto args = std::make_shared<Args>();
  CLI::App* stats = study->add_subcommand(
      "stats", "Votes per pair of conditions with the exact binomial test; mean score per condition");
  stats->add_option("file", args->file, "Trials CSV (method_a,method_b,chosen and/or condition,score)")->required();
  stats->add_flag("--json", args->json, "Print the report as JSON");
  stats->callback([args, &exit_code] {
    auto trials = read_study_trials(args->file);
    if (!trials) {
      exit_code = cli::report(trials.error());
      return;
    }
    const StudyStats st = compute_study_stats(*trials);
    if (args->json) cli::print_json(stats_json(args->file, st));
    else print_text(args->file, st);
  });
}

}  // namespace foveal::cmd
