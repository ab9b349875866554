#pragma once
// Shared by the foveal and foveald command lines: exit codes, error printing, progress.
#include <cstdint>
#include <string>

#include <nlohmann/json_fwd.hpp>

#include "foveal/core/error.hpp"

namespace foveal::cli {

constexpr int kExitOk = 0;
constexpr int kExitFailure = 1;   ///< internal error
constexpr int kExitBadInput = 2;  ///< bad input, bad arguments, unreadable or unwritable files

/// Prints "foveal: <message>" to stderr and returns the exit code for the error.
int report(const Error& e, const char* program = "foveal");

/// Prints "foveal: warning: <message>" to stderr (something ignored, the run goes on).
void warn(const std::string& message, const char* program = "foveal");

/// Prints `j` indented to stdout.
void print_json(const nlohmann::json& j);

/// A one-line terminal progress bar on stderr; silent when stderr is not a terminal
/// or when disabled (--json, -q).
class Progress {
 public:
  Progress(std::string label, std::uint64_t total, bool enabled = true);
  ~Progress();
  void update(std::uint64_t done);
  void finish();

 private:
  std::string label_;
  std::uint64_t total_;
  bool enabled_;
  int last_permille_ = -1;
  bool finished_ = false;
};

}  // namespace foveal::cli
