#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include <cstdio>
#include <cstdlib>
#include <filesystem>

#include "commands.hpp"
#include "ctl/ctl_summary.hpp"
#include "foveal/core/json_text.hpp"
#include "foveal/runtime/cli.hpp"
#include "foveal/runtime/control_server.hpp"

namespace foveal::cmd {

namespace {

// "sigma_d=2.2" -> {"sigma_d": 2.2}; "f_x=auto" -> {"f_x": "auto"}.
Status parse_assignment(const std::string& text, nlohmann::json& into) {
  const auto eq = text.find('=');
  if (eq == std::string::npos || eq == 0) return bad_input("'" + text + "': expected KEY=VALUE");
  const std::string key = text.substr(0, eq), value = text.substr(eq + 1);
  char* end = nullptr;
  const double d = std::strtod(value.c_str(), &end);
  into[key] = (!value.empty() && *end == '\0') ? nlohmann::json(d) : nlohmann::json(value);
  return {};
}

}  // namespace

void add_ctl(CLI::App& app, int& exit_code) {
  struct Args {
    std::string socket = default_control_socket_path();
    std::vector<std::string> words;
    bool json = false;
    int timeout_ms = 2000;
  };
  auto a = std::make_shared<Args>();
  CLI::App* ctl = app.add_subcommand("ctl", "Talk to a running foveald over its control socket");
  ctl->footer(
      "Requests:\n"
      "  status                   daemon state, rates, latency, memory\n"
      "  fovea                    the latest per-eye fovea\n"
      "  profiles                 list profiles and the active one\n"
      "  use NAME                 switch to another profile\n"
      "  set KEY=VALUE...         sigma_d, sigma_nd, f_x, f_y at run time\n"
      "  pause | resume           stop / restart rendering and gaze processing\n"
      "  mark TEXT...             a timestamped event marker in foveald's trace, and in the log of a\n"
      "                           `foveal record --control` in progress (without --socket)\n");
  ctl->add_option("request", a->words, "The request and its arguments")->required();
  ctl->add_option("--socket", a->socket, "Control socket")->capture_default_str();
  ctl->add_option("--timeout-ms", a->timeout_ms, "How long connecting, sending and the reply may take together (per socket)")
      ->check(CLI::Range(1, 3600 * 1000))
      ->capture_default_str();
  ctl->add_flag("--json", a->json, "Print the whole reply as JSON (the default: one line for status, fovea, use and set)");
  ctl->callback([a, ctl, &exit_code] {
    const std::string& cmd = a->words.front();
    nlohmann::json req = {{"cmd", cmd}};
    if (cmd == "use") {
      if (a->words.size() != 2) {
        exit_code = cli::report(bad_input("ctl use: expected one profile name"));
        return;
      }
      req["profile"] = a->words[1];
    } else if (cmd == "set") {
      if (a->words.size() < 2) {
        exit_code = cli::report(bad_input("ctl set: expected KEY=VALUE..."));
        return;
      }
      for (std::size_t i = 1; i < a->words.size(); ++i)
        if (Status s = parse_assignment(a->words[i], req); !s) {
          exit_code = cli::report(s.error());
          return;
        }
    } else if (cmd == "mark") {
      if (a->words.size() < 2) {
        exit_code = cli::report(bad_input("ctl mark: expected the marker's text"));
        return;
      }
      std::string text = a->words[1];
      for (std::size_t i = 2; i < a->words.size(); ++i) text += " " + a->words[i];
      req["text"] = text;
    } else if (a->words.size() != 1) {
      exit_code = cli::report(bad_input("ctl " + cmd + ": takes no arguments"));
      return;
    }
    // A mark also goes to a recording in progress at the default place (docs/daemon.md).
    const std::string record_socket = default_record_socket_path();
    std::error_code ec;
    if (cmd == "mark" && ctl->count("--socket") == 0 && std::filesystem::exists(record_socket, ec)) {
      nlohmann::json both;
      bool any_ok = false;
      for (const auto& [name, path] : {std::pair<const char*, std::string>{"foveald", a->socket}, {"record", record_socket}}) {
        auto reply = control_request(path, req, a->timeout_ms);
        both[name] = reply ? *reply : nlohmann::json{{"ok", false}, {"error", reply.error().message}};
        any_ok |= both[name].value("ok", false);
      }
      std::printf("%s\n", a->json ? json_text(both).c_str() : json_text(both, 2).c_str());
      if (!any_ok) exit_code = cli::kExitBadInput;
      return;
    }
    auto reply = control_request(a->socket, req, a->timeout_ms);
    if (!reply) {
      exit_code = cli::report(reply.error());
      return;
    }
    const bool ok = reply->value("ok", false);
    if (!ok) exit_code = cli::kExitBadInput;
    if (a->json || !ok) {
      std::printf("%s\n", a->json ? reply->dump().c_str() : reply->dump(2).c_str());
      return;
    }
    if (cmd == "status" || cmd == "pause" || cmd == "resume") std::printf("%s\n", status_line(*reply).c_str());
    else if (cmd == "fovea") std::printf("%s\n", fovea_line(*reply).c_str());
    else if (cmd == "use" || cmd == "set") std::printf("%s\n", change_line(*reply, cmd).c_str());
    else std::printf("%s\n", reply->dump(2).c_str());
  });
}

}  // namespace foveal::cmd
