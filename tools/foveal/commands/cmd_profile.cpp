#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include <cmath>
#include <cstdio>
#include <cstdlib>

#include "commands.hpp"
#include "foveal/core/atomic_file.hpp"
#include "foveal/core/display_model.hpp"
#include "foveal/core/json_text.hpp"
#include "foveal/core/shown_text.hpp"
#include "foveal/runtime/cli.hpp"
#include "foveal/runtime/jod_levels.hpp"
#include "foveal/runtime/profile.hpp"

namespace foveal::cmd {

namespace {

struct ProfileArgs {
  std::string name, key, value, file, from;
  std::string dominant;
  std::optional<double> sigma_d, sigma_nd;
  std::optional<std::string> fx, fy;
  bool json = false, force = false;
};

/// The levels a profile's `quality` chooses, as `profile show` prints them.
nlohmann::json chosen_levels(const Profile& p) {
  JodLevels l;
  auto applied = apply_quality(p, display_model_path(p.display_model), &l);
  if (!applied) return {{"error", applied.error().message}};
  auto jnum = [](double v) { return std::isfinite(v) ? nlohmann::json(v) : nlohmann::json(nullptr); };
  return {{"quality", p.quality}, {"sigma_d", l.sigma_d}, {"sigma_nd", l.sigma_nd}, {"f_x", l.f}, {"f_y", l.f},
          {"predicted_jod_dominant", jnum(l.jod_d)}, {"predicted_jod_non_dominant", jnum(l.jod_nd)}, {"table", l.table}};
}

void print_profile(const Profile& p, bool active, bool json) {
  nlohmann::json j = p.to_json();
  j["name"] = p.name;
  j["active"] = active;
  if (!p.quality.empty()) j["levels"] = chosen_levels(p);
  if (json) {
    cli::print_json(j);
    return;
  }
  std::printf("%s%s\n%s\n", p.name.c_str(), active ? " (active)" : "", json_text(p.to_json(), 2).c_str());
  if (p.quality.empty()) return;
  const nlohmann::json& l = j["levels"];
  if (l.contains("error")) {
    std::printf("levels: %s cannot be applied: %s\n", p.quality.c_str(), l["error"].get<std::string>().c_str());
    return;
  }
  auto shown = [](const nlohmann::json& v) { return v.is_null() ? std::string("past the table") : shown_number(v.get<double>()); };
  std::printf("levels (%s, from %s): sigma_d %s, sigma_nd %s, f %s; predicted JOD %s dominant, %s non-dominant\n",
              p.quality.c_str(), l["table"].get<std::string>().c_str(), shown_number(l["sigma_d"].get<double>()).c_str(),
              shown_number(l["sigma_nd"].get<double>()).c_str(), shown_number(l["f_x"].get<double>()).c_str(),
              shown(l["predicted_jod_dominant"]).c_str(), shown(l["predicted_jod_non_dominant"]).c_str());
}

}  // namespace

void add_profile(CLI::App& app, int& exit_code) {
  CLI::App* prof = app.add_subcommand("profile", "Manage user profiles (dominant eye, sigma pair, f, IPD, filter)");
  prof->require_subcommand(1);
  auto a = std::make_shared<ProfileArgs>();
  auto fail = [&exit_code](const Error& e) { exit_code = cli::report(e); };

  CLI::App* create = prof->add_subcommand("create", "Create a profile (defaults: right eye dominant, sigma 2.0/3.0, f 0.3)");
  create->add_option("name", a->name, "Profile name (letters, digits, - and _)")->required();
  create->add_option("--from", a->from, "Copy this existing profile");
  create->add_option("--dominant", a->dominant, "Dominant eye")->check(CLI::IsMember({"left", "right"}));
  create->add_option("--sigma-d", a->sigma_d, "Dominant eye's sigma");
  create->add_option("--sigma-nd", a->sigma_nd, "Non-dominant eye's sigma (>= sigma-d)");
  create->add_option("--fx", a->fx, "f_x as a fraction of W, or auto");
  create->add_option("--fy", a->fy, "f_y as a fraction of H, or auto");
  create->add_flag("--force", a->force, "Overwrite an existing profile");
  create->add_flag("--json", a->json, "Print the profile as JSON");
  create->callback([a, fail] {
    const ProfileStore store = ProfileStore::user();
    if (!valid_profile_name(a->name)) return fail(bad_input("profile name '" + a->name + "': use letters, digits, '-' and '_'"));
    auto lock = store.lock();  // the exists check and the save as one step
    if (!lock) return fail(lock.error());
    if (store.exists(a->name) && !a->force) return fail(bad_input("profile '" + a->name + "' exists (use --force)"));
    Profile p;
    if (!a->from.empty()) {
      auto base = store.load(a->from);
      if (!base) return fail(base.error());
      p = *base;
    }
    p.name = a->name;
    // Apply every option, then validate once: the sigma pair is checked together.
    nlohmann::json j = p.to_json();
    if (!a->dominant.empty()) j["dominant_eye"] = a->dominant;
    if (a->sigma_d) j["sigma_d"] = *a->sigma_d;
    if (a->sigma_nd) j["sigma_nd"] = *a->sigma_nd;
    for (const auto& [key, text] : {std::pair{"f_x", a->fx}, std::pair{"f_y", a->fy}}) {
      if (!text) continue;
      char* end = nullptr;
      const double v = std::strtod(text->c_str(), &end);
      if (*text == "auto") j[key] = "auto";
      else if (!text->empty() && *end == '\0') j[key] = v;
      else return fail(bad_input(std::string("--") + (key[2] == 'x' ? "fx" : "fy") + ": '" + *text + "' is not a number or auto"));
    }
    auto built = Profile::from_json(j, a->name, "profile " + a->name);
    if (!built) return fail(built.error());
    auto active = store.active();  // before the save: a refusal leaves nothing written
    if (!active) return fail(active.error());
    if (Status s = store.save(*built); !s) return fail(s.error());
    print_profile(*built, *active == a->name, a->json);
  });

  CLI::App* list = prof->add_subcommand("list", "List profiles");
  list->add_flag("--json", a->json, "Print JSON");
  list->callback([a, fail] {
    const ProfileStore store = ProfileStore::user();
    auto names = store.list();
    if (!names) return fail(names.error());
    auto read_active = store.active();
    if (!read_active) return fail(read_active.error());
    const std::string active = *read_active;
    if (a->json) {
      cli::print_json({{"profiles", *names}, {"active", active}, {"directory", store.root() + "/profiles"}});
      return;
    }
    if (names->empty()) std::printf("no profiles in %s/profiles (foveal profile create NAME)\n", store.root().c_str());
    for (const auto& n : *names) std::printf("%s %s\n", n == active ? "*" : " ", n.c_str());
  });

  CLI::App* show = prof->add_subcommand("show", "Show a profile (default: the active one)");
  show->add_option("name", a->name, "Profile name");
  show->add_flag("--json", a->json, "Print JSON");
  show->callback([a, fail] {
    const ProfileStore store = ProfileStore::user();
    auto active = store.active();
    if (!active) return fail(active.error());
    const std::string name = a->name.empty() ? *active : a->name;
    if (a->name.empty() && !store.exists(name)) {
      // No profile made yet: foveald runs with the built-in defaults, which is what is shown.
      Profile builtin;
      builtin.name = name;
      if (a->json) {
        nlohmann::json j = builtin.to_json();
        j["name"] = name;
        j["active"] = true;
        j["builtin"] = true;
        cli::print_json(j);
        return;
      }
      std::printf("no profile made yet: foveald uses the built-in defaults (`foveal profile create NAME` makes one)\n");
      print_profile(builtin, true, false);
      return;
    }
    auto p = store.load(name);
    if (!p) return fail(p.error());
    print_profile(*p, *active == name, a->json);
  });

  CLI::App* set = prof->add_subcommand("set", "Set one key of a profile, e.g. 'set alice sigma_nd 3.2'");
  set->add_option("name", a->name, "Profile name")->required();
  set->add_option("key", a->key, "dominant_eye, sigma_d, sigma_nd, f_x, f_y, ipd_mm, display_model, filter, quality")->required();
  set->add_option("value", a->value, "New value (f_x/f_y accept auto; filter takes a JSON object; quality: jod:T or off)")->required();
  set->add_flag("--json", a->json, "Print the profile as JSON");
  set->callback([a, fail] {
    const ProfileStore store = ProfileStore::user();
    auto lock = store.lock();  // load, change, save: a concurrent set must not be lost
    if (!lock) return fail(lock.error());
    auto p = store.load(a->name);
    if (!p) return fail(p.error());
    if (Status s = p->set(a->key, a->value); !s) return fail(s.error());
    // A quality the display model has no table for is refused here, not at foveald's start.
    if (auto applied = apply_quality(*p, display_model_path(p->display_model)); !applied) return fail(applied.error());
    auto active = store.active();  // before the save: a refusal leaves nothing written
    if (!active) return fail(active.error());
    if (Status s = store.save(*p); !s) return fail(s.error());
    print_profile(*p, *active == a->name, a->json);
    if (!a->json)
      std::printf("saved; a running foveald takes it at `foveal ctl use %s` or a reload (SIGHUP; `systemctl --user reload foveald`)\n",
                  a->name.c_str());
  });

  CLI::App* use = prof->add_subcommand("use", "Make a profile the active one");
  use->add_option("name", a->name, "Profile name")->required();
  use->callback([a, fail] {
    const ProfileStore store = ProfileStore::user();
    auto lock = store.lock();
    if (!lock) return fail(lock.error());
    if (Status s = store.set_active(a->name); !s) return fail(s.error());
    std::printf("active profile: %s\n", a->name.c_str());
  });

  CLI::App* del = prof->add_subcommand("delete", "Delete a profile");
  del->add_option("name", a->name, "Profile name")->required();
  del->callback([a, fail] {
    const ProfileStore store = ProfileStore::user();
    auto lock = store.lock();
    if (!lock) return fail(lock.error());
    if (Status s = store.remove(a->name); !s) return fail(s.error());
    std::printf("deleted profile %s\n", a->name.c_str());
  });

  CLI::App* exp = prof->add_subcommand("export", "Write a profile to a file");
  exp->add_option("name", a->name, "Profile name")->required();
  exp->add_option("file", a->file, "Output file (written atomically)")->required();
  exp->callback([a, fail] {
    const ProfileStore store = ProfileStore::user();
    if (Status s = check_output_is_not_an_input(a->file, {store.path_of(a->name)}); !s) return fail(s.error());
    auto p = store.load(a->name);
    if (!p) return fail(p.error());
    if (Status s = write_file_atomically(a->file, json_text(p->to_json(), 2) + "\n"); !s) return fail(s.error());
    std::printf("exported %s -> %s\n", a->name.c_str(), a->file.c_str());
  });

  CLI::App* imp = prof->add_subcommand("import", "Add a profile from a file (validated first)");
  imp->add_option("file", a->file, "Profile file")->required();
  imp->add_option("--name", a->name, "Name to store it under (default: the file's name)");
  imp->add_flag("--force", a->force, "Overwrite an existing profile");
  imp->callback([a, fail] {
    const ProfileStore store = ProfileStore::user();
    std::string name = a->name;
    if (name.empty()) {
      name = a->file.substr(a->file.find_last_of('/') + 1);
      if (auto dot = name.rfind('.'); dot != std::string::npos) name.resize(dot);
    }
    auto lock = store.lock();
    if (!lock) return fail(lock.error());
    if (store.exists(name) && !a->force) return fail(bad_input("profile '" + name + "' exists (use --force)"));
    auto p = ProfileStore::load_file(a->file, name);
    if (!p) return fail(p.error());
    if (Status s = store.save(*p); !s) return fail(s.error());
    std::printf("imported %s as profile %s\n", a->file.c_str(), name.c_str());
  });
}

}  // namespace foveal::cmd
