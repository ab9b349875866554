#pragma once
// A command's output files written as one set: either every file appears in the output
// directory or none does (docs/bad-input.md). Each file goes into a private staging
// directory made inside the output directory (the same file system, so a rename moves
// it); helper programs (the chart scripts) write their files there too. commit() checks
// every target, then renames them all into place. An uncommitted set is removed with
// everything in it; one left by a killed process (no flock on it any more) goes with
// the next set made in the same directory.
#include <string>
#include <string_view>
#include <vector>

#include "foveal/core/error.hpp"

namespace foveal::cli {

class StagedOutputs {
 public:
  /// Creates `dir` (and parents) when missing, and the staging directory in it.
  static Result<StagedOutputs> create(const std::string& dir);
  StagedOutputs(StagedOutputs&&) noexcept;
  StagedOutputs& operator=(StagedOutputs&&) = delete;
  ~StagedOutputs();

  /// The staging directory, for a helper program to write into.
  const std::string& staging() const { return staging_; }
  /// Writes `name` (a plain file name: no '/', not "." or "..") into the staging
  /// directory, flushed to disk; errors name the final path (ENOSPC says the disk is full).
  Status write(const std::string& name, std::string_view data);
  /// Moves every regular file of the staging directory into `dir`, after checking that
  /// each target is absent or a regular file (never a link, FIFO or directory); an
  /// existing target keeps its permission bits. Returns the names moved.
  Result<std::vector<std::string>> commit();

 private:
  StagedOutputs() = default;
  void discard();
  std::string dir_, staging_;
  int lock_fd_ = -1;             ///< flock on the staging directory: marks it live
  bool created_dir_ = false;     ///< `dir` was made here: removed again when the set fails and it is empty
};

/// strerror, with what ENOSPC and EDQUOT mean for the user.
std::string describe_write_error(int err);

}  // namespace foveal::cli
