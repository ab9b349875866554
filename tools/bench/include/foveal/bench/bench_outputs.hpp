#pragma once
// What `foveal bench` writes from a sweep's rows, shared by a single run and by
// `foveal bench merge` so that both write the same files from the same rows: the tables
// (bench.csv, fgrid.csv, ...), bench.json and the charts; and a shard's own files.
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "foveal/bench/bench_shard_file.hpp"
#include "foveal/bench/bench_sweep.hpp"
#include "foveal/core/error.hpp"

namespace foveal::bench {

/// A figure as the CSV tables hold it: 6 significant digits; inf, -inf, nan as words.
std::string csv_number(double v);
/// A figure as bench.json holds it: the number, or csv_number's word when it is not
/// finite (JSON has no infinity: "inf" is the PSNR of identical images).
nlohmann::json json_number(double v);

/// What a sweep writes besides its tables, by kind (the table in bench_outputs.cpp):
/// "bench" (bench.json with the list "rows", the automatic-f results and, with --flicker,
/// the list "flicker"; bench_charts.py),
/// "gaze" (`--gaze`: gaze.json with the list "rows", gaze_charts.py).
/// `summary`: the run's facts besides the rows (renderer, size, peak RSS, settings).
/// Writes every table, then the JSON (summary + rows), then the charts unless `charts`
/// is false; prints the summary as JSON or a line. Returns the exit code.
int write_outputs(const std::string& dir, const SweepRows& rows, nlohmann::json summary, const std::string& kind, bool charts,
                  bool json);

/// Whether the chart scripts can run (/usr/bin/python3 imports matplotlib): bad_input
/// saying what to install (or to pass --no-png) when not.
Status check_charts_can_run();

/// A shard's directory: its tables (its own rows only) and shard.json, which holds the
/// tagged rows, the summary, the kind and `sweep` (the options that define the grid).
int write_shard(const std::string& dir, const SweepRows& rows, const nlohmann::json& summary, const std::string& sweep,
                const std::string& kind, bool json);

}  // namespace foveal::bench
