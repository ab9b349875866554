// foveal service: show and set foveald's options file, which the user service
// (`foveald --service`, lib/systemd/user/foveald.service) reads at start (docs/daemon.md).
#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include <cstdio>
#include <functional>

#include "commands.hpp"
#include "foveal/core/atomic_file.hpp"
#include "foveal/runtime/cli.hpp"
#include "foveal/runtime/daemon_config.hpp"
#include "foveal/runtime/profile.hpp"

namespace foveal::cmd {

namespace {

struct ServiceArgs {
  std::string key, value;
  bool json = false;
};

std::string config_path() { return daemon_config_path(ProfileStore::user().root()); }

void show(const DaemonConfig& c, const std::string& path, bool json) {
  if (json) {
    nlohmann::json entries = nlohmann::json::object();
    for (const auto& [k, v] : c.entries()) entries[k] = v;
    cli::print_json({{"path", path}, {"entries", entries}});
    return;
  }
  std::printf("%s%s\n", path.c_str(), c.entries().empty() ? ": no options set (the service's defaults: source auto, head auto, no rendering)" : "");
  for (const auto& [k, v] : c.entries()) std::printf("%s = %s\n", k.c_str(), v.c_str());
}

/// Loads the file, applies `edit`, writes it back atomically under the profile store's lock.
int edit_file(const std::function<Status(DaemonConfig&)>& edit, bool json) {
  const ProfileStore store = ProfileStore::user();
  auto lock = store.lock();
  if (!lock) return cli::report(lock.error());
  const std::string path = config_path();
  auto c = DaemonConfig::load(path);
  if (!c) return cli::report(c.error());
  if (Status s = edit(*c); !s) return cli::report(s.error());
  if (Status s = write_file_atomically(path, c->text()); !s) return cli::report(s.error());
  show(*c, path, json);
  if (!json)
    std::printf("foveald reads it when it starts (check with `foveald --service --print-config`): "
                "systemctl --user restart foveald\n");
  return 0;
}

}  // namespace

void add_service(CLI::App& app, int& exit_code) {
  CLI::App* svc = app.add_subcommand("service", "Show and set foveald's options file, read by the user service at start");
  svc->require_subcommand(1);
  auto a = std::make_shared<ServiceArgs>();

  CLI::App* show_cmd = svc->add_subcommand("show", "The file's path and its options");
  show_cmd->add_flag("--json", a->json, "As JSON: {path, entries}");
  show_cmd->callback([a, &exit_code] {
    const std::string path = config_path();
    auto c = DaemonConfig::load(path);
    if (!c) {
      exit_code = cli::report(c.error());
      return;
    }
    show(*c, path, a->json);
    exit_code = 0;
  });

  CLI::App* set = svc->add_subcommand("set", "Set one option (a key of `foveal service keys`)");
  set->add_option("key", a->key, "The option")->required();
  set->add_option("value", a->value, "Its value, as on foveald's command line")->required();
  set->add_flag("--json", a->json, "Print the file's options as JSON");
  set->callback([a, &exit_code] { exit_code = edit_file([a](DaemonConfig& c) { return c.set(a->key, a->value); }, a->json); });

  CLI::App* unset = svc->add_subcommand("unset", "Remove one option (foveald's default applies again)");
  unset->add_option("key", a->key, "The option")->required();
  unset->add_flag("--json", a->json, "Print the file's options as JSON");
  unset->callback([a, &exit_code] {
    exit_code = edit_file(
        [a](DaemonConfig& c) -> Status {
          if (!c.unset(a->key)) return bad_input("'" + a->key + "' is not set");
          return {};
        },
        a->json);
  });

  CLI::App* keys = svc->add_subcommand("keys", "The keys the file may hold");
  keys->add_flag("--json", a->json, "As JSON");
  keys->callback([a, &exit_code] {
    nlohmann::json j = nlohmann::json::array();
    for (const auto& k : daemon_config_keys()) {
      if (a->json) j.push_back({{"key", k.name}, {"help", k.help}});
      else std::printf("%-10s %s\n", k.name, k.help);
    }
    if (a->json) cli::print_json(j);
    exit_code = 0;
  });
}

}  // namespace foveal::cmd
