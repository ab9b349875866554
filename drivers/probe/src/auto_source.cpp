#include "auto_source.hpp"

namespace foveal::probe {

Status AutoSource::open() {
  close();
  auto rows = list_devices(false);
  if (!rows) return rows.error();
  std::string problems;
  for (const DeviceRow& row : *rows) {
    auto spec = parse_source_spec(row.spec);
    if (!spec) continue;
    auto made = make_source(*spec, options_);
    if (!made) {
      problems += "; " + row.spec + ": " + made.error().message;
      continue;
    }
    if (Status s = made->source->open(); !s) {
      problems += "; " + row.spec + ": " + s.error().message;
      continue;
    }
    current_.emplace(std::move(*made));
    return {};
  }
  return io_error("auto: no eye tracker could be opened (" + std::to_string(rows->size()) + " found" + problems + ")");
}

void AutoSource::close() {
  if (current_) current_->source->close();
  // Keep the last tracker's counters readable until the next open() chooses again.
}

Status AutoSource::start() {
  if (!current_) return io_error("auto: start() before a successful open()");
  return current_->source->start();
}

void AutoSource::stop() {
  if (current_) current_->source->stop();
}

ReadResult AutoSource::next(std::chrono::nanoseconds timeout) {
  if (!current_) {
    ReadResult r;
    r.status = ReadStatus::disconnected;
    return r;
  }
  return current_->source->next(timeout);
}

SourceInfo AutoSource::info() const {
  if (current_) return current_->source->info();
  SourceInfo i;
  i.driver = "auto";
  i.name = "no tracker yet";
  return i;
}

nlohmann::json AutoSource::counters() const {
  if (!current_) return nlohmann::json::object();
  nlohmann::json j = current_->counters();
  j["spec"] = current_->spec.text();
  return j;
}

}  // namespace foveal::probe
