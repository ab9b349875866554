#include <string>

#include "foveal/drivers/synthetic_source.hpp"

namespace foveal {

Status SyntheticSource::start() {
  if (Status s = opts_.validate(); !s) return s;
  gen_ = SyntheticGenerator(opts_);
  have_pending_ = gen_.next(pending_, pending_truth_);
  pacer_.start(0);
  started_ = true;
  return {};
}

ReadResult SyntheticSource::next(std::chrono::nanoseconds timeout) {
  ReadResult r;
  if (!started_) {
    r.status = ReadStatus::error;
    r.error = {ErrorKind::internal, "synthetic: next() before start()"};
    return r;
  }
  if (!have_pending_) {
    r.status = ReadStatus::end;
    return r;
  }
  const TimeNs due = pacer_.due(pending_.t_ns);
  if (!pacer_.wait(due, timeout)) {
    r.status = ReadStatus::timeout;
    return r;
  }
  r.status = ReadStatus::sample;
  r.sample = pending_;
  r.sample.t_ns = due;
  truth_ = pending_truth_;
  truth_.t_ns = due;
  have_pending_ = gen_.next(pending_, pending_truth_);
  return r;
}

SourceInfo SyntheticSource::info() const {
  SourceInfo i;
  i.driver = "synthetic";
  i.name = "synthetic scanpath (seed " + std::to_string(opts_.seed) + ")";
  i.nominal_rate_hz = opts_.rate_hz;
  return i;
}

}  // namespace foveal
