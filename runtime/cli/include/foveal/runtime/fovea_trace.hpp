#pragma once
// The per-sample fovea trace (foveald's trace.csv, foveal replay --trace): time from
// the first sample, then per eye state, viewport pixel and confidence. Written through
// an AtomicFile: nothing appears until commit(). Event markers are rows of their own,
// `#mark,T_NS,TEXT` (docs/daemon.md), which CSV readers that skip '#' lines pass over.
#include <cstdio>
#include <optional>
#include <span>
#include <string>

#include "foveal/core/atomic_file.hpp"
#include "foveal/runtime/fovea.hpp"
#include "foveal/runtime/trace_markers.hpp"

namespace foveal::cli {

class FoveaTrace {
 public:
  static Result<FoveaTrace> create(const std::string& path) {
    auto f = AtomicFile::create(path);
    if (!f) return f.error();
    FoveaTrace w(std::move(f.value()));
    w.file_->write("t_ns,left_state,left_x_px,left_y_px,left_confidence,right_state,right_x_px,right_y_px,right_confidence\n");
    return w;
  }
  /// A trace that keeps only its origin and writes no file (foveald --no-trace: a service
  /// running for days would otherwise hold ~45 MB an hour until it exits).
  static FoveaTrace off() { return FoveaTrace(std::nullopt); }
  bool on() const { return file_.has_value(); }
  /// Times are written relative to the first sample. `markers_before` (stamped no later
  /// than f) go in first; those stamped before the first sample get negative times.
  void write(const FoveaFrame& f, std::span<const TraceMarker> markers_before = {}) {
    if (!have_t0_) {
      t0_ = f.t_ns;
      have_t0_ = true;
    }
    write_markers(markers_before);
    if (!file_) return;
    const FoveaPoint &l = f.eye(Eye::left), &r = f.eye(Eye::right);
    char row[256];
    const int n = std::snprintf(row, sizeof row, "%lld,%s,%.3f,%.3f,%.2f,%s,%.3f,%.3f,%.2f\n",
                                static_cast<long long>(f.t_ns - t0_), fovea_state_name(l.state), l.px.x, l.px.y,
                                l.confidence, fovea_state_name(r.state), r.px.x, r.px.y, r.confidence);
    file_->write(std::string_view(row, static_cast<std::size_t>(n)));
  }
  /// Markers after the last sample (at the end), or in a trace without samples (then
  /// the first marker is the origin).
  void write_markers(std::span<const TraceMarker> markers) {
    for (const TraceMarker& m : markers) {
      if (!have_t0_) {
        t0_ = m.t_ns;
        have_t0_ = true;
      }
      if (file_) file_->write(marker_row({m.t_ns - t0_, m.text}));
    }
  }
  Status commit() { return file_ ? file_->commit() : Status{}; }

  /// The CLOCK_MONOTONIC time the trace's times count from; none before the first row.
  std::optional<TimeNs> t0_ns() const { return have_t0_ ? std::optional<TimeNs>(t0_) : std::nullopt; }

 private:
  explicit FoveaTrace(std::optional<AtomicFile> f) : file_(std::move(f)) {}
  std::optional<AtomicFile> file_;
  TimeNs t0_ = 0;
  bool have_t0_ = false;
};

}  // namespace foveal::cli
