// foveal record: reads a tracker and writes what it delivers as a native gaze log,
// riding out unplugs (retry with backoff) until the duration is over or Ctrl-C.
#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <atomic>
#include <csignal>
#include <cstdio>
#include <optional>
#include <vector>

#include "commands.hpp"
#include "foveal/core/gaze_log.hpp"
#include "foveal/drivers/probe.hpp"
#include "foveal/tools/cli.hpp"

namespace foveal::cmd {

namespace {

std::atomic<bool> g_interrupted{false};
void on_signal(int) { g_interrupted.store(true); }

/// The median sample interval's rate, for devices that do not say theirs.
double estimate_rate(const std::vector<GazeSample>& s) {
  if (s.size() < 3) return 0;
  std::vector<TimeNs> d;
  for (std::size_t i = 1; i < s.size(); ++i) d.push_back(s[i].t_ns - s[i - 1].t_ns);
  std::nth_element(d.begin(), d.begin() + static_cast<std::ptrdiff_t>(d.size() / 2), d.end());
  const TimeNs median = d[d.size() / 2];
  return median > 0 ? 1e9 / static_cast<double>(median) : 0;
}

}  // namespace

void add_record(CLI::App& app, int& exit_code) {
  struct Args {
    std::string source, device, out;
    double duration_s = 10;
    bool json = false;
  };
  auto args = std::make_shared<Args>();
  CLI::App* sub = app.add_subcommand("record", "Record a tracker's gaze into a native gaze log");
  sub->add_option("--source,-s", args->source, "Source spec (default: auto, the first tracker found):\n" + probe::source_spec_help());
  sub->add_option("--device,-d", args->device, "Short form: an id from `foveal devices`, a hidraw path, psvr2, or auto")
      ->excludes("--source");
  sub->add_option("--out,-o", args->out, "Output native gaze log (written atomically)")->required();
  sub->add_option("--duration", args->duration_s, "Seconds to record (Ctrl-C stops early)")->capture_default_str();
  sub->add_flag("--json", args->json, "Print the summary as JSON");
  sub->callback([args, &exit_code] {
    if (!(args->duration_s > 0)) {
      exit_code = cli::report(bad_input("record: --duration must be > 0"));
      return;
    }
    auto spec = probe::parse_source_spec(args->source.empty() ? probe::device_spec(args->device) : args->source);
    if (!spec) {
      exit_code = cli::report(spec.error());
      return;
    }
    probe::SourceOptions so;
    so.synthetic_duration_s = args->duration_s;
    auto device = probe::make_source(*spec, so);
    if (!device) {
      exit_code = cli::report(device.error());
      return;
    }
    GazeSource& src = *device->source;
    if (Status s = src.open(); !s) {
      exit_code = cli::report(s.error());
      return;
    }
    if (Status s = src.start(); !s) {
      exit_code = cli::report(s.error());
      return;
    }
    std::signal(SIGINT, on_signal);
    std::signal(SIGTERM, on_signal);
    const SourceInfo info = src.info();
    const TimeNs t_end = monotonic_now_ns() + static_cast<TimeNs>(args->duration_s * 1e9);
    // The log header needs the rate: buffer the first second in case the device only
    // tells it in a status input report, or not at all.
    std::vector<GazeSample> head;
    std::optional<GazeLogWriter> writer;
    TimeNs last_t = 0;
    std::uint64_t reconnects = 0;
    auto open_writer = [&]() -> Status {
      GazeLogHeader h;
      h.rate_hz = src.info().nominal_rate_hz > 0 ? src.info().nominal_rate_hz : estimate_rate(head);
      if (!(h.rate_hz > 0)) h.rate_hz = 120;  // nothing to go on: the common tracker rate
      h.meta["driver"] = info.driver;
      h.meta["source"] = info.path;
      h.meta["device"] = info.name;
      auto w = GazeLogWriter::create(args->out, h);
      if (!w) return w.error();
      writer.emplace(std::move(w.value()));
      for (const GazeSample& s : head)
        if (Status st = writer->write(s); !st) return st;
      head.clear();
      return {};
    };
    const TimeNs head_until = monotonic_now_ns() + kNsPerSec;
    while (!g_interrupted.load() && monotonic_now_ns() < t_end) {
      const auto r = src.next(std::chrono::milliseconds(50));
      if (r.status == ReadStatus::sample) {
        if (r.sample.t_ns <= last_t) continue;
        last_t = r.sample.t_ns;
        if (writer) {
          if (Status st = writer->write(r.sample); !st) {
            exit_code = cli::report(st.error());
            return;
          }
        } else {
          head.push_back(r.sample);
        }
      } else if (r.status == ReadStatus::disconnected) {
        if (reopen_with_backoff(src, [&] { return g_interrupted.load() || monotonic_now_ns() >= t_end; })) ++reconnects;
      } else if (r.status == ReadStatus::end) {
        break;
      } else if (r.status == ReadStatus::error) {
        exit_code = cli::report(r.error);
        return;
      }
      if (!writer && monotonic_now_ns() >= head_until)
        if (Status st = open_writer(); !st) {
          exit_code = cli::report(st.error());
          return;
        }
    }
    src.close();
    if (!writer)
      if (Status st = open_writer(); !st) {
        exit_code = cli::report(st.error());
        return;
      }
    if (Status st = writer->commit(); !st) {
      exit_code = cli::report(st.error());
      return;
    }
    nlohmann::json j = {{"output", args->out},  {"driver", info.driver},     {"device", info.path},
                        {"samples", writer->samples_written()}, {"reconnects", reconnects},
                        {"driver_counters", device->counters()}};
    if (args->json) cli::print_json(j);
    else
      std::printf("recorded %llu samples from %s %s -> %s (%llu reconnects)\n",
                  static_cast<unsigned long long>(writer->samples_written()), info.driver.c_str(), info.path.c_str(),
                  args->out.c_str(), static_cast<unsigned long long>(reconnects));
  });
}

}  // namespace foveal::cmd
