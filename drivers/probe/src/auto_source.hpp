#pragma once
// `auto`: whichever live tracker is present, chosen again at every open() so that a
// replug (or a different tracker plugged in) is picked up.
#include <optional>

#include "driver_entry.hpp"

namespace foveal::probe {

class AutoSource final : public GazeSource {
 public:
  explicit AutoSource(SourceOptions options) : options_(std::move(options)) {}
  Status open() override;
  void close() override;
  Status start() override;
  void stop() override;
  ReadResult next(std::chrono::nanoseconds timeout) override;
  SourceInfo info() const override;
  /// The chosen tracker's counters (empty object before the first open).
  nlohmann::json counters() const;

 private:
  SourceOptions options_;
  std::optional<OpenedSource> current_;
};

}  // namespace foveal::probe
