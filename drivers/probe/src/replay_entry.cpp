// replay:PATH and synthetic[:SEED]: the sources that need no device.
#include <charconv>

#include "driver_entry.hpp"
#include "foveal/drivers/synthetic_source.hpp"

namespace foveal::probe {

DriverEntry replay_entry() {
  DriverEntry e{"replay", "replay:PATH", "a native gaze log, paced like the recording (--speed)",
                DriverEntry::Arg::required, false, {}, {}};
  e.make = [](const std::string& path, const SourceOptions& o) -> Result<OpenedSource> {
    ReplayOptions r = o.replay;
    r.path = path;
    if (Status s = r.validate(); !s) return s.error();
    auto src = std::make_unique<ReplaySource>(r);
    const ReplaySource* raw = src.get();
    return OpenedSource{std::move(src), {"replay", path}, false,
                        [raw] { return nlohmann::json{{"loops", raw->loops_completed()}}; }};
  };
  return e;
}

DriverEntry synthetic_entry() {
  DriverEntry e{"synthetic", "synthetic[:SEED]", "the seeded synthetic scanpath generator, in real time",
                DriverEntry::Arg::optional, false, {}, {}};
  e.make = [](const std::string& arg, const SourceOptions& o) -> Result<OpenedSource> {
    SyntheticOptions so;
    if (!arg.empty()) {
      const auto [end, ec] = std::from_chars(arg.data(), arg.data() + arg.size(), so.seed);
      if (ec != std::errc() || end != arg.data() + arg.size())
        return bad_input("synthetic:" + arg + ": the seed must be a whole number");
    }
    so.speed = o.synthetic_speed;
    so.duration_s = o.synthetic_duration_s;
    if (Status s = so.validate(); !s) return s.error();
    return OpenedSource{std::make_unique<SyntheticSource>(so), {"synthetic", arg}, false,
                        [] { return nlohmann::json::object(); }};
  };
  return e;
}

}  // namespace foveal::probe
