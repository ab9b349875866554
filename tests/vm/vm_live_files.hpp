#pragma once
// foveald's outputs as the live checks read them (vm_live.cpp): trace.csv, frames.csv,
// summary.json and control replies.
#include <cstdint>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "foveal/core/clock.hpp"

namespace foveal::vmtest {

struct TraceRow {
  TimeNs rel = 0;  ///< from the first sample
  std::string state[2];
  double x[2] = {0, 0}, y[2] = {0, 0};
};
std::vector<TraceRow> read_trace(const std::string& path);

struct FrameRow {
  TimeNs t_ns = 0;
  double fx[2] = {0, 0}, fy[2] = {0, 0};  ///< fovea per eye, in viewport fractions
};
std::vector<FrameRow> read_frames(const std::string& path);

/// The file's JSON, or a discarded value.
nlohmann::json read_json(const std::string& path);
/// A value at a JSON pointer, or null (the summary's shape is checked, not trusted).
nlohmann::json at(const nlohmann::json& j, const std::string& pointer);
std::string str_at(const nlohmann::json& j, const std::string& pointer);    ///< "" unless a string
std::uint64_t u64_at(const nlohmann::json& j, const std::string& pointer);  ///< 0 unless a count

}  // namespace foveal::vmtest
